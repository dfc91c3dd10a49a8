"""The settings the reference study does not report (ldem.study.seed_settings):
each new parameter does what it says, the study runs on tiny cubes and its
table is its runs' means, and the fit recovers a setting it was given."""
import json
import math

import numpy as np
import pytest

import ldem
from ldem.study.cases import case_name
from ldem.study.seed_settings import fit as F, tables as T, variants as V
from ldem.study.registry import STUDIES


@pytest.mark.direct
def test_damping_omega_states_zeta_on_that_frequency():
    """D_f = 2 zeta damping_omega; 0 keeps D_f = 2 zeta omega_1."""
    own = ldem.CubeTest(size=0.04, zeta=0.02).simulation()
    assert own.damping_coefficient == pytest.approx(2 * 0.02 * own.omega1, rel=1e-12)
    other = ldem.CubeTest(size=0.04, zeta=0.02, damping_omega=1000.0).simulation()
    assert other.damping_coefficient == pytest.approx(40.0, rel=1e-12)
    assert other.omega1 == own.omega1  # the modal analysis is the specimen's, whatever zeta is stated on


@pytest.mark.direct
def test_a_lower_bound_of_G_f_holds_in_every_bar_and_keeps_the_mean():
    """Gf_min 4.5 N/m, above both families' brittle thresholds (4.0 and 3.4 N/m):
    no bar below it, none made perfectly brittle; the mean within 4 standard errors."""
    sim = ldem.CubeTest(size=0.12, Gf_min=4.5).simulation()
    g = np.asarray(sim.fracture_energy_field)
    assert g.min() >= 4.5
    assert g.mean() == pytest.approx(100.0, abs=4 * 100 / math.sqrt(g.size))
    assert np.asarray(ldem.CubeTest(size=0.12).simulation().fracture_energy_field).min() < 4.0
    with pytest.raises(ValueError, match="Gf_min"):
        ldem.CubeTest(size=0.04, Gf_min=100.0).params()


@pytest.mark.direct
def test_the_axial_mode_is_the_rayleigh_quotient_of_the_uniform_field():
    """omega_d = sqrt(3 E / rho) / H: at 0.96 m, 6,890 rad/s (c = 3,819 m/s)."""
    assert V.axial_omega(0.96) == pytest.approx(math.sqrt(3 * 3.5e10 / 2400) / 0.96, rel=1e-12)
    assert V.axial_omega(0.96) == pytest.approx(6890, rel=1e-3)


def test_the_registry_lists_the_study_and_every_variant_is_a_valid_cube():
    assert "seed-settings" in STUDIES
    pairs, tests = V.plan([s for s in V.SETTINGS if s != "base"], [0.12, 0.96], [1], threads=1)
    assert len(tests) == len(pairs)  # no two variants share their parameters
    for t in tests:
        t.params()


@pytest.mark.direct
def test_the_constant_drive_reaches_its_rate_by_an_eighth_of_eps_p():
    """Its smooth start lasts eps_p / (4 rate): the mean strain at its end, rate x ramp / 2, is eps_p / 8."""
    for rate in (0.01, 1.0):
        o = V.constant_rate(rate)(0.96)
        assert o["crack_pace"] == 1 and o["crack_secant"] == 0
        assert rate * o["ramp_time"] / 2 == pytest.approx(6.3e-5 / 8, rel=1e-5)


def test_the_study_runs_on_tiny_cubes_and_its_table_is_its_runs_means(tmp_path, cli):
    out = tmp_path / "ss"
    r = cli("study", "seed-settings", "--out", str(out), "--sizes", "0.06,0.08", "--seeds", "2",
            "--settings", "upper face", "--threads", "1")
    assert r.returncode == 0, r.stderr
    runs = ldem.study.read_csv(str(out / "runs.csv"))
    assert sorted({x["variant"] for x in runs}) == sorted(v.label for v in V.variants(["upper face"]))
    sens = {x["variant"]: x for x in ldem.study.read_csv(str(out / "sensitivity.csv"))}
    for label, row in sens.items():
        for size in (0.06, 0.08):
            peaks = [x["peak_stress_MPa"] for x in runs if x["variant"] == label and x["size_m"] == size]
            assert len(peaks) == 2 and row[f"peak_{size:g}"] == pytest.approx(np.mean(peaks), rel=1e-5)
        assert row["peak_ratio"] == pytest.approx(row["peak_0.08"] / row["peak_0.06"], rel=1e-5)
    fixed, base = sens["lateral DOFs fixed"], sens[V.SETTINGS["base"][0].label]
    assert fixed["peak_0.06"] != base["peak_0.06"]  # the setting reaches the run
    assert (out / "ratio.png").is_file() and "| Table 3 |" not in (out / "sensitivity.md").read_text()
    assert all(x["energy_balance_error"] < 1e-2 for x in runs)


def test_the_fit_recovers_a_lower_bound_it_was_given(tmp_path):
    """Targets made by the 0.06 and 0.08 m cubes at Gf_min 20 N/m (seeds 1-2):
    the fit on the grid 0-40 finds 20 again, within half a grid step."""
    truth = F.fit_variant({"Gf_min": 20.0})
    pairs = [(truth, V.variant_test(truth, s, k, 1)) for s in (0.06, 0.08) for k in (1, 2)]
    runs = T.run_rows(pairs, {case_name(t): dict(t.run().summary) for _, t in pairs})
    target = F.size_means(runs, truth.label)
    fit = F.run_fit({"Gf_min": [0.0, 10.0, 20.0, 30.0, 40.0]}, [1, 2], str(tmp_path / "fit"), target=target,
                     threads=1)
    assert abs(fit["best"]["Gf_min"] - 20.0) <= 5.0
    assert fit["J"] == pytest.approx(0.0, abs=1e-6)
    far = [p["J"] for p in fit["points"] if p["Gf_min"] in (0.0, 40.0)]
    assert min(far) > 1e-5  # the misfit sees the parameter: the grid's ends miss the targets


@pytest.mark.direct
def test_a_held_point_reads_choices_by_name_and_the_rate_by_each_cubes_periods():
    point = F.parse_point(["bottom_lateral=free", "rate_periods=3"])
    assert point == {"bottom_lateral": "free", "rate_periods": 3.0}
    o = F.fit_variant(point).overrides(0.04)
    omega1 = ldem.CubeTest(size=0.04).simulation().omega1
    assert o["bottom_lateral"] == "free" and o["crack_pace"] == 1.0
    assert o["strain_rate"] == pytest.approx(6.3e-5 * omega1 / (2 * math.pi * 3), rel=1e-5)  # rule (c), N = 3
    for bad in (["bottom_lateral=loose"], ["nosuch=1"], ["rate_periods"]):
        with pytest.raises(ValueError):
            F.parse_point(bad)


def test_the_proposal_runs_the_criterions_law_on_a_coarse_cube_against_the_fine_study(tmp_path, cli):
    """A fine 0.08 m study at a held point, then the proposal with modules of
    0.04 m: the law is the criterion's from the 0.04 m fine cubes (c_a = 0.1385
    E[U_num/U_min], eps_p = mean peak / E), the errors are coarse over fine."""
    hold = ["--hold", "rate_periods=3", "--hold", "bottom_lateral=free"]
    r = cli("study", "seed-settings", "--out", str(tmp_path / "fine"), "--study", "--sizes", "0.08", "--seeds", "2",
            "--loads", "uniform", "--threads", "1", *hold)
    assert r.returncode == 0, r.stderr
    r = cli("study", "seed-settings", "--out", str(tmp_path / "p"), "--proposal", str(tmp_path / "fine"),
            "--sizes", "0.08", "--module", "0.04", "--seeds", "2", *hold)
    assert r.returncode == 0, r.stderr
    p = json.loads((tmp_path / "p" / "proposal.json").read_text())
    assert p["law"]["c_a"] == pytest.approx(0.1385 * p["law"]["U_ratio_mean"], rel=1e-3)
    assert p["law"]["eps_p"] == pytest.approx(p["law"]["peak_stress_MPa_mean"] * 1e6 / 3.5e10, rel=1e-3)
    fine = [x for x in ldem.study.read_csv(str(tmp_path / "fine" / "cases.csv")) if x["load"] == "uniform"]
    assert p["fine"]["peak"] == pytest.approx(np.mean([x["peak_stress_MPa"] for x in fine]), rel=1e-5)
    assert p["errors"]["peak"] == pytest.approx(p["coarse"]["peak"] / p["fine"]["peak"] - 1, rel=1e-9)
    assert "Coarse against fine: peak" in (tmp_path / "p" / "proposal.md").read_text()


@pytest.mark.direct
def test_a_fixed_upper_face_holds_every_upper_node_laterally():
    """top_lateral fixed: every upper node's x and y are prescribed at zero
    (weight 0) beside its driven z; free: only z is."""
    for lateral, dims in (("fixed", {0, 1, 2}), ("free", {2})):
        sim = ldem.CubeTest(size=0.06, top_lateral=lateral).simulation()
        p = sim.prescribed_dofs()
        z0 = np.asarray(sim.lattice.z0)
        top = np.flatnonzero(np.isclose(z0, 0.06))
        node, dim, weight = (np.asarray(p[k]) for k in ("node", "dim", "weight"))
        at_top = np.isin(node, top)
        for n in top:
            assert set(dim[node == n]) == dims
        assert np.all(weight[at_top & (dim != 2)] == 0) and np.all(weight[at_top & (dim == 2)] == 1)


@pytest.mark.direct
def test_the_comparison_sets_each_column_beside_the_reference_and_table_3():
    def row(load, size, peak, u):
        return {"load": load, "size_m": size, "peak_stress_MPa_mean": peak, "strain_at_peak_mean": 1.5e-4,
                "U_ratio_mean": u, "U_ratio_cv": 0.05, "separation_strain_mean": "" if load != "uniform" else 0.06}
    ref = [row("uniform", 0.12, 2.0, 1.0), row("triangular", 0.12, 1.5, "")]
    new = [row("uniform", 0.12, 2.1, 2.3), row("triangular", 0.12, 1.6, "")]
    text = T.study_comparison(ref, new, 2.14, 2.5)
    assert "| 0.12 | 2.000 / 2.100, 2.450 | 1.500e-04 / 1.500e-04, 1.470e-04 | 1.000 / 2.300 |" in text
    assert "| 0.12 | 1.500 / 1.600 | 1.500e-04 / 1.500e-04 |" in text  # triangular: no Table 3, no energy
    assert text.rstrip().endswith("reference 2.140, these settings 2.500.")


def test_a_missing_reference_is_refused_before_any_case_runs(tmp_path, cli):
    r = cli("study", "seed-settings", "--out", str(tmp_path / "s"), "--study", "--sizes", "0.08", "--seeds", "1",
            "--reference", str(tmp_path / "nowhere"))
    assert r.returncode == 2 and "no summary.csv" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not (tmp_path / "s" / "cases").exists()
