"""SIGTERM and Ctrl-C: heard in every phase of a run within a fraction of a
second (the core's loops poll Python's handlers, pkg/ldem/Interrupt.hpp),
from the command's first instant (exit_while_starting, before numpy, the core
and matplotlib load), and a run stopped where its files say what they hold: at a record (the curve
has its row, checkpoint.npz is of that record) or, between records far from
the next one, at once (the curve keeps the rows to the last record; an older
checkpoint stays what it was)."""
from __future__ import annotations

import os
import signal
import sys
import threading
import time


class Terminated(KeyboardInterrupt):
    """SIGTERM, handled as Ctrl-C: the run stops, its summary says interrupted."""


def _terminate(signum, frame):
    raise Terminated()


def _how(signum) -> str:
    return "terminated (SIGTERM)" if signum == signal.SIGTERM else "interrupted"


def _exit_at_once(signum, frame):
    command = " ".join(["ldem"] + sys.argv[1:2] if sys.argv[1:2] and not sys.argv[1].startswith("-") else ["ldem"])
    os.write(2, f"{command}: {_how(signum)} while starting: nothing ran\n".encode())
    os._exit(128 + signum)


def exit_while_starting() -> None:
    """SIGINT and SIGTERM end `ldem` at once with one line while it starts
    (imports, options): nothing is written yet, and an exception raised in an
    import could come out of it wrapped (Python 3.11 wraps one raised while a
    class is made: "Error calling __set_name__", in matplotlib's 3-D axes). A
    signal ignored by the caller (nohup, a background job) stays ignored."""
    for s in (signal.SIGINT, signal.SIGTERM):  # SIGTERM last: a test sees it caught once both are
        if signal.getsignal(s) is not signal.SIG_IGN:
            signal.signal(s, _exit_at_once)


def raise_on_signals() -> None:
    """From the start of the work on: SIGINT raises KeyboardInterrupt and
    SIGTERM Terminated (in the main thread), which the command turns into its
    message of what is kept."""
    if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, _terminate)


class SignalsAtRecords:
    """SIGINT and SIGTERM during a run's loop (as the last observer of its
    records). A signal heard at a record, or within NEAR_SECONDS of the next
    one (from the pace of the steps since the last), is held to the end of
    that record (every other observer has seen it, curve.csv has its row),
    then checkpoint.npz of that record is written (with a saver) and the
    signal's own handler runs (KeyboardInterrupt, or Terminated): a restart
    continues from there bit for bit. With a saver, one up to WAIT_SECONDS
    from its record is held too, saying so in a line: a run whose records
    are seconds apart (a large specimen on a busy machine) keeps its
    checkpoint whenever it is stopped. One farther, or a second signal, runs
    its handler at once: the run stops between records, where no checkpoint
    can be taken. Only Python handlers are held (not the defaults, not off
    the main thread, where signals cannot be handled)."""

    SIGNALS = (signal.SIGINT, signal.SIGTERM)
    NEAR_SECONDS = 1.0
    WAIT_SECONDS = 20.0  # below a batch system's grace between SIGTERM and SIGKILL (Slurm's KillWait: 30 s)

    def __init__(self, saver=None, sim=None):
        self.saver, self.sim, self.pending, self.previous = saver, sim, None, {}
        self.last = None  # (monotonic time, step) of the last record seen

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            self.previous = {s: signal.getsignal(s) for s in self.SIGNALS if callable(signal.getsignal(s))}
            for s in self.previous:
                signal.signal(s, self._hold)
        return self

    def _hold(self, signum, frame):
        wait = self.seconds_to_record()
        if self.pending is None and (wait <= self.NEAR_SECONDS or self.saver is not None and wait <= self.WAIT_SECONDS):
            self.pending = signum
            if wait > self.NEAR_SECONDS:  # os.write: a print could be re-entered, the signal come amid one
                os.write(2, f"{_how(signum)}: stopping at the next record, in about {wait:.0f} s, to keep its "
                            "checkpoint; a second signal stops at once\n".encode())
        else:
            self._handle(signum)

    def seconds_to_record(self) -> float:
        """Wall time to the next record at the pace since the last: 0 at a
        record (or with no simulation to ask), inf before the pace is known."""
        if self.sim is None:
            return 0.0
        step, every = self.sim.steps, self.sim.record_every
        to_go = -step % every
        if to_go == 0:
            return 0.0
        if self.last is None or step <= self.last[1]:
            return float("inf")
        return to_go * (time.monotonic() - self.last[0]) / (step - self.last[1])

    def __call__(self, row: dict) -> None:
        self.last = (time.monotonic(), int(row["step"]))
        if self.pending is not None:
            if self.saver is not None:
                self.saver.write()
            self._handle(self.pending)

    def _handle(self, signum) -> None:
        handler = self.previous.get(signum, signal.default_int_handler)
        self.__exit__()
        handler(signum, None)

    def __exit__(self, *exc):
        for s, handler in self.previous.items():
            signal.signal(s, handler)
        self.previous = {}
