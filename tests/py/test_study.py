"""The study machinery on tiny cubes: resume, aggregation, the fractal fit,
parallel processes and a local dask cluster."""
import json
import math
import os
import re

import numpy as np
import pytest

from conftest import FAST, ROOT, colour_share, picture, undamaged_on_white
from ldem import study
from ldem.cube import CubeTest
from ldem.study.cases import Named

TINY = dict(strain_rate=FAST["strain_rate"], final_strain=0.02, threads=1)


@pytest.mark.direct
def test_fractal_fit_recovers_known_exponent():
    b = np.array([0.12, 0.24, 0.48, 0.72, 0.96])
    u = 3.7 * (b / 0.12) ** 2.31
    fit = study.fit_fractal(b, u)
    assert fit["d"] == pytest.approx(2.31, abs=1e-12)
    assert fit["d_specific"] == pytest.approx(0.31, abs=1e-12)
    assert fit["U_b0_J"] == pytest.approx(3.7)
    assert fit["rms_log_residual"] < 1e-12
    # Noise in log space moves d by sum(x n) / sum(x^2), x = ln(b/b0) = ln 1, 2, 4, 6, 8, here
    # 0.05 ln(2 x 6 / (4 x 8)) / (ln^2 2 + ln^2 4 + ln^2 6 + ln^2 8) = -0.00494.
    noisy = u * np.exp([0.0, 0.05, -0.05, 0.05, -0.05])
    logs = np.log([2.0, 4.0, 6.0, 8.0])
    shift = 0.05 * math.log(2 * 6 / (4 * 8)) / float(np.sum(logs ** 2))
    assert shift == pytest.approx(-0.004935, abs=1e-6)
    assert study.fit_fractal(b, noisy)["d"] == pytest.approx(2.31 + shift, rel=1e-12)
    with pytest.raises(ValueError, match="reference size"):
        study.fit_fractal([0.24, 0.48], [1.0, 2.0])


def test_mean_cv_and_aggregation():
    rows = [{"load": "uniform", "size_m": 0.12, "peak_stress_MPa": p, "strain_at_peak": 1e-4 * p,
             "edge_strain_at_peak": 1e-4 * p, "separated": True, "U_num_J": u, "U_min_J": 1.44, "U_ratio": u / 1.44,
             "U_loss_ratio": 0.5, "U_mincut_ratio": 0.7, "energy_error": False, "wall_s": 1.0,
             "separation_strain": 0.01 * p}
            for p, u in ((2.0, 1.0), (3.0, 2.0), (4.0, 3.0))]
    # A fourth specimen that did not separate: in the peak means, not in U_num's.
    rows.append(dict(rows[0], peak_stress_MPa=3.0, separated=False, U_num_J="", U_ratio="", energy_error=True,
                     separation_strain=""))
    (r,) = study.aggregate(rows[:3], c_a=0.1385)
    (r4,) = study.aggregate(rows, c_a=0.1385)
    assert (r4["seeds"], r4["separated"], r4["energy_errors"]) == (4, 3, 1)
    assert r4["U_ratio_mean"] == r["U_ratio_mean"] and r4["peak_stress_MPa_mean"] == pytest.approx(3.0)
    assert r4["separation_strain_mean"] == r["separation_strain_mean"] == pytest.approx(0.03)  # separated ones
    assert r4["U_num_J_mean"] == r["U_num_J_mean"] == pytest.approx(2.0)
    assert r["seeds"] == 3
    assert r["peak_stress_MPa_mean"] == pytest.approx(3.0)
    assert r["peak_stress_MPa_cv"] == pytest.approx(1.0 / 3.0)  # sample std 1 over mean 3
    assert r["U_ratio_mean"] == pytest.approx(2.0 / 1.44)
    assert r["ca_corrected"] == pytest.approx(0.1385 * 2.0 / 1.44)
    assert (r["ref_peak_stress_MPa"], r["ref_strain_at_peak"]) == (2.45, 1.47e-4)  # Table 3


def test_one_value_has_no_cv():
    """A CV over one specimen is no measure of scatter: "" (a table's "-"), never 0."""
    assert study.mean_cv([2.5]) == (2.5, "")
    assert study.mean_cv([2.0, 4.0])[1] == pytest.approx(2 ** 0.5 / 3)


def test_a_one_seed_study_prints_and_tabulates_no_cv(tmp_path, cli):
    out = tmp_path / "one"
    r = cli("study", "size-effect", "--out", str(out), "--sizes", "0.04", "--seeds", "1", "--loads", "uniform",
            "--strain-rate", "0.5", "--threads", "1", "--jobs", "1", "--no-progress")
    assert r.returncode == 0, r.stderr
    (line,) = [x for x in r.stdout.splitlines() if x.lstrip().startswith("uniform ")]
    assert "(cv -)" in line and "cv 0" not in line
    (row,) = study.read_csv(str(out / "summary.csv"))
    assert [row[k] for k in row if k.endswith("_cv")] == [""] * 6  # peak, strain, U_num, load loss, U_final, cut
    report = (out / "report.md").read_text()
    peaks = next(x for x in report.splitlines() if x.startswith("| 0.04 | 1 |")).split(" | ")
    assert (peaks[3], peaks[6]) == ("-", "-")  # the CVs of the peak and of its strain
    energies = next(x for x in report.splitlines() if x.startswith("| uniform | 0.04 |")).split(" | ")
    assert energies[7] == "-"  # U_num/U_min's CV


def test_peak_of_the_mean_curve():
    # Two specimens: a peak of 1 MPa at 1e-4 (then split), and 3 MPa at 3e-4.
    # Mean of the peaks: 2 MPa at 2e-4; the mean curve peaks at 3e-4 with 1.5 MPa
    # (the first specimen carries nothing after it split).
    a = {"mean_strain": np.array([0.0, 1e-4, 1.1e-4]), "stress_MPa": np.array([0.0, 1.0, 0.0])}
    b = {"mean_strain": np.array([0.0, 3e-4, 3.3e-4]), "stress_MPa": np.array([0.0, 3.0, 0.0])}
    peak, strain = study.mean_curve_peak([a, b])
    assert peak == pytest.approx(1.5, rel=1e-3)
    assert strain == pytest.approx(3e-4, rel=1e-3)
    # Where a specimen separated, far past the peaks, does not move the peak of the mean.
    c = {"mean_strain": np.array([0.0, 1.02e-4, 1.1e-4, 0.1]), "stress_MPa": np.array([0.0, 1.0, 0.2, 0.0])}
    assert study.mean_curve_peak([a, c]) == study.mean_curve_peak([a, {k: v[:3] for k, v in c.items()}])
    rows = [{"load": "uniform", "size_m": 0.12, "peak_stress_MPa": p, "strain_at_peak": e, "edge_strain_at_peak": e,
             "separated": True, "U_num_J": 1.0, "U_min_J": 1.44, "U_ratio": 1 / 1.44, "U_loss_ratio": 0.5,
             "U_mincut_ratio": 0.6, "energy_error": False, "wall_s": 1.0, "separation_strain": 1e-2}
            for p, e in ((1.0, 1e-4), (3.0, 3e-4))]
    (r,) = study.aggregate(rows, c_a=0.1385, curves={("uniform", 0.12): [a, b]})
    assert (r["peak_stress_MPa_mean"], r["strain_at_peak_mean"]) == (pytest.approx(2.0), pytest.approx(2e-4))
    assert (r["mean_curve_peak_MPa"], r["mean_curve_strain_at_peak"]) == (peak, strain)


def test_case_names_carry_non_default_parameters():
    assert study.case_name(CubeTest(size=0.24, seed=3)) == "uniform_0.24m_s3"
    assert study.case_name(CubeTest(size=0.24, seed=3, zeta=2.0, threads=2)) == "uniform_0.24m_s3_zeta2"
    # Values that %g would round alike get every digit: two cases never share a folder.
    assert study.case_name(CubeTest(zeta=0.03000001)) == "uniform_0.12m_s1_zeta0.03000001"
    assert study.case_name(CubeTest(zeta=0.030000000001)) != study.case_name(CubeTest(zeta=0.03))


def test_a_case_line_says_where_a_run_stopped(tmp_path):
    """A triangular cube stops past its peak, not "before separation": its line says where."""
    [test] = study.size_effect_tests([0.04], 1, ["triangular"], **TINY)
    log = []
    [summary] = study.run_cases([test], str(tmp_path / "st"), log=log.append)
    assert summary["stop_reason"] == "past_peak"
    assert "stopped at peak_stop_strain_ratio x the strain at the peak, " in log[-1], log
    assert "separation" not in log[-1]


def test_a_case_stopped_by_its_own_observer_is_not_said_to_stop_before_separation(tmp_path):
    """A case whose run ends where an observer of its own says (a study's beam
    past its peak) ended where it was meant to, even if its test would run
    to separation: its line says the observer stopped it, nothing more."""
    class TwoRows(Named):
        def run(self, observers=(), simulation=None, previous_rows=()):
            rows = []
            return self.test.run(list(observers) + [lambda row: rows.append(row) or len(rows) < 2],
                                 simulation, previous_rows)

    [cube] = study.size_effect_tests([0.04], 1, ["uniform"], **TINY)
    assert cube.stop_at == "separation"
    log = []
    [summary] = study.run_cases([TwoRows(cube, "two_rows")], str(tmp_path / "st"), log=log.append)
    assert summary["stop_reason"] == "stopped"
    assert "stopped at an observer's request," in log[-1], log
    assert "separation" not in log[-1], log


def test_study_resumes_and_never_recomputes_finished_cases(tmp_path):
    out = str(tmp_path / "st")
    tests = study.size_effect_tests([0.04, 0.08], 2, ["uniform"], **TINY)
    first = study.run_cases(tests, out, log=lambda s: None)
    assert [s["status"] for s in first] == ["done"] * 4
    dirs = [os.path.join(out, "cases", study.case_name(t)) for t in tests]
    stamp = {d: os.path.getmtime(os.path.join(d, "summary.json")) for d in dirs}
    # Half-finished case: interrupted run (summary says so) -> recomputed; the others are kept.
    with open(os.path.join(dirs[1], "summary.json")) as f:
        s = json.load(f)
    s["status"] = "interrupted"
    with open(os.path.join(dirs[1], "summary.json"), "w") as f:
        json.dump(s, f)
    os.remove(os.path.join(dirs[2], "slice.npz"))  # died before its last file
    # Ran before a parameter was declared (at its default now): still finished.
    with open(os.path.join(dirs[0], "summary.json")) as f:
        s = json.load(f)
    del s["parameters"]["Gf_draw"]
    with open(os.path.join(dirs[0], "summary.json"), "w") as f:
        json.dump(s, f)
    stamp[dirs[0]] = os.path.getmtime(os.path.join(dirs[0], "summary.json"))
    # A curve.csv cut in its last row (a full disk, a kill): not finished.
    curve = os.path.join(dirs[3], "curve.csv")
    with open(curve, "rb") as f:
        data = f.read()
    with open(curve, "wb") as f:
        f.write(data[:-7])
    ran = []
    again = study.run_cases(tests, out, log=ran.append)
    assert ran[0] == f"1 of 4 cases already finished in {out}/cases"
    names = [study.case_name(t) for t in tests]
    assert ran[1:4] == [f"  {names[1]}: status 'interrupted': running it again",
                        f"  {names[2]}: no loadable slice.npz: running it again",
                        f"  {names[3]}: curve.csv incomplete (last row at step -1, summary.json says "
                        f"{first[3]['steps']}): running it again"]
    assert len(ran) == 7  # those lines and the three recomputed cases
    assert os.path.getmtime(os.path.join(dirs[0], "summary.json")) == stamp[dirs[0]]
    assert again[3]["peak_stress_MPa"] == first[3]["peak_stress_MPa"]
    assert again[1]["status"] == "done"
    # Deterministic: the recomputed case gives the same figures.
    assert again[1]["peak_stress_MPa"] == first[1]["peak_stress_MPa"]
    assert again[2]["fracture_energy_J"] == first[2]["fracture_energy_J"]


def test_an_interrupted_case_continues_from_its_checkpoint(tmp_path, monkeypatch):
    """A case writes checkpoint.npz as it runs; a study killed in the middle of
    it continues from there, and ends bit for bit as the case that never
    stopped: the same curve.csv and summary figures. Its wall time counts both
    pieces; the checkpoint is removed once the case is finished."""
    import ldem
    from ldem.rerun import RESTART_SKIPS, differences
    from ldem.study import cases

    monkeypatch.setattr(cases, "CHECKPOINT_SECONDS", 1e-9)  # a checkpoint at every curve row
    test = CubeTest(size=0.06, **TINY)
    whole = study.run_cases([test], str(tmp_path / "whole"), log=lambda s: None)[0]
    cut = study.case_dir(str(tmp_path / "cut"), test)
    with open(os.path.join(study.case_dir(str(tmp_path / "whole"), test), "curve.csv"), "rb") as f:
        curve = f.read()
    rows = []

    def killed(row):  # three quarters through: most of the wall time is before the checkpoint
        rows.append(row["step"])
        if len(rows) == 3 * (curve.count(b"\n") - 1) // 4:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        ldem.run_cube(test, out=cut, progress=False, plots=False, checkpoint_seconds=1e-9, observers=[killed])
    _, _, wall_before = ldem.io.read_checkpoint(os.path.join(cut, "checkpoint.npz"))
    assert wall_before > 0
    log = []
    again = study.run_cases([test], str(tmp_path / "cut"), log=log.append)[0]
    name = study.case_name(test)
    assert log[0] == f"  {name}: status 'interrupted': continuing from its checkpoint at step {rows[-1]}"
    assert again["restarted_at_step"] == rows[-1] and 0 < rows[-1] < whole["steps"]
    assert differences(whole, again, RESTART_SKIPS) == []
    with open(os.path.join(cut, "curve.csv"), "rb") as f:
        assert f.read() == curve
    assert again["wall_s"] > wall_before
    assert not os.path.exists(os.path.join(cut, "checkpoint.npz"))
    assert study.run_cases([test], str(tmp_path / "cut"), log=log.append)[0] == again  # finished: not run again


def test_size_effect_command_tables_and_report(tmp_path, cli):
    out = str(tmp_path / "se")
    r = cli("study", "size-effect", "--out", out, "--sizes", "0.04,0.12", "--seeds", "2", "--jobs", "2",
            "--strain-rate", "0.1", "--set", "final_strain=0.3", "--no-progress")
    assert r.returncode == 0, r.stderr
    summary = study.read_csv(os.path.join(out, "summary.csv"))
    cases = study.read_csv(os.path.join(out, "cases.csv"))
    assert len(cases) == 8 and len(summary) == 4
    import ldem
    assert all(c["ldem_version"] == ldem.__version__ and c["host"] and c["date"] for c in cases)  # provenance
    for col in study.SUMMARY_COLUMNS:
        assert col in summary[0]
    u012 = [c for c in cases if c["load"] == "uniform" and c["size_m"] == 0.12]
    row = next(s for s in summary if s["load"] == "uniform" and s["size_m"] == 0.12)
    assert row["peak_stress_MPa_mean"] == pytest.approx(np.mean([c["peak_stress_MPa"] for c in u012]), rel=1e-5)
    separated = [c["U_ratio"] for c in u012 if c["separated"] in (True, "True")]
    assert row["separated"] == len(separated) > 0
    assert row["U_ratio_mean"] == pytest.approx(np.mean(separated), rel=1e-5)
    assert all(c["U_ratio"] == "" for c in cases if c["separated"] not in (True, "True"))
    assert all(c["energy_balance_error"] < 0.01 for c in cases)
    # The fit of each load whose both sizes have separated specimens, through the
    # mean U_num of summary.csv (written to 6 digits); none for the others.
    fits = json.load(open(os.path.join(out, "fractal.json")))
    for load in ("uniform", "triangular"):
        rows = sorted((s for s in summary if s["load"] == load), key=lambda s: s["size_m"])
        if any(s["U_num_J_mean"] == "" for s in rows):
            assert load not in fits, load
            continue
        want = study.fit_fractal([s["size_m"] for s in rows], [s["U_num_J_mean"] for s in rows])
        assert set(fits[load]) == set(want)
        assert fits[load]["U_b0_J"] == pytest.approx(rows[1]["U_num_J_mean"], rel=1e-5)
        assert fits[load]["d"] == pytest.approx(want["d"], abs=1e-4)
        assert fits[load]["d_specific"] == pytest.approx(fits[load]["d"] - 2, abs=1e-12)
        assert fits[load]["rms_log_residual"] < 1e-12  # two sizes: the line goes through both
    assert "uniform" in fits
    for name in ("fractal.png", "curves_triangular.png", "mean_curves_uniform.png", "fracture_energy_triangular.png"):
        picture(os.path.join(out, name))
    cracks = picture(os.path.join(out, "cracks_uniform.png"))
    assert colour_share(cracks, "red") > 1e-4 and colour_share(cracks, undamaged_on_white()) > 1e-4
    report = open(os.path.join(out, "report.md")).read()
    assert "| 0.12 | 2 |" in report
    # The cost of each load: its cases' wall times added up, the longest, the commits they ran on.
    cost = {m[0]: m[1:] for m in re.findall(r"^\| (uniform|triangular) \| (\d+) \| [\d, ]+ \| (\d+) \| (\d+) \| (.*) \|$",
                                             report, re.M)}
    for load in ("uniform", "triangular"):
        walls = [c["wall_s"] for c in cases if c["load"] == load]
        n, total, longest, commits = cost[load]
        assert int(n) == 4 and abs(int(total) - sum(walls)) <= 1 and abs(int(longest) - max(walls)) <= 1
        assert commits.split(", ") == sorted({str(c["git_commit"])[:7] or "?" for c in cases if c["load"] == load})


def test_study_bad_input_is_one_line(tmp_path, cli):
    r = cli("study", "size-effect", "--out", str(tmp_path), "--sizes", "0.12,-1")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "size must be > 0 (got -1 m)" in r.stderr
    r = cli("study", "damping", "--out", str(tmp_path), "--loads", "shear")
    assert r.returncode == 2 and "unknown load 'shear'" in r.stderr


def test_cases_on_a_local_dask_cluster(tmp_path):
    import distributed  # README: install.sh installs python3-distributed; missing is a failure
    out = str(tmp_path / "dask")
    tests = study.damping_tests(0.04, [0.02, 1.5], ["uniform"], **TINY)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as c:
        summaries = study.run_cases(tests, out, scheduler=c.scheduler_address, log=lambda s: None)
    assert [s["status"] for s in summaries] == ["done", "done"]
    assert [s["parameters"]["zeta"] for s in summaries] == [0.02, 1.5]
    # The same cases in this process give the same numbers.
    local = study.run_cases(tests, str(tmp_path / "local"), log=lambda s: None)
    assert [s["peak_stress_MPa"] for s in local] == [s["peak_stress_MPa"] for s in summaries]


def test_two_studies_never_share_a_folder(tmp_path):
    """A study holds out/.lock while it runs; a second one stops with the holder's
    name. A lock whose process is gone (killed) is taken over."""
    import socket
    import subprocess

    out = str(tmp_path / "st")
    os.makedirs(out)
    lock = os.path.join(out, ".lock")
    with open(lock, "w") as f:
        f.write(f"{socket.gethostname()} {os.getpid()}\n")  # this process: alive
    tests = study.size_effect_tests([0.04], 1, ["uniform"], **TINY)
    with pytest.raises(ValueError, match=f"study folder {out} is in use by process {os.getpid()}"):
        study.run_cases(tests, out, log=lambda s: None)
    p = subprocess.Popen(["true"])  # a finished child: its pid runs nothing
    p.wait()
    with open(lock, "w") as f:
        f.write(f"{socket.gethostname()} {p.pid}\n")
    said = []
    assert study.run_cases(tests, out, log=said.append)[0]["status"] == "done"
    assert any("left its lock: taking it over" in s for s in said) and not os.path.exists(lock)



def test_a_relative_study_folder_on_dask_workers_elsewhere(tmp_path, monkeypatch):
    """--scheduler with a relative --out: the workers (started in another
    folder) write where the client means, because case folders are made
    absolute before they are sent."""
    import distributed

    start, here = tmp_path / "workers_start_here", tmp_path / "client"
    start.mkdir(), here.mkdir()
    monkeypatch.chdir(start)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as c:
        monkeypatch.chdir(here)  # the client moves; the worker stays in `start`
        tests = study.damping_tests(0.04, [0.02], ["uniform"], **TINY)
        summaries = study.run_cases(tests, "rel", scheduler=c.scheduler_address, log=lambda s: None)
    assert summaries[0]["status"] == "done"
    assert (here / "rel" / "cases" / study.case_name(tests[0]) / "summary.json").is_file()
    assert not (start / "rel").exists()


def test_threads_per_case_are_the_studys():
    """Threads per case come from the study's options, never from the client's
    cores when the cases run on a dask cluster."""
    import argparse
    import os

    from ldem.study.options import common_settings as _common

    def args(**kw):
        base = dict(threads=0, scheduler=None, jobs=1, strain_rate=0.02, set=[])
        return argparse.Namespace(**{**base, **kw})

    assert _common(args(scheduler="tcp://elsewhere:8786"))["threads"] == 1
    assert _common(args(scheduler="tcp://elsewhere:8786", threads=4))["threads"] == 4
    assert _common(args(jobs=2))["threads"] == max(1, (os.cpu_count() or 1) // 2)


def test_no_study_lock_is_committed():
    """A study's .lock names a process of one machine: committed, it would stop a
    study in that folder on every other machine."""
    import subprocess

    r = subprocess.run(["git", "-C", ROOT, "ls-files", "*.lock", "**/.lock"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr  # the suite runs on a checkout (CI: a fresh clone)
    assert r.stdout.strip() == "", r.stdout


def test_worker_processes_take_the_largest_cubes_first():
    """In worker processes the study's cases (listed smallest first) start
    largest first, so that the run ends on small cases, not on a 0.96 m cube
    alone on one core; a test with no size keeps its place after the cubes."""
    from ldem.study.executors import largest_first

    class NoSize:
        pass

    tests = study.size_effect_tests([0.12, 0.96, 0.48], 2, ["uniform"]) + [NoSize(), NoSize()]
    todo = list(range(len(tests)))
    order = [i for i, _ in largest_first(todo, [(t, f"d{i}") for i, t in enumerate(tests)])]
    assert [getattr(tests[i], "size", None) for i in order] == [0.96, 0.96, 0.48, 0.48, 0.12, 0.12, None, None]
    assert order == [2, 3, 4, 5, 0, 1, 6, 7]  # stable: seeds and the sizeless keep their order
