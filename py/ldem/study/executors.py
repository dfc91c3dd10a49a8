"""Running the cases of a study: one after the other, in worker processes, or
on a dask.distributed cluster; finished cases are never recomputed."""
from __future__ import annotations

import contextlib
import os
import signal
import socket
from typing import Callable, List, Optional, Sequence

from .. import io
from ..cube import label_words
from ..progress import CaseProgress
from ..runner import STOP_WORDS, stopped_short
from ..signals import Terminated
from .cases import case_dir, case_name, checkpoint_step, load_summary, run_case, unfinished_reason


def default_threads(jobs: int) -> int:
    return max(1, (os.cpu_count() or 1) // max(1, jobs))


@contextlib.contextmanager
def study_lock(out: str, log: Callable[[str], None] = print):
    """Holds out/.lock (host and pid) while a study runs there: a second study
    in the same folder stops with the holder's name. A lock left by a process
    of this host that no longer runs is taken over."""
    path = os.path.join(out, ".lock")
    me = f"{socket.gethostname()} {os.getpid()}\n"
    for _ in range(2):
        try:
            fd = os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
            break
        except FileExistsError:
            try:
                with open(path) as f:
                    host, pid = f.read().split()
            except (OSError, ValueError):
                host, pid = "?", "0"
            if host == socket.gethostname() and not _alive(int(pid)):
                log(f"{out}: a study that stopped without cleaning up (pid {pid}) left its lock: taking it over")
                os.remove(path)
                continue
            raise ValueError(f"study folder {out} is in use by process {pid} on {host} "
                             f"(if it is not, remove {path})") from None
    else:
        raise ValueError(f"cannot lock study folder {out}")
    with os.fdopen(fd, "w") as f:
        f.write(me)
    try:
        yield
    finally:
        os.remove(path)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return pid > 0


def run_cases(tests: Sequence, out: str, jobs: int = 1, scheduler: Optional[str] = None,
              progress: Optional[bool] = None, log: Callable[[str], None] = print) -> List[dict]:
    """Runs every test (any case of ldem.study.cases) not finished yet (in `jobs` processes, or on the dask
    cluster at `scheduler`) and returns the summaries of all, in order. The
    folder is locked meanwhile (study_lock)."""
    if jobs < 1:
        raise ValueError(f"--jobs must be at least 1 (got {jobs})")
    io.prepare_dir(out)
    with study_lock(out, log):
        return _run_cases(tests, out, jobs, scheduler, progress, log)


def _run_cases(tests, out, jobs, scheduler, progress, log) -> List[dict]:
    # Absolute: worker processes and dask workers may start in other folders.
    dirs = [case_dir(os.path.abspath(out), t) for t in tests]
    if len(set(dirs)) != len(dirs):
        raise ValueError("two cases of the study have the same parameters")
    reasons = [unfinished_reason(d, t) for t, d in zip(tests, dirs)]
    todo = [i for i, r in enumerate(reasons) if r is not None]
    if len(todo) < len(tests):
        log(f"{len(tests) - len(todo)} of {len(tests)} cases already finished in {out}/cases")
    for i in todo:
        step = checkpoint_step(dirs[i], tests[i])
        if step is not None:
            log(f"  {case_name(tests[i])}: {reasons[i]}: continuing from its checkpoint at step {step}")
        elif reasons[i] != "not run yet":
            log(f"  {case_name(tests[i])}: {reasons[i]}: running it again")
    bar = CaseProgress(len(tests), len(tests) - len(todo), progress)
    args = [(tests[i], dirs[i]) for i in todo]

    def finished(i, summary):
        bar.step()
        unit = label_words((summary.get("labels") or {}).get("stress", ""))[1] or "MPa"  # an L-panel's: MN
        peak, at = summary["peak_stress_MPa"], summary["strain_at_peak"]
        log(f"  {case_name(tests[i])}: peak {peak:.5g} {unit} at {at:.4e}, "
            + (f"U_num/U_min {summary['U_ratio']:.3f}" if summary.get("U_ratio") is not None  # None: no U_min
               else f"U_num {summary['U_num_J']:.4g} J" if summary.get("separated")
               else f"stopped at {STOP_WORDS.get(summary.get('stop_reason'), summary.get('stop_reason'))}"
               + " before separation" * stopped_short(tests[i], summary.get("stop_reason")))
            + (", ENERGY ERROR" if summary.get("energy_error") else "") + f", {summary['wall_s']:.1f} s")

    try:
        if scheduler:
            _run_on_dask(scheduler, todo, args, finished)
        elif jobs == 1 or len(todo) <= 1:
            for i, (t, d) in zip(todo, args):
                finished(i, run_case(t, d))
        else:
            _run_in_processes(jobs, todo, args, finished)
    finally:
        bar.close()
    return [load_summary(d) for d in dirs]


def _run_in_processes(jobs, todo, args, finished):
    import concurrent.futures as cf
    import multiprocessing

    # spawn, not fork: a forked OpenMP runtime can hang in the child. Each worker gets every case once, as it
    # starts, and the pool's queue carries only a case's place in that list: pickled cases (a 200 mm beam's is
    # 61 KB) filled the queue's pipe, and once the workers were terminated the pool's shutdown waited for its
    # writer forever (Python 3.11 leaves the pipe's read end open).
    with cf.ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("spawn"),
                                initializer=_worker_start, initargs=(list(args),)) as pool:
        futures = {pool.submit(_worker_case, k): todo[k] for k, _ in largest_first(range(len(args)), args)}
        try:
            for fut in cf.as_completed(futures):
                finished(futures[fut], fut.result())
        except BaseException as e:
            for fut in futures:
                fut.cancel()
            if isinstance(e, Terminated):  # the running cases stop too (Ctrl-C reaches them from the terminal)
                for process in list((pool._processes or {}).values()):  # the pool's workers: no public handle
                    if process.is_alive():
                        process.terminate()
            raise


def largest_first(todo, args):
    """(case index, (test, dir)) pairs, the largest cubes first (stable; a
    test with no size keeps its place after them): the longest cases start
    first and small ones fill the cores at the end, instead of a 0.96 m cube
    left to run alone on one core while the others idle (longest processing
    time first; the size-effect study lists its cases smallest first)."""
    def size(pair):
        s = getattr(pair[1][0], "size", 0.0)
        return s if isinstance(s, (int, float)) else 0.0
    return sorted(zip(todo, args), key=lambda pair: -size(pair))


_cases = []  # a worker process's: the (test, folder) of every case to run, from the pool's initializer
_in_case = False  # a worker process's: whether it runs a case now
_stopping = False  # a worker process's: whether a signal has stopped its case


def _worker_start(cases) -> None:
    """A worker keeps the cases and hears SIGTERM and SIGINT as `ldem` does
    (its case stops and leaves its files: ldem.signals) or, between cases,
    ends at once."""
    global _cases
    _cases = cases
    for s in (signal.SIGTERM, signal.SIGINT):
        signal.signal(s, _worker_signal)


def _worker_signal(signum, frame):
    """Only the first signal stops the case. A stopping worker hears more:
    the pool SIGTERMs every worker left once one has ended by os._exit
    (CPython's terminate_broken), the study SIGTERMs its workers when it is
    itself terminated, and a signal to the process group reaches them too. One
    of them, raised in the clean-up of the first, lost the case's summary.json
    (test_signals.py, 4 runs in 100). The stopping worker writes its files and
    ends within a fraction of a second: it needs no second signal."""
    global _stopping
    if not _in_case:
        os._exit(128 + signum)
    if _stopping:
        return
    _stopping = True
    raise Terminated() if signum == signal.SIGTERM else KeyboardInterrupt()


def _worker_case(k: int) -> dict:
    """run_case of case k in a worker; stopped by a signal, the worker ends
    (its case has written what it keeps) rather than take the next case."""
    global _in_case, _stopping
    test, case_dir = _cases[k]
    _in_case, _stopping = True, False  # each case hears its own first signal: no worker is left deaf to them
    try:
        return run_case(test, case_dir)
    except KeyboardInterrupt as e:
        os._exit(128 + (signal.SIGTERM if isinstance(e, Terminated) else signal.SIGINT))
    finally:
        _in_case = False


def _run_on_dask(address, todo, args, finished):
    from distributed import Client, as_completed

    with Client(address) as client:
        futures = [client.submit(run_case, t, d, pure=False) for t, d in args]
        index = {f.key: i for f, i in zip(futures, todo)}
        for fut in as_completed(futures):
            finished(index[fut.key], fut.result())
