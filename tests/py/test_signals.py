"""Issue 40, item 2: SIGTERM and Ctrl-C heard within seconds in every phase
(the set-up of a large lattice, its Lanczos analysis, a run between records
far apart, a study's worker processes), and a message that says only what
the files hold. Each test signals the real command and gives it 5 s."""
import json
import os
import signal
import subprocess
import time

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


def _signal_and_time(proc, signum=signal.SIGTERM):
    """Sends signum; (return code, stderr, seconds to the exit). Whatever
    is left of the session after the deadline is killed (and fails the test)."""
    t0 = time.monotonic()
    proc.send_signal(signum)
    try:
        _, err = proc.communicate(timeout=DEADLINE)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        pytest.fail(f"no exit within {DEADLINE} s of the signal")
    return proc.returncode, err, time.monotonic() - t0


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


def test_a_study_and_its_workers_stop_within_seconds(tmp_path):
    """Two cases in two worker processes, each between records 10^8 steps
    apart: SIGTERM to the study ends it and both workers within the deadline
    (no process of its session is left), and each case's summary says
    interrupted."""
    out = tmp_path / "study"
    proc = _start("study", "size-effect", "--out", str(out), "--sizes", "0.04", "--seeds", "2", "--loads", "uniform",
                  "--jobs", "2", "--threads", "1", "--set", "record_every=100000000", "--no-report", "--no-progress")
    curves = lambda: list((out / "cases").glob("*/curve.csv")) if (out / "cases").exists() else []  # noqa: E731
    _wait_for(lambda: len(curves()) == 2 and all(_rows(c) == 1 for c in curves()), proc, "both cases' first rows")
    time.sleep(1.0)
    rc, err, seconds = _signal_and_time(proc)
    assert rc == 143, err
    assert "Traceback" not in err, err
    ps = subprocess.run(["ps", "-o", "stat=,args=", "-s", str(proc.pid)], capture_output=True, text=True).stdout
    assert [line for line in ps.splitlines() if not line.startswith("Z")] == [], ps  # the workers ended too
    for c in curves():
        assert json.loads((c.parent / "summary.json").read_text())["status"] == "interrupted"


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
