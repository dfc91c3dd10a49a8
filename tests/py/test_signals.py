"""Issue 40, item 2: SIGTERM and Ctrl-C heard within seconds in every phase
(the set-up of a large lattice, its Lanczos analysis, a run between records
far apart, a study's worker processes), and a message that says only what
the files hold. Each test signals the real command and gives it 5 s."""
import json
import math
import os
import signal
import subprocess
import time
from types import SimpleNamespace

import pytest

from conftest import LDEM_SCRIPT, subprocess_env

DEADLINE = 5.0  # seconds from the signal to the exit


def _start(*args):
    """`ldem ...` in its own session (so that the test signals exactly it and
    sees its workers), with SIGINT at its default, as on a terminal."""
    return subprocess.Popen(["/usr/bin/python3", LDEM_SCRIPT, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=subprocess_env(), start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))


def _wait_for(predicate, proc, what, timeout=120):
    t0 = time.monotonic()
    while not predicate():
        assert proc.poll() is None, f"the process ended (code {proc.returncode}) before {what}: {proc.stderr.read()}"
        assert time.monotonic() - t0 < timeout, f"timeout waiting for {what}"
        time.sleep(0.01)


def _signal_and_time(proc, signum=signal.SIGTERM, deadline=DEADLINE):
    """Sends signum; (return code, stderr, seconds to the exit). Whatever
    is left of the session after the deadline is killed (and fails the test)."""
    t0 = time.monotonic()
    proc.send_signal(signum)
    try:
        _, err = proc.communicate(timeout=deadline)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        pytest.fail(f"no exit within {deadline} s of the signal")
    return proc.returncode, err, time.monotonic() - t0


def _caught(pid: int, signum: int) -> bool:
    """Whether process pid has a handler of its own for signum (its SigCgt mask, /proc/PID/status)."""
    with open(f"/proc/{pid}/status") as f:
        mask = next(line for line in f if line.startswith("SigCgt:")).split()[1]
    return bool(int(mask, 16) >> (signum - 1) & 1)


STARTING = 0.5  # seconds from the interpreter's start to ldem's handlers, at most (about 0.02 s here)


@pytest.mark.parametrize("command", ["cube", "run"])
@pytest.mark.parametrize("delay", [0.05, 0.3, 1.0, 2.0])
@pytest.mark.parametrize("signum,code,how", [(signal.SIGTERM, 143, "terminated (SIGTERM)"),
                                             (signal.SIGINT, 130, "interrupted")], ids=["SIGTERM", "SIGINT"])
def test_a_signal_at_any_time_from_the_start_gives_one_line(tmp_path, command, delay, signum, code, how):
    """From its first line on, `ldem` hears SIGINT and SIGTERM: while it
    imports numpy, the core, the studies and matplotlib (it was a
    KeyboardInterrupt traceback, a RuntimeError from matplotlib's 3-D axes,
    or a silent death by SIGTERM), in set-up, and in the run (records 10^8
    steps apart). Each signal gives one line and 128 + the signal. Only the
    interpreter's own start comes before any line of ldem (0.04-0.1 s here,
    seconds on a machine loaded many times over): a signal sent earlier waits
    for the interpreter (its own SIGINT handler, from which on it runs the
    site's imports, then the script), and then for ldem's handlers, which must
    be there within STARTING seconds (they were after the imports of numpy,
    the core and the studies: seconds)."""
    what = ["cube", "--size", "0.04"] if command == "cube" else \
        ["run", os.path.join(os.path.dirname(LDEM_SCRIPT), "..", "..", "examples", "cube_uniform.toml")]
    t0 = time.monotonic()
    proc = _start(*what, "--set" if command == "run" else "--record-every",
                  "record_every=100000000" if command == "run" else "100000000",
                  "--threads", "1", "--no-plots", "--no-progress", "--out", str(tmp_path / "out"))
    _wait_for(lambda: _caught(proc.pid, signal.SIGINT), proc, "the interpreter", timeout=60)
    started = time.monotonic()
    time.sleep(max(0.0, delay - (started - t0)))
    _wait_for(lambda: _caught(proc.pid, signal.SIGTERM), proc, "the handlers",
              timeout=STARTING - (time.monotonic() - started))
    rc, err, seconds = _signal_and_time(proc, signum)
    assert rc == code, err
    said = [line for line in err.splitlines() if ": warning: " not in line]  # the file's warnings come first
    assert len(said) == 1 and said[0].startswith(f"ldem {command}: {how}"), err


def test_a_signal_wrapped_by_an_import_is_still_a_signal(monkeypatch, capsys):
    """Python 3.11 wraps an exception raised while a class is made (a
    descriptor's __set_name__, as in matplotlib's 3-D axes, imported where
    pictures are drawn) in a RuntimeError: the command still says it was
    interrupted, in one line, with 130."""
    from ldem import cli, run_command

    class Descriptor:
        def __set_name__(self, owner, name):
            raise KeyboardInterrupt()

    def made_while_interrupted(args):
        type("Axes", (), {"x": Descriptor()})
    monkeypatch.setattr(run_command, "cmd_cube", made_while_interrupted)
    assert cli.main(["cube", "--out", "nowhere"]) == 130
    assert capsys.readouterr().err.startswith("ldem cube: interrupted: nothing ran")


@pytest.mark.direct
def test_the_wait_for_the_next_record_is_paced_from_the_last(monkeypatch):
    """SignalsAtRecords.seconds_to_record: the steps to the next record at
    the pace since the last. A record every 100 steps, the last at step 100
    at t = 10 s, now step 130 at t = 13 s: 70 steps to go at 0.1 s a step, 7 s.
    At a record 0; before any step since the last, the pace is unknown: inf."""
    from ldem import signals

    now = [10.0]
    monkeypatch.setattr(signals.time, "monotonic", lambda: now[0])
    sim = SimpleNamespace(steps=100, record_every=100)
    held = signals.SignalsAtRecords(sim=sim)
    assert held.seconds_to_record() == 0.0
    held({"step": 100})
    sim.steps, now[0] = 130, 13.0
    assert held.seconds_to_record() == pytest.approx(7.0, rel=1e-12)
    held.last = (10.0, 130)
    assert held.seconds_to_record() == math.inf  # no step since the last record seen


@pytest.mark.direct
def test_a_signal_seconds_from_its_record_waits_for_it_when_a_checkpoint_is_kept(monkeypatch, capfd):
    """Records 3 s apart (eccentric_notch_beam.toml on a busy machine kept no
    checkpoint when stopped between two): with a saver, a signal 7 s from the
    next record (70 steps at 0.1 s) is held to it, says so, and the
    checkpoint of that record is written; without one it stops at once, as
    one 24.75 s away (99 steps at 0.25 s, beyond WAIT_SECONDS) does anyway."""
    from ldem import signals

    now, written = [10.0], []
    monkeypatch.setattr(signals.time, "monotonic", lambda: now[0])

    def seconds_away(steps, at, saver):
        sim = SimpleNamespace(steps=100, record_every=100)
        held = signals.SignalsAtRecords(saver, sim)
        now[0] = 10.0
        held({"step": 100})
        sim.steps, now[0] = steps, at
        return held
    held = seconds_away(130, 13.0, SimpleNamespace(write=lambda: written.append("checkpoint")))
    held._hold(signal.SIGTERM, None)
    assert held.pending == signal.SIGTERM and written == []
    assert capfd.readouterr().err == ("terminated (SIGTERM): stopping at the next record, in about 7 s, to keep its "
                                      "checkpoint; a second signal stops at once\n")
    with pytest.raises(KeyboardInterrupt):  # (the default handler: no previous one was installed here)
        held({"step": 200})
    assert written == ["checkpoint"]
    with pytest.raises(KeyboardInterrupt):
        seconds_away(130, 13.0, None)._hold(signal.SIGINT, None)
    with pytest.raises(KeyboardInterrupt):
        seconds_away(101, 10.25, SimpleNamespace(write=lambda: written.append("too far")))._hold(signal.SIGINT, None)
    assert written == ["checkpoint"] and capfd.readouterr().err == ""


def _rows(path):
    return max(0, len(path.read_text().splitlines()) - 1) if path.exists() else 0


@pytest.mark.parametrize("checkpoints", [False, True], ids=["no-checkpoint", "checkpoint-of-step-0"])
@pytest.mark.parametrize("signum,code,how", [(signal.SIGTERM, 143, "terminated (SIGTERM)"),
                                             (signal.SIGINT, 130, "interrupted")], ids=["SIGTERM", "SIGINT"])
def test_a_run_between_far_records_stops_at_once_and_says_what_is_kept(tmp_path, signum, code, how, checkpoints):
    """A record every 10^8 steps (hours): the row of step 0 is written, then
    the loop runs. The signal stops it between records, where no checkpoint
    can be taken: the message names the rows kept and the checkpoint there
    is (that of step 0, with --checkpoint-every 1) or says there is none."""
    out = tmp_path / "far"
    proc = _start("cube", "--size", "0.04", "--record-every", "100000000", "--threads", "1", "--no-plots",
                  "--no-progress", "--out", str(out), *(["--checkpoint-every", "1"] if checkpoints else []))
    _wait_for(lambda: _rows(out / "curve.csv") == 1 and (not checkpoints or (out / "checkpoint.npz").exists()),
              proc, "the first row")
    time.sleep(1.0)  # well into the steps
    rc, err, seconds = _signal_and_time(proc, signum)
    assert rc == code, err
    kept = "checkpoint.npz is of step 0; continue with: ldem cube --restart " + str(out) if checkpoints else \
        "no checkpoint: it would run again from the start"
    assert err.strip().splitlines()[-1] == f"ldem cube: {how}: curve.csv keeps 1 row, to step 0; {kept}", err
    assert "Traceback" not in err and seconds < DEADLINE
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "interrupted" and s["stop_reason"] == "interrupted"
    assert _rows(out / "curve.csv") == 1 and (out / "checkpoint.npz").exists() == checkpoints


@pytest.mark.parametrize("delay", [0.0, 1.5], ids=["lattice-build", "lanczos"])
def test_the_set_up_of_a_large_lattice_stops_at_once(tmp_path, delay):
    """The 1.2 m cube (60^3 modules, 3 million bars): its lattice is built in
    about 0.1 s, then the Lanczos analysis takes about 27 s (measured on one
    thread). A signal as soon as the output folder exists (the set-up starts)
    or 1.5 s later (in the Lanczos iterations) ends the command within the
    deadline; nothing ran, and the message and summary.json say so."""
    out = tmp_path / "big"
    proc = _start("cube", "--size", "1.2", "--threads", "1", "--no-plots", "--no-progress", "--out", str(out))
    _wait_for(out.exists, proc, "the output folder")
    time.sleep(delay)
    rc, err, seconds = _signal_and_time(proc)
    assert rc == 143, err
    assert err.strip().splitlines()[-1] == "ldem cube: terminated (SIGTERM): nothing ran: curve.csv has no rows; " \
                                           "no checkpoint: it would run again from the start", err
    s = json.loads((out / "summary.json").read_text())
    assert (s["status"], s["error"]) == ("interrupted", "interrupted during set-up")
    assert not (out / "curve.csv").exists()


def _cpu_seconds(pid: int) -> float:
    """The CPU time process pid has used (utime + stime, /proc/PID/stat): a
    point of its work that a busy machine does not move, as it moves wall time."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()  # after the command's name, which may hold spaces
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


SET_UP_HEARD = 2.0  # seconds from a signal in set-up to the exit (a signal is polled for every 0.1 s)


def test_a_signal_amid_the_correlated_field_is_heard_at_once(tmp_path):
    """The correlated G_f field (--corr-length: 512 cosines a bar) of the
    0.72 m cube (36^3 modules, 650,000 bars) takes about 7 s of CPU, after a
    Lanczos analysis of about 1.4 s (one thread, measured here). It was one
    OpenMP loop that heard no signal: SIGTERM waited for its end, 43.6 s at
    0.96 m beside other work. Sent 3 s of CPU into the set-up (amid the
    field, however busy the machine), it ends the command within
    SET_UP_HEARD, in one line: nothing ran."""
    out = tmp_path / "field"
    proc = _start("cube", "--size", "0.72", "--corr-length", "0.02", "--threads", "1", "--no-plots", "--no-progress",
                  "--out", str(out))
    _wait_for(out.exists, proc, "the output folder")
    cpu = _cpu_seconds(proc.pid)
    _wait_for(lambda: _cpu_seconds(proc.pid) - cpu >= 3.0, proc, "the field")
    rc, err, seconds = _signal_and_time(proc)
    assert rc == 143, err
    assert err.splitlines() == ["ldem cube: terminated (SIGTERM): nothing ran: curve.csv has no rows; no checkpoint: "
                                "it would run again from the start"], err
    assert seconds < SET_UP_HEARD
    assert json.loads((out / "summary.json").read_text())["error"] == "interrupted during set-up"


def test_a_study_and_its_workers_stop_within_seconds(tmp_path):
    """Two cases in two worker processes, each between records 10^8 steps
    apart: SIGTERM to the study ends it and both workers within the deadline
    (no process of its session is left), and each case's summary says
    interrupted."""
    out = tmp_path / "study"
    proc = _start("study", "size-effect", "--out", str(out), "--sizes", "0.04", "--seeds", "2", "--loads", "uniform",
                  "--jobs", "2", "--threads", "1", "--set", "record_every=100000000", "--no-report", "--no-progress")
    curves = lambda: list((out / "cases").glob("*/curve.csv")) if (out / "cases").exists() else []  # noqa: E731
    _wait_for(lambda: len(curves()) == 2 and all(_rows(c) == 1 for c in curves()), proc, "both cases' first rows",
              timeout=600)
    time.sleep(1.0)
    # The study ends once its workers have written their summaries and ended: beside a study at raised
    # priority and builds (a load of 10 on 2 cores) that took more than 5 s, its message coming at once.
    rc, err, seconds = _signal_and_time(proc, deadline=4 * DEADLINE)
    assert rc == 143, err
    assert "Traceback" not in err, err
    # The workers end too, within the deadline from the study's own exit: on a loaded machine (it failed once
    # beside a build) a worker writing its summary may outlast its study by a moment, so the session is
    # watched until it is empty rather than seen once.
    t0, left = time.monotonic(), ["?"]
    while left and time.monotonic() - t0 < 4 * DEADLINE:
        ps = subprocess.run(["ps", "-o", "stat=,args=", "-s", str(proc.pid)], capture_output=True, text=True).stdout
        left = [line for line in ps.splitlines() if not line.startswith("Z")]
        time.sleep(0.1)
    assert left == [], left
    for c in curves():
        assert json.loads((c.parent / "summary.json").read_text())["status"] == "interrupted"


# A study's pool of workers on synthetic cases of 40 KB each (a 200 mm beam's
# pickle is 61 KB), whose runs sleep: the first ends at once, the others in
# a minute. Spawned workers import this file as their main module, so the
# fake run_case is theirs too.
POOL_SCRIPT = """
import os, sys, time
from ldem.signals import Terminated, raise_on_signals
from ldem.study import executors

class Case:
    def __init__(self, k):
        self.k, self.payload = k, bytes(40_000)

def run_case(test, case_dir):
    end = time.monotonic() + (0.2 if test.k == 0 else 60.0)
    while time.monotonic() < end:
        time.sleep(0.02)
    return {"k": test.k}

executors.run_case = run_case

if __name__ == "__main__":
    raise_on_signals()
    args = [(Case(k), f"case{k}") for k in range(6)]
    try:
        executors._run_in_processes(2, list(range(6)), args, lambda i, s: print("finished", i, flush=True))
    except Terminated:
        sys.exit(143)
"""


def test_a_study_with_cases_waiting_for_a_worker_stops_within_seconds(tmp_path):
    """A case has ended, so the pool has queued the next ones, more than a
    pipe holds: SIGTERM to the study alone ends it within the deadline. The
    pool's queue once held the cases themselves; with its workers terminated,
    nobody read the pipe, and the pool's shutdown waited for its writer
    forever (Python 3.11 leaves the pipe's read end open)."""
    script = tmp_path / "pool.py"
    script.write_text(POOL_SCRIPT)
    proc = subprocess.Popen(["/usr/bin/python3", str(script)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=subprocess_env(), cwd=tmp_path, start_new_session=True)
    assert proc.stdout.readline() == "finished 0\n", proc.stderr.read() if proc.poll() is not None else ""
    time.sleep(1.0)  # the pool queues the waiting cases once one has ended
    rc, err, _ = _signal_and_time(proc)
    assert rc == 143, err


@pytest.mark.parametrize("argv,kept", [
    (["study", "validation", "l_panel", "--root", "ROOT"], "finished cases are kept in ROOT/results/validation/l_panel"),
    (["study", "fracture-energy", "ROOT/m.json"], "finished cases are kept in ROOT/fracture_energy"),
    (["study", "calibration", "--fc", "30e6", "--L0", "0.01", "--out", "ROOT/m.json"], "nothing kept")])
def test_an_interrupted_study_names_the_folder_that_keeps_its_cases(tmp_path, monkeypatch, capsys, argv, kept):
    """The message of a signal names the folder a study's cases are kept in
    when the folder is the study's default (it said "nothing kept" of a
    validation that had kept its cases and a checkpoint), and a calibration,
    whose --out is its result file and whose prisms run again, keeps nothing."""
    from ldem import cli
    from ldem.signals import Terminated
    from ldem.study import calibration, fracture_energy, validation

    def stop(*args, **kw):
        raise Terminated()
    for module, name in ((validation, "predict"), (fracture_energy, "measure"), (calibration, "calibrate")):
        monkeypatch.setattr(module, name, stop)
    (tmp_path / "m.json").write_text(json.dumps({"material": {}, "L0": 0.01}))
    root = str(tmp_path)
    assert cli.main([a.replace("ROOT", root) for a in argv]) == 143
    err = capsys.readouterr().err
    assert err.strip().splitlines()[-1].endswith(f"terminated (SIGTERM): {kept.replace('ROOT', root)}"
                                                 + ("; the same command continues the others" if "kept in" in kept
                                                    else "")), err
