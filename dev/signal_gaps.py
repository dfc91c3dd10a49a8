#!/usr/bin/python3
"""The longest waits for a signal in `ldem cube`'s set-up: how late a SIGTERM
sent then would be heard.

ldem runs in this process with a handler of SIGUSR1 that notes the time and
the Python line it ran at; a second process sends SIGUSR1 every 10 ms. A
Python handler runs only where ldem would hear SIGTERM (between Python lines,
or where the core's loops poll, pkg/ldem/Interrupt.hpp), so the gaps between
its runs are the waits a SIGTERM would have had. The set-up ends at the first
row of curve.csv; then the sender sends SIGTERM and the command stops.

    PYTHONPATH=build/python dev/signal_gaps.py --size 0.96 --threads 1
    (any options of ldem cube; --out defaults to a temporary folder)
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

SENDER = """
import os, signal, sys, time
pid, curve = int(sys.argv[1]), sys.argv[2]
while True:
    try:
        with open(curve) as f:
            if len(f.read().splitlines()) > 1:
                print(time.monotonic(), flush=True)
                os.kill(pid, signal.SIGTERM)
                break
    except OSError:
        pass
    os.kill(pid, signal.SIGUSR1)
    time.sleep(0.01)
"""


def main(argv):
    out = None
    if "--out" not in argv:
        out = tempfile.mkdtemp(prefix="signal_gaps_")
        argv = [*argv, "--out", os.path.join(out, "cube")]
    folder = argv[argv.index("--out") + 1]
    heard = []  # (monotonic time, file:line of the Python code it ran at)
    signal.signal(signal.SIGUSR1, lambda s, frame: heard.append(
        (time.monotonic(), f"{os.path.basename(frame.f_code.co_filename)}:{frame.f_lineno}")))
    from ldem import cli

    t0 = time.monotonic()
    sender = subprocess.Popen([sys.executable, "-c", SENDER, str(os.getpid()), os.path.join(folder, "curve.csv")],
                              stdout=subprocess.PIPE, text=True)
    code = cli.main(["cube", *argv, "--no-plots", "--no-progress"])
    first_row = float(sender.communicate()[0] or "inf")
    signal.signal(signal.SIGUSR1, signal.SIG_IGN)
    times = [(t0, "start")] + [h for h in heard if h[0] <= first_row]
    gaps = sorted(((b[0] - a[0], a[1], b[1], a[0] - t0) for a, b in zip(times, times[1:])), reverse=True)
    print(f"exit {code}; set-up to the first row {first_row - t0:.2f} s, {len(times) - 1} signals heard")
    print("longest gaps: seconds, at (s from the start), from -> to")
    for gap, a, b, at in gaps[:8]:
        print(f"  {gap:6.3f}  at {at:6.2f}  {a} -> {b}")
    if out:
        subprocess.run(["rm", "-rf", out])


if __name__ == "__main__":
    main(sys.argv[1:])
