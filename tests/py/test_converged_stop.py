"""When a triangular cube is done (issue 27, item 5): stop_at "converged"
stops a specimen that does not separate once its fracture energy U has
converged (two doublings of the mean strain past the load loss in a row, each
with U growing by less than converged_growth and the load still lost), and
reports U there as U_final, never as U_num. The rule itself is tested on
synthetic sequences in tests/cpp/test_convergence.cpp; here a whole run."""
import numpy as np
import pytest

import ldem
from ldem import study

GROWTH = 0.05  # the 0.08 m cube is lumpy (a column of 4 modules breaks at once): 1 % takes it past 0.11
SEED = 5


@pytest.fixture(scope="module")
def run():
    # At the constant rate: paced, this cube loses its load later and its energy grows to the final strain of 0.5:
    # no convergence to test. Seed 5: seed 1 also hangs on to 0.5 at the default step (its load lost at 9.4e-3);
    # seeds 2-6 converge by 8.8e-3, seeds 4 and 5 with a balance below 1e-3.
    return ldem.CubeTest(size=0.08, load="triangular", stop_at="converged", converged_growth=GROWTH,
                         threads=1, crack_pace=1.0, seed=SEED).run()


def _rungs(curve, loss_step):
    """The rungs of the rule, read back from the curve's rows: the load-loss
    record, then the first record at or past twice the last rung's strain."""
    rows = np.nonzero(curve["step"] >= loss_step)[0]
    rungs = [rows[0]]
    for i in rows[1:]:
        if curve["mean_strain"][i] >= 2 * curve["mean_strain"][rungs[-1]]:
            rungs.append(i)
    return rungs


def test_a_triangular_cube_stops_once_its_energy_has_converged(run):
    s, c = run.summary, run.curve
    assert s["stop_reason"] == "converged" and not s["separated"]
    assert s["U_num_J"] is None  # never U_num: it did not separate
    conv = s["converged"]
    assert s["U_final_J"] == conv["fracture_energy_J"] == c["fracture_J"][-1]
    assert conv["mean_strain"] == c["mean_strain"][-1] < run.test.final_strain
    assert s["energy_balance_error"] < 1e-3
    rungs = _rungs(c, s["load_loss"]["step"])
    assert rungs[-1] == len(c["step"]) - 1  # it stopped on a rung
    u = c["fracture_J"][rungs]
    growth = (u[1:] - u[:-1]) / u[1:]
    assert growth[-1] < GROWTH and growth[-2] < GROWTH  # two quiet doublings in a row
    assert len(growth) == 2 or growth[-3] >= GROWTH  # and not earlier: the rung before them was loud


def test_the_size_effect_study_stops_triangular_cubes_past_their_peak_at_load_loss_or_when_converged():
    tests = study.size_effect_tests([0.12], 1, ["uniform", "triangular"])
    assert [(t.load, t.stop_at) for t in tests] == [("uniform", "separation"), ("triangular", "past_peak")]
    for stop in ("load_loss", "converged"):
        tests = study.size_effect_tests([0.12], 1, ["uniform", "triangular"], triangular_stop=stop)
        assert [(t.load, t.stop_at) for t in tests] == [("uniform", "separation"), ("triangular", stop)]
    with pytest.raises(ValueError, match="triangular_stop"):
        study.size_effect_tests([0.12], 1, ["triangular"], triangular_stop="separation")


def test_past_peak_stops_at_the_first_record_past_ten_times_the_strain_at_the_peak(run):
    """The same cube as the converged run, stopped past its peak: the same records
    up to there (the stop changes nothing else)."""
    r = ldem.CubeTest(size=0.08, load="triangular", stop_at="past_peak", threads=1, crack_pace=1.0, seed=SEED).run()
    s, c = r.summary, r.curve
    assert s["stop_reason"] == "past_peak" and not s["separated"] and s["U_num_J"] is None
    ten = 10 * s["strain_at_peak"]
    assert c["mean_strain"][-1] >= ten > c["mean_strain"][-2]
    assert s["fracture_energy_J"] == c["fracture_J"][-1]
    n = len(c["step"])
    assert len(run.curve["step"]) > n
    for key in ("step", "mean_strain", "stress_MPa", "fracture_J"):
        assert np.array_equal(c[key], run.curve[key][:n]), key


def test_the_report_names_each_stop_with_its_number_and_reads_older_runs():
    from ldem.markdown import stop_rule
    p = {"load": "triangular", "final_strain": 0.5, "stop_at": "past_peak", "peak_stop_strain_ratio": 12.0}
    assert stop_rule(p) == "triangular: 12 x the mean strain at the peak, or mean strain 0.5"
    old = {"load": "uniform", "final_strain": 0.5, "stop_at": "separation"}  # a run from before past_peak
    assert stop_rule(old).startswith("uniform: separation (no chain")


def test_the_size_effect_study_damps_the_tails_of_its_larger_cubes_relative_to_their_mean():
    tests = study.size_effect_tests([0.48, 0.72, 0.96], 1, ["uniform", "triangular"])
    assert [t.tail_damping for t in tests] == ["absolute", "relative", "relative"] * 2
    assert [study.case_name(t) for t in tests[:2]] == ["uniform_0.48m_s1", "uniform_0.72m_s1_tail_dampingrelative"]
    tests = study.size_effect_tests([0.48, 0.96], 1, ["uniform"], tail_damping="absolute")  # --set
    assert [t.tail_damping for t in tests] == ["absolute", "absolute"]
    tests = study.size_effect_tests([0.48], 1, ["uniform"], tail_damping="relative")
    assert tests[0].tail_damping == "relative"


def test_the_size_effect_study_paces_its_drive_near_the_peak_as_the_cube_does_and_set_gives_the_constant_rate():
    """Every case of the study slows its drive to a sixteenth near the peak and
    while a crack runs, as ldem cube does by default (cube.CUBE_DEFAULTS), and
    specimens from a file do not (the core's default); --set crack_pace=1 is the
    constant rate, and its case folder names it."""
    tests = study.size_effect_tests([0.12, 0.96], 1, ["uniform", "triangular"])
    assert {(t.crack_pace, t.crack_secant, t.crack_kinetic) for t in tests} == {(0.0625, 0.9, 0.01)}
    cube = ldem.CubeTest()
    assert (cube.crack_pace, cube.crack_secant, cube.crack_kinetic) == (0.0625, 0.9, 0.01)
    table = {p["name"]: p["default"] for p in ldem.cube.PARAMETERS}
    assert (table["crack_pace"], table["crack_secant"], table["crack_kinetic"]) == (1.0, 0.0, 1e-3)
    tests = study.size_effect_tests([0.12], 1, ["uniform"], crack_pace=1.0)
    assert (tests[0].crack_pace, study.case_name(tests[0])) == (1.0, "uniform_0.12m_s1_crack_pace1")


def test_the_study_hands_a_large_triangular_cube_to_the_tail_drive_below_a_tenth_of_its_peak():
    """From 0.72 m on (the relative tail) a triangular case that stops past its
    peak loses its load at stop_fraction 0.1, and the report says so; the other
    cases, and a triangular stop at the load loss, keep CubeTest's 0.01."""
    from ldem.markdown import loss_fraction_words

    tests = study.size_effect_tests([0.48, 0.72, 0.96], 1, ["uniform", "triangular"])
    assert [t.stop_fraction for t in tests] == [0.01, 0.01, 0.01, 0.01, 0.1, 0.1]
    assert [t.stop_fraction for t in study.size_effect_tests([0.96], 1, ["triangular"], "load_loss")] == [0.01]
    words = loss_fraction_words([t.parameters() for t in tests])
    assert words == "0.01 x peak (0.1 x peak for the triangular cubes of 0.72, 0.96 m)"


def test_the_report_names_the_tail_damping_and_the_sizes_that_had_it_and_reads_older_runs():
    from ldem.markdown import damping_words

    small, large = (ldem.CubeTest(size=s, tail_damping=d).parameters()
                    for s, d in ((0.48, "absolute"), (0.96, "relative")))
    assert damping_words([large]).endswith("on, of each node's velocity less its mean over 2 fundamental periods "
                                           "(tail_damping relative)")
    assert "; from the load loss on at 0.96 m, of each node's" in damping_words([small, large, large])
    old = {k: v for k, v in small.items() if k not in ("tail_damping", "damping_filter_periods")}
    assert damping_words([old, old]) == "zeta = 0.02 on omega_1 (D_f = 2 zeta omega_1, mass-proportional)"
