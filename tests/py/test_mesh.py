"""The mesh study (issue 15): coarse lattices against fine ones, the
criterion's mapping, and `ldem study mesh` / `refinement` end to end."""
import os

import numpy as np
import pytest

from conftest import run_cli

import ldem
from ldem.study import mesh
from ldem.study.mesh import tables as mesh_tables


def _modulus(size, L0):
    """E_app / E of a cube pulled uniformly below eps_p: the slope of the
    second half of the stress-strain curve (past the smooth start)."""
    result = ldem.CubeTest(size=size, L0=L0, final_strain=3e-5, threads=1).run()
    assert result.curve["damaged_bars"][-1] == 0
    e, s = result.curve["mean_strain"], result.curve["stress_MPa"] * 1e6
    k = len(e) // 2
    return np.polyfit(e[k:], s[k:], 1)[0] / ldem.CubeTest().E


def test_a_coarse_and_a_fine_block_have_the_same_stiffness_up_to_the_surface_layer():
    """Bars scale with their module (areas L^2, masses L^3): a block of n
    modules has one stiffness per unit size whatever L, so 0.12 m at L = 0.04
    and 0.24 m at L = 0.08 agree (measured: 3e-5). Across n the interior is
    the same material; the surface layer (softer: no centre-to-centre bars
    cross the surface) weighs 1/n, so 1/E_app is linear in 1/n and the fine
    block (n = 12) is within 5 % of E. The coarse block's deficit is that
    layer's and nothing else: n = 6 on the line through n = 3 and n = 12 within
    0.5 % (measured 0.23 %; E_app = 0.823, 0.915, 0.966 E at n = 3, 6, 12)."""
    e3 = _modulus(0.12, 0.04)
    assert _modulus(0.24, 0.08) == pytest.approx(e3, rel=1e-3)
    e6, e12 = _modulus(0.12, 0.02), _modulus(0.12, 0.01)
    assert e3 < e6 < e12 < 1.0 and e12 > 0.95
    line = 1 / e12 + (1 / e3 - 1 / e12) * (1 / 6 - 1 / 12) / (1 / 3 - 1 / 12)
    assert 1 / e6 == pytest.approx(line, rel=5e-3)


def _row(peak, strain, ratio, separated=True, size=0.06):
    return {"size_m": size, "peak_stress_MPa": peak, "strain_at_peak": strain,
            "separated": separated, "U_ratio": ratio if separated else ""}


def test_the_criterion_maps_a_synthetic_fine_table_onto_its_law():
    """eps_p = mean peak / E, E[G_f] unchanged, CV(G_f) = CV(U_num/U_min) over
    the separated cubes (sample CV), c_a = 0.1385 E[U_num/U_min]; rounded to 4
    digits. A cube that did not separate counts for the peak only."""
    base = ldem.CubeTest()
    rows = [_row(2.4, 2e-4, 1.2), _row(2.6, 3e-4, 1.0), _row(2.5, 2.5e-4, 1.4), _row(2.1, 1e-4, 0, separated=False)]
    law = mesh.criterion_law(rows, base)
    assert law["peak_stress_MPa_mean"] == pytest.approx(2.4)
    assert law["eps_p"] == pytest.approx(2.4e6 / 3.5e10, rel=1e-4)
    assert law["U_ratio_mean"] == pytest.approx(1.2) and law["separated"] == 3 and law["seeds"] == 4
    assert law["Gf_cv"] == pytest.approx(0.2 / 1.2, rel=1e-3)   # sample std of 1.0, 1.2, 1.4 is 0.2
    assert law["c_a"] == pytest.approx(0.1385 * 1.2, rel=1e-4) and law["Gf_mean"] == base.Gf_mean
    # The fine law is its own fixed point: cubes peaking at E eps_p, splitting at U_min with CV 1.
    same = mesh.criterion_law([_row(3.5e10 * 6.3e-5 / 1e6, 1e-4, r) for r in (1 - 1.0, 1.0, 1 + 1.0)], base)
    assert (same["eps_p"], same["Gf_cv"], same["c_a"]) == (base.eps_p, base.Gf_cv, base.c_a)
    with pytest.raises(ValueError, match="at least two"):
        mesh.criterion_law([_row(2.4, 2e-4, 1.2), _row(2.4, 2e-4, 0, separated=False)], base)


def test_the_calibration_scales_eps_p_and_c_a_by_fine_over_coarse():
    """On the calibration cube: eps_p x fine peak / coarse peak, c_a x fine
    U_num/U_min / coarse U_num/U_min (separated specimens only)."""
    base = ldem.CubeTest()
    fine = [_row(2.4, 2e-4, 1.1), _row(2.6, 2e-4, 1.3)]
    coarse = [_row(2.0, 2e-4, 2.0), _row(2.0, 2e-4, 2.4), _row(2.0, 2e-4, 0, separated=False)]
    law = mesh.calibrated_law(fine, coarse, base)
    assert law["calibration_peak_ratio"] == pytest.approx(1.25)
    assert law["calibration_U_ratio"] == pytest.approx(1.2 / 2.2)
    assert law["calibrated_eps_p"] == pytest.approx(6.3e-5 * 1.25, rel=1e-4)
    assert law["calibrated_c_a"] == pytest.approx(0.1385 * 1.2 / 2.2, rel=1e-4)
    with pytest.raises(ValueError, match="calibration cubes separated"):
        mesh.calibrated_law(fine, coarse[2:], base)


def test_each_variant_takes_its_part_of_the_law():
    base = ldem.CubeTest()
    law = {"eps_p": 7e-5, "Gf_mean": 100.0, "Gf_cv": 0.2, "c_a": 0.15}
    assert mesh.variant_law("plain", law, base) == {}
    assert mesh.variant_law("law", law, base) == {"eps_p": 7e-5, "Gf_cv": 0.2}    # Gf_mean unchanged
    assert mesh.variant_law("c_a", law, base) == {"c_a": 0.15}
    assert mesh.variant_law("criterion", law, base) == {"eps_p": 7e-5, "Gf_cv": 0.2, "c_a": 0.15}
    law.update(calibrated_eps_p=7.5e-5, calibrated_c_a=0.1)
    assert mesh.variant_law("calibrated", law, base) == {"eps_p": 7.5e-5, "c_a": 0.1}   # CV(G_f) the material's
    with pytest.raises(ValueError, match="unknown variant"):
        mesh.variant_law("better", law, base)


def test_the_verdict_reads_the_distance_from_the_fine_lattice():
    rows = [dict(role="fine", variant="fine", module_m=0.02, corr_length_m=0.0, load="uniform", size_m=0.96,
                 peak_stress_MPa=2.0, strain_at_peak=1e-4, separated=True, U_ratio=1.4, clamped_bars=0, n_bars=1000,
                 steps=300, wall_s=100.0),
            dict(role="coarse", variant="criterion", module_m=0.06, corr_length_m=0.0, load="uniform", size_m=0.96,
                 peak_stress_MPa=2.3, strain_at_peak=1e-4, separated=True, U_ratio=1.5, clamped_bars=1, n_bars=10,
                 steps=100, wall_s=4.0)]
    table = mesh_tables.summarize(rows)
    assert table[1]["speedup"] == pytest.approx(25.0) and table[1]["U_vs_fine"] == pytest.approx(1.5 / 1.4)
    assert table[1]["work_ratio"] == pytest.approx(300.0) and table[1]["clamped_fraction"] == pytest.approx(0.1)
    (v,) = mesh_tables.verdict(table)
    assert v["peak_error"] == pytest.approx(0.15) and not v["peak_ok"] and v["U_ok"]


def _results(out):
    """summary.csv without the wall times."""
    return [{k: v for k, v in r.items() if k not in ("wall_s_mean", "speedup")}
            for r in ldem.study.read_csv(os.path.join(out, "summary.csv"))]


def _case_folders(out):
    return sorted(os.listdir(os.path.join(out, "cases")))


def test_ldem_study_mesh_end_to_end_and_resumed(tmp_path):
    """Tiny cubes: the fine cubes of side 0.04 m give the law, the 0.08 m
    ones the calibration, the 0.12 m cube runs fine (L0 = 0.02) and coarse
    (L = 0.04) with three variants; a second call computes nothing, a lost
    case is computed again alone."""
    out = str(tmp_path / "mesh")
    args = ["study", "mesh", "--out", out, "--sizes", "0.12", "--modules", "0.04", "--seeds", "2", "--law-seeds", "2",
            "--loads",
            "uniform", "--variants", "plain,criterion,calibrated", "--calibration-size", "0.08", "--threads", "1",
            "--no-progress"]
    first = run_cli(*args)
    assert first.returncode == 0, first.stderr
    names = _case_folders(out)
    assert len(names) == 2 + 2 + 2 + 2 + 6   # law cubes, calibration fine and coarse, fine references, coarse
    law = mesh.read_laws(out)[0.04]
    assert any(f"eps_p{law['eps_p']:g}" in n for n in names)
    assert any(f"c_a{law['calibrated_c_a']:g}" in n for n in names)
    table = {(r["module_m"], r["variant"]): r for r in ldem.study.read_csv(os.path.join(out, "summary.csv"))}
    assert table[(0.02, "fine")]["peak_vs_fine"] == 1.0 and table[(0.04, "criterion")]["seeds"] == 2
    assert os.path.exists(os.path.join(out, "report.md")) and os.path.exists(os.path.join(out, "peak_vs_module.png"))
    before = _results(out)
    again = run_cli(*args)
    assert again.returncode == 0 and "6 of 6 cases already finished" in again.stdout   # the law's cubes
    assert "8 of 8 cases already finished" in again.stdout                                # fine and coarse
    os.remove(os.path.join(out, "cases", names[-1], "summary.json"))
    third = run_cli(*args, "--report-only")     # computes nothing: the tables of the finished cases
    assert third.returncode == 0 and "already finished" not in third.stdout
    assert len(ldem.study.read_csv(os.path.join(out, "cases.csv"))) == 7
    with open(os.path.join(out, "report.md")) as f:
        assert "**1 of the cases asked for are not finished**" in f.read()
    fourth = run_cli(*args)
    assert "7 of 8 cases already finished" in fourth.stdout
    assert _results(out) == before    # the same seed gives the same specimen
    # Extended from its tables alone: the laws and the 8 cases are the earlier run's, only seed 3 runs.
    more = str(tmp_path / "more")
    fifth = run_cli(*[a if a != out else more for a in args], "--seeds", "3", "--earlier", out)
    assert fifth.returncode == 0, fifth.stderr
    assert len(_case_folders(more)) == 4 and all("_s3" in n for n in _case_folders(more))
    assert mesh.read_laws(more) == mesh.read_laws(out)
    rows = ldem.study.read_csv(os.path.join(more, "cases.csv"))
    assert len(rows) == 12 and [r for r in rows if r["seed"] < 3] == ldem.study.read_csv(os.path.join(out, "cases.csv"))
    with open(os.path.join(more, "report.md")) as f:
        assert "8 cases are rows of an earlier run's cases.csv" in f.read()


@pytest.mark.parametrize("extra, message", [
    (["--variants", "plain,better"], "unknown variant 'better'"),
    (["--modules", "0.05"], "module 0.05 m: the criterion reads a fine cube of that side"),
    (["--modules", "0.08"], "a 0.12 m cube cannot be cut into modules of 0.08 m"),
    (["--set", "c_a=0.2"], "--set c_a: the mesh study sets it"),
    (["--reference", "/nonexistent"], "not a study folder"),
    (["--law-seeds", "1"], "--law-seeds must be at least 2"),
    (["--modules", "0.04", "--calibration-size", "0.12"], "must not be one of the cubes predicted"),
    (["--modules", "0.04", "--earlier", "/nonexistent"], "--earlier /nonexistent: no laws.csv in it"),
])
def test_bad_mesh_study_input_is_one_line(tmp_path, extra, message):
    r = run_cli("study", "mesh", "--out", str(tmp_path / "m"), "--sizes", "0.12", "--seeds", "1", *extra)
    assert r.returncode == 2 and message in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_ldem_study_refinement_end_to_end(tmp_path):
    """A 0.04 m cube at L0 = 0.02 and 0.01, per bar and with l_c = 0.02 m,
    past the peak only (--set final_strain): the table compares each with
    L0 = 0.02 and the same field."""
    out = str(tmp_path / "ref")
    r = run_cli("study", "refinement", "--out", out, "--sizes", "0.04", "--L0s", "0.02,0.01", "--seeds", "2",
                "--corr-lengths", "0,0.02", "--set", "final_strain=0.002", "--threads", "1", "--no-progress")
    assert r.returncode == 0, r.stderr
    table = ldem.study.read_csv(os.path.join(out, "summary.csv"))
    assert [(t["module_m"], t["corr_length_m"]) for t in table] == [(0.02, 0), (0.02, 0.02), (0.01, 0), (0.01, 0.02)]
    assert all(t["seeds"] == 2 and t["separated"] == 0 for t in table) and table[0]["peak_vs_fine"] == 1.0
    ratio = table[2]["peak_stress_MPa_mean"] / table[0]["peak_stress_MPa_mean"]
    assert table[2]["peak_vs_fine"] == pytest.approx(ratio, rel=1e-4)
    assert os.path.exists(os.path.join(out, "refinement.png"))


def test_a_refinement_study_extends_the_rows_of_an_earlier_one(tmp_path):
    """A committed study keeps cases.csv, not its case folders: with
    --earlier, its cases are not run again (no folder is made for them),
    enter the tables as they were, and only the cases they lack are run."""
    args = ["study", "refinement", "--sizes", "0.04", "--L0s", "0.02,0.01", "--corr-lengths", "0",
            "--set", "final_strain=0.002", "--threads", "1", "--no-progress"]
    first = str(tmp_path / "first")
    assert run_cli(*args, "--out", first, "--seeds", "1").returncode == 0
    old = ldem.study.read_csv(os.path.join(first, "cases.csv"))
    out = str(tmp_path / "extended")
    r = run_cli(*args, "--out", out, "--seeds", "2", "--earlier", first)
    assert r.returncode == 0, r.stderr
    assert _case_folders(out) == sorted(n for n in _case_folders(out) if "_s2_" in n) and len(_case_folders(out)) == 2
    rows = ldem.study.read_csv(os.path.join(out, "cases.csv"))
    assert [(x["module_m"], x["seed"]) for x in rows] == [(0.02, 1), (0.02, 2), (0.01, 1), (0.01, 2)]
    assert [rows[0], rows[2]] == old    # kept as they were, wall times and commits included
    assert [t["seeds"] for t in ldem.study.read_csv(os.path.join(out, "summary.csv"))] == [2, 2]
    with open(os.path.join(out, "report.md")) as f:
        assert "2 cases are rows of an earlier run's cases.csv" in f.read()
    lost = run_cli(*args, "--out", str(tmp_path / "x"), "--earlier", str(tmp_path / "none"))
    assert lost.returncode == 2 and "--earlier" in lost.stderr and "no cases.csv in it" in lost.stderr
