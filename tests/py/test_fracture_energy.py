"""The lattice's own fracture energy (ldem.study.fracture_energy): the RILEM
beam's size at any module, the work of fracture of a known curve, the stop at
2 % of the peak, and a coarse beam run to its stop whose G_F is the work that
its energy balance says the bars and the damping took."""
import json
import math
import os
from types import SimpleNamespace

import numpy as np
import pytest

from ldem.study import concrete, fracture_energy as fe


@pytest.mark.direct
def test_the_beam_is_ten_modules_deep_and_never_less_than_50_mm():
    assert fe.depth(0.005) == pytest.approx(0.050)  # RILEM's beam in half size: the diagnosis's
    assert fe.depth(0.0025) == pytest.approx(0.050)  # 20 modules
    assert fe.depth(0.0102) == pytest.approx(0.102)  # Malvar-Warren's module: RILEM's full size
    assert fe.depth(0.0125) == pytest.approx(0.125)
    for L0 in (0.002, 0.003, 0.0045, 0.007, 0.0102):  # an even number of modules: the notch is whole ones
        n = fe.depth(L0) / L0
        assert abs(n - round(n)) < 1e-9 and round(n) % 2 == 0 and round(n) >= fe.MODULES


@pytest.mark.direct
def test_the_half_size_beam_at_5_mm_is_the_diagnosis_beam():
    d = fe.rilem_beam(concrete.lattice_material(37.5e9, 0.21, 1.14e-4, 143.24), 0.005, 1).description
    assert d["shape"]["size"] == pytest.approx([0.42, 0.05, 0.05])
    assert d["shape"]["notch"]["depth"] == pytest.approx(0.025) and d["shape"]["notch"]["at"] == pytest.approx(0.2125)
    left, right = d["groups"]["left"]["plane"]["x"], d["groups"]["right"]["plane"]["x"]
    assert right - left - 0.005 == pytest.approx(0.40)  # the span, 8 D: the planes lie half a module outside it


@pytest.mark.direct
def test_the_work_of_fracture_is_the_area_under_the_load_over_the_ligament():
    """A triangle of 1 kN over a deflection of 0.2 mm: W = 0.1 J over (D - a) b = 25 x 50 mm^2 = 80 N/m."""
    D = 0.05
    delta = np.array([0.0, 0.05e-3, 0.2e-3])
    curve = {"stress_MPa": np.array([0.0, 1e-3, 0.0]), "mean_strain": delta / D}
    assert fe.work_of_fracture(curve, D) == pytest.approx(0.1 / (0.025 * 0.05), rel=1e-12)


@pytest.mark.direct
def test_load_gone_stops_once_support_and_platen_carry_less_than_the_fraction():
    stop = fe.LoadGone(0.02)  # no window: the last record alone
    row = lambda t, support, platen: {"time_s": t, "stress_MPa": support, "stress_top_MPa": platen,  # noqa: E731
                                      "broken_bars": 1}
    assert stop(row(0.0, 0.0, 0.0))
    assert stop(row(1.0, 1.0, 1.0))
    assert stop(row(2.0, 0.01, 0.5))  # the platen still pushes
    assert stop(row(3.0, 0.01, 0.01)) is False


@pytest.mark.direct
def test_load_gone_waits_through_a_ringing_load_s_dips():
    """A load that rings about 0.3 of its peak dips below 2 % at single
    records; averaged over the window (1 s here) it is not gone until its
    mean is: 0.3 + 0.35 sin(...) over whole periods of 0.2 s."""
    stop = fe.LoadGone(0.02, window=1.0)
    assert stop({"time_s": 0.0, "stress_MPa": 1.0, "stress_top_MPa": 1.0, "broken_bars": 0})
    dips = 0
    for k in range(1, 400):
        t = k * 0.01
        load = 0.3 + 0.35 * math.sin(2 * math.pi * t / 0.2)
        dips += load < 0.02
        assert stop({"time_s": t, "stress_MPa": load, "stress_top_MPa": load, "broken_bars": 3})
    assert dips > 50
    t, going = 4.0, True
    while going:  # then the load is gone: stops one window later, not before
        t += 0.01
        going = stop({"time_s": t, "stress_MPa": 0.0, "stress_top_MPa": 0.0, "broken_bars": 3})
    assert 4.0 + 0.8 < t < 4.0 + 1.02


def _ringing_rows():
    """A load that rises to 1 in 1 s, rings about 0.3 (periods of 0.2 s) until 4 s, then is gone: a record every 10 ms."""
    rows = []
    for k in range(600):
        t = k * 0.01
        load = t if t <= 1 else 0.3 + 0.35 * math.sin(2 * math.pi * (t - 1) / 0.2) if t <= 4 else 0.0
        rows.append({"time_s": t, "stress_MPa": load, "stress_top_MPa": load, "broken_bars": 0 if t <= 1 else 3})
    return rows


@pytest.mark.direct
@pytest.mark.parametrize("restart", [50, 150, 300, 420])
def test_a_restarted_rilem_case_stops_on_the_row_a_straight_run_stops(restart):
    """RilemCase.run on a restart hands LoadGone the rows so far (the peak and
    its window): the case stops on the row a straight run stops on, the
    row about a window (two periods, 1 s here) after the load is gone at 4 s.
    A LoadGone that had not seen them would take a ringing 0.65 for the peak
    (restarted past the peak) and stop elsewhere."""
    rows = _ringing_rows()
    case = fe.RilemCase(concrete.lattice_material(30e9, 0.2, 1.0e-4, 100.0), 0.01, 1)

    def stops_on(observers, simulation, previous_rows):
        stop = observers[-1]
        return next(k for k in range(len(previous_rows), len(rows)) if stop(rows[k]) is False)
    case.test.run = stops_on
    one_period = SimpleNamespace(omega1=2 * math.pi / 0.5)
    straight = case.run(simulation=one_period)
    assert 4.0 + 0.8 < rows[straight]["time_s"] < 4.0 + 1.02
    assert case.run(simulation=one_period, previous_rows=rows[:restart]) == straight


def test_a_coarse_beam_runs_to_its_stop_and_its_g_f_is_the_drive_s_work_over_the_ligament(tmp_path, monkeypatch):
    """Four modules deep at L0 = 10 mm (MODULES and HALF_D made small, RATE large): the run
    ends below 2 % of its peak over two periods, by LoadGone, and the work of fracture read from
    the load cell's curve (the trapezoidal rule over its records) is the work
    the drive did, which the integrator sums step by step, over the ligament;
    that work is what the bars dissipated, the damping took and what is left
    stored and moving (the energy balance)."""
    monkeypatch.setattr(fe, "MODULES", 4)
    monkeypatch.setattr(fe, "HALF_D", 0.01)
    monkeypatch.setattr(fe, "RATE", 0.5)  # five times as fast: a test of seconds
    material = concrete.lattice_material(30e9, 0.2, 1.0e-4, 100.0)
    material["Gf_cv"] = 0.0  # no field: a smooth crack
    r = fe.measure({"material": material, "L0": 0.01}, 1, str(tmp_path), log=lambda s: None)
    row, D = r["seeds"][0], 0.04
    assert r["beam"]["D_m"] == pytest.approx(D)
    assert row["stop"] == "stopped"  # by LoadGone, not by the final strain
    case = os.path.join(tmp_path, "cases", "rilem_s1")
    last = fe.io.read_curve(os.path.join(case, "curve.csv"))
    window = last["time_s"] > last["time_s"][-1] - 2 * 2 * math.pi / fe.io.read_summary(
        os.path.join(case, "summary.json"))["omega1_rad_s"]
    assert np.mean(last["stress_MPa"][window]) < 0.02 * row["peak_kN"] * 1e-3 < last["stress_MPa"].max()
    ligament = D * D / 2
    work = last["external_work_J"][-1]
    assert row["G_F"] * ligament == pytest.approx(work, rel=0.01)
    assert row["dissipated_over_ligament"] * ligament == pytest.approx(last["fracture_J"][-1], rel=1e-9)
    took = last["fracture_J"][-1] + last["damping_J"][-1] + last["elastic_J"][-1] + last["kinetic_J"][-1]
    assert took == pytest.approx(work, rel=2e-3)
    assert row["stored_over_ligament"] * ligament == pytest.approx(last["elastic_J"][-1], rel=1e-9)
    assert r["ratio"] == pytest.approx(row["G_F"] / 100.0, rel=1e-12)
    json.dumps(r)  # the result is plain data
