#!/usr/bin/python3
"""The longest waits for a signal in `ldem cube`'s set-up: how late a SIGTERM
sent then would be heard.

ldem runs in this process with a handler of SIGUSR1; a second process sends
SIGUSR1 every 10 ms, noting in a shared file the time of the first one the
handler has not yet seen. A Python handler runs only where ldem would hear
SIGTERM (between Python lines, or where the core's loops poll,
pkg/ldem/Interrupt.hpp), so the time from that note to the handler's run is
the wait a SIGTERM would have had (the sender's own delays on a busy machine
do not count: a signal not yet sent is not waited for). The set-up ends at
the first row of curve.csv; then the sender sends SIGTERM and the command
stops.

    PYTHONPATH=build/python dev/signal_gaps.py --size 0.96 --threads 1
    (any options of ldem cube; --out defaults to a temporary folder)
"""
import mmap
import os
import signal
import struct
import subprocess
import sys
import tempfile
import time

SENDER = """
import mmap, os, signal, struct, sys, time
pid, curve, note = int(sys.argv[1]), sys.argv[2], sys.argv[3]
with open(note, "r+b") as f:
    sent = mmap.mmap(f.fileno(), 8)
while True:
    try:
        with open(curve) as f:
            if len(f.read().splitlines()) > 1:
                print(time.monotonic(), flush=True)
                os.kill(pid, signal.SIGTERM)
                break
    except OSError:
        pass
    if struct.unpack("d", sent[:8])[0] == 0:
        sent[:8] = struct.pack("d", time.monotonic())
    os.kill(pid, signal.SIGUSR1)
    time.sleep(0.01)
"""


def main(argv):
    tmp = tempfile.mkdtemp(prefix="signal_gaps_")
    if "--out" not in argv:
        argv = [*argv, "--out", os.path.join(tmp, "cube")]
    folder = argv[argv.index("--out") + 1]
    note = os.path.join(tmp, "sent")
    with open(note, "wb") as f:
        f.write(bytes(8))
    with open(note, "r+b") as f:
        sent = mmap.mmap(f.fileno(), 8)
    heard = []  # (seconds waited, monotonic time heard, file:line of the Python code it ran at)

    def handler(signum, frame):
        now, first = time.monotonic(), struct.unpack("d", sent[:8])[0]
        sent[:8] = bytes(8)
        if first:
            heard.append((now - first, now, f"{os.path.basename(frame.f_code.co_filename)}:{frame.f_lineno}"))
    signal.signal(signal.SIGUSR1, handler)
    from ldem import cli

    t0 = time.monotonic()
    sender = subprocess.Popen([sys.executable, "-c", SENDER, str(os.getpid()), os.path.join(folder, "curve.csv"), note],
                              stdout=subprocess.PIPE, text=True)
    code = cli.main(["cube", *argv, "--no-plots", "--no-progress"])
    first_row = float(sender.communicate()[0] or "inf")
    signal.signal(signal.SIGUSR1, signal.SIG_IGN)
    waits = sorted((h for h in heard if h[1] <= first_row), reverse=True)
    print(f"exit {code}; set-up to the first row {first_row - t0:.2f} s, {len(waits)} signals heard")
    print("longest waits: seconds, heard at (s from the start), where")
    for wait, at, where in waits[:8]:
        print(f"  {wait:6.3f}  at {at - t0:6.2f}  {where}")
    subprocess.run(["rm", "-rf", tmp])


if __name__ == "__main__":
    main(sys.argv[1:])
