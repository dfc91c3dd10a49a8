"""`ldem study beams` (issue 38, a study in one place): its sub-commands are
listed by its --help, and those that run no beam work end to end on the
committed prediction turned back into the case folders it was written from
(curve.csv from curves/*.csv, summary.json's peak from size_effect.csv, of
each of the 54 runs)."""
import csv
import os

import numpy as np
import pytest

from conftest import ROOT, picture
from ldem import io
from ldem.study.beams import cases as beams

PREDICTION = os.path.join(ROOT, "results", "beams", "gregoire2013")
COMMANDS = ["calibrate", "predict", "uniform", "curves", "compare", "size-effect", "diagnose", "calibrated",
            "whole-curves", "transfer", "convergence"]


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_the_help_lists_every_sub_command(cli):
    r = cli("study", "beams", "--help")
    assert r.returncode == 0, r.stderr
    listed = [line.split()[0] for line in r.stdout.split("positional arguments:")[1].splitlines()[2:]
              if line.startswith("    ") and not line.startswith("     ")]
    assert listed == COMMANDS, r.stdout
    r = cli("study", "beams", "predict", "--help")
    assert r.returncode == 0 and "--eps-p" in r.stdout and "(default: results/beams/gregoire2013)" in r.stdout
    r = cli("study", "beams")
    assert r.returncode == 2 and "required: COMMAND" in r.stderr
    r = cli("study", "beams", "predict", "--seeds", "2")
    assert r.returncode == 2 and "--eps-p" in r.stderr


@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    """OUT/cases/D{mm}_n{notch}_s{seed}/ from the committed curves/*.csv (units back to the run's)."""
    out = tmp_path_factory.mktemp("beams")
    peaks = {(float(r["D_m"]), float(r["notch"]), int(r["seed"])): float(r["F_N"])  # the runs' [N]
             for r in _rows(os.path.join(PREDICTION, "size_effect.csv")) if r["Gf_cv"] == "1"}
    for D in beams.DEPTHS:
        for notch in beams.NOTCHES:
            table = np.genfromtxt(os.path.join(PREDICTION, "curves", f"D{D * 1e3:g}_n{notch:g}.csv"),
                                  delimiter=",", names=True)
            for seed in range(1, 7):
                load = table[f"load_kN_s{seed}"]
                keep = ~np.isnan(load)
                case = out / "cases" / f"D{D * 1e3:g}_n{notch:g}_s{seed}"
                case.mkdir(parents=True)
                columns = {"mean_strain": table[f"deflection_mm_s{seed}"][keep] / 1e3 / D,
                           "stress_MPa": load[keep] / 1e3, "cmod_m": table[f"cmod_mm_s{seed}"][keep] / 1e3}
                io.write_table(str(case / io.tables.CURVE), [{k: f"{v[i]:.9g}" for k, v in columns.items()}
                                                             for i in range(int(keep.sum()))], list(columns))
                io.tables.write_summary({"status": "done", "peak_stress_MPa": peaks[D, notch, seed] / 1e6},
                                        str(case / io.tables.SUMMARY))
    return out


def test_the_tables_and_figures_from_finished_cases(cases, cli):
    """predict --jobs 0 (the table only), curves and size-effect give back the
    committed tables (to their 6 digits)."""
    r = cli("study", "beams", "predict", "--eps-p", "1e-4", "--jobs", "0", "--out", str(cases))
    assert r.returncode == 0, r.stderr
    assert not list((cases / "cases").glob("*/checkpoint*"))  # nothing ran
    got, committed = _rows(cases / "predictions.csv"), _rows(os.path.join(PREDICTION, "predictions.csv"))
    assert [(g["D_mm"], g["notch_ratio"], g["seeds"]) for g in got] == \
        [(c["D_mm"], c["notch_ratio"], c["seeds"]) for c in committed]
    for g, c in zip(got, committed):
        for k in ("peak_load_kN", "min_kN", "max_kN"):
            assert float(g[k]) == pytest.approx(float(c[k]), rel=1e-5), (g, c, k)
        # The peaks are read to 6 digits (5e-6 relative): the sample deviation moves by
        # up to that times the load over the deviation, 5e-6 / 0.022 = 2.3e-4 at the least CV.
        assert float(g["cv"]) == pytest.approx(float(c["cv"]), rel=3e-4), (g, c)
    r = cli("study", "beams", "curves", "--out", str(cases))
    assert r.returncode == 0, r.stderr
    for name in ("D50_n0.5.csv", "D200_n0.csv"):
        a = np.genfromtxt(cases / "curves" / name, delimiter=",", skip_header=1)
        b = np.genfromtxt(os.path.join(PREDICTION, "curves", name), delimiter=",", skip_header=1)
        np.testing.assert_allclose(a, b, rtol=1e-5, atol=1e-12)
    picture(cases / "curves.png")
    r = cli("study", "beams", "size-effect", "--out", str(cases))
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines()[0] == (cases / "size_effect.md").read_text().splitlines()[2]
    got = _rows(cases / "size_effect.csv")
    committed = [row for row in _rows(os.path.join(PREDICTION, "size_effect.csv")) if row["Gf_cv"] == "1"]
    assert len(got) == len(committed) == 54
    key = lambda row: (float(row["D_m"]), float(row["notch"]), int(row["seed"]))  # noqa: E731
    for g, c in zip(sorted(got, key=key), sorted(committed, key=key)):
        assert key(g) == key(c) and float(g["F_N"]) == pytest.approx(float(c["F_N"]), rel=1e-5)
    picture(cases / "size_effect.png")


def test_bad_input_is_one_line_before_anything_runs(tmp_path, cli):
    for command in ("predict", "uniform"):
        r = cli("study", "beams", command, "--out", str(tmp_path), "--eps-p", "0")
        assert r.returncode == 2 and r.stderr.count("\n") == 1 and "--eps-p must be positive (got 0.0" in r.stderr
    r = cli("study", "beams", "predict", "--out", str(tmp_path), "--eps-p", "1e-4", "--seeds", "0")
    assert r.returncode == 2 and "--seeds must be at least 1 (got 0)" in r.stderr
    assert not (tmp_path / "cases").exists() and not (tmp_path / "cases_cv0").exists()
    r = cli("study", "beams", "predict", "--out", str(tmp_path), "--eps-p", "1e-4", "--notches", "0.3")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "--notches: each one of 0, 0.2, 0.5" in r.stderr
    r = cli("study", "beams", "predict", "--out", str(tmp_path), "--eps-p", "1e-4", "--rate-periods", "-1")
    assert r.returncode == 2 and "--rate-periods must be >= 0 (got -1.0)" in r.stderr
    assert not (tmp_path / "cases").exists()
    r = cli("study", "beams", "size-effect", "--out", str(tmp_path))
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "no finished case" in r.stderr
    r = cli("study", "beams", "diagnose", "--out", str(tmp_path), "--factors", "cmod,nothing")
    assert r.returncode == 2 and "unknown factor 'nothing'" in r.stderr
    assert not (tmp_path / "diagnosis").exists()


def test_whole_curves_and_transfer_refuse_bad_input_in_one_line(cli, tmp_path):
    """No calibrated concrete beside OUT, a --start that is not there, or a beam that was not measured: rc 2
    and one line naming it, before anything runs."""
    data = os.path.join(ROOT, "..", "shared", "data", "gregoire2013")
    out = tmp_path / "study" / "whole_curves"
    r = cli("study", "beams", "whole-curves", "--out", str(out), "--data", data)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "calibrated/material.json not found" in r.stderr
    if os.path.isdir(data):
        r = cli("study", "beams", "transfer", "--on", "D60_n0", "--out", str(tmp_path / "t"), "--data", data)
        assert r.returncode == 2 and r.stderr.count("\n") == 1 and "unknown beam 'D60_n0'" in r.stderr
        r = cli("study", "beams", "transfer", "--start", str(tmp_path / "none.json"), "--out", str(tmp_path / "t"),
                "--data", data)
        assert r.returncode == 2 and r.stderr.count("\n") == 1 and "none.json not found" in r.stderr
    assert not out.exists()


def test_rule_c_drives_a_beam_in_place_of_the_study_s_rate():
    """--rate-periods N: the beam's file asks rule (c)'s rate (eps_p in N periods of omega_d), not 0.1 D/s."""
    study = beams.beam(0.05, 0.5, 1e-4, 1)
    rule = beams.beam(0.05, 0.5, 1e-4, 1, v=beams.Variant(rate_periods=3))
    assert study.build.params["rate_periods"] == 0 and study.strain_rate == beams.PREDICTION.rate == 0.1
    assert rule.build.params["rate_periods"] == 3
    assert [t.notch for t in beams.series_tests(1e-4, 2, notches=(0.5,))] == [0.5] * 6  # three depths, two seeds
