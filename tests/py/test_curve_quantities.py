"""The whole-curve quantities of issue 39 item 2 (ldem.study.curve_quantities,
curve_report) on synthetic curves with known answers, and the clip gauge of
the Grégoire beams' whole-curve runs (ldem.study.beams.whole_curves)."""
import math

import numpy as np
import pytest

from ldem.study import curve_quantities as cq, curve_report
from ldem.study.beams import cases as beams, whole_curves

# A bilinear curve: P = 10 x up to the peak (x_p = 0.1 mm, 1 kN), then falling
# linearly to zero at 0.5 mm, recorded at points that miss every multiple of x_p.
XP, PP, END = 0.1, 1.0, 0.5


def bilinear(x):
    return np.where(x <= XP, PP * x / XP, PP * (END - x) / (END - XP))


def recorded(step=0.013, start=0.0):
    x = np.append(np.arange(start, 0.6, step), XP)
    x.sort()
    return x, bilinear(x)  # below zero still P = 10 x (as a beam zeroed under its weight)


def test_the_loads_past_the_peak_and_the_work_of_a_bilinear_curve():
    q = cq.quantities(recorded(), XP)
    assert q["peak_kN"] == pytest.approx(PP)
    assert q["x_at_peak"] == pytest.approx(XP)
    for m in cq.MULTIPLES:  # linear between recorded points: exact
        assert q[f"load_at_{m:g}"] == pytest.approx(PP * (END - m * XP) / (END - XP), rel=1e-12)
    # 1/2 P_p x_p, then the trapezoid from x_p to 4 x_p
    work = 0.5 * PP * XP + 0.5 * (PP + bilinear(np.array(4 * XP))) * 3 * XP
    assert q["work_J"] == pytest.approx(work, rel=1e-12)


def test_a_curve_that_starts_below_zero_is_read_from_zero():
    """A beam zeroed under its weight starts at negative x: the work counts from x = 0."""
    x, load = recorded(start=-0.05)
    assert x[0] < 0
    work = 0.5 * PP * XP + 0.5 * (PP + float(bilinear(np.array(4 * XP)))) * 3 * XP
    assert cq.work_to((x, load), 4 * XP) == pytest.approx(work, rel=1e-12)


def test_an_opening_that_steps_back_before_the_peak_is_read_past_the_peak():
    """A measured CMOD is noisy at its start: 1.5 x_p is first reached past the
    peak, not at a noisy early point; the work follows the recorded path."""
    x = np.array([0.0, 0.2, 0.0, XP, 0.3, 0.6])  # an early spike to 0.2 mm at no load, then back
    load = np.array([0.0, 0.0, 0.0, PP, 0.5, 0.0])
    assert cq.load_past_the_peak((x, load), 0.15) == pytest.approx(PP + (0.5 - PP) * 0.05 / 0.2)
    assert cq.work_to((x, load), 0.3) == pytest.approx(0.5 * PP * XP + 0.5 * (PP + 0.5) * 0.2)


def test_a_curve_that_ends_short_reads_nan():
    x, load = recorded()
    short = (x[x < 0.3], load[x < 0.3])
    q = cq.quantities(short, XP)
    assert not math.isnan(q["load_at_2"]) and math.isnan(q["load_at_4"]) and math.isnan(q["work_J"])


def test_the_table_leaves_a_blind_predictions_measured_column_empty():
    curves = [recorded(), (recorded()[0], 1.1 * recorded()[1])]
    blind = curve_report.table_lines(curve_report.summarize(curves, XP))
    rows = [[c.strip() for c in line.split("|")[1:-1]] for line in blind[2:]]
    assert len(rows) == 2 + len(cq.MULTIPLES) + 1
    assert all(r[2] == "" and r[3] == "" for r in rows)
    assert rows[0][1] == "1.050 (1.000-1.100)"  # the peak's mean (min-max) over the seeds
    measured = curve_report.table_lines(curve_report.summarize(curves, XP, recorded()))
    assert [c.strip() for c in measured[2].split("|")[1:-1]][2:] == ["1.000", "1.050"]


def test_the_clip_gauge_spans_whole_modules_across_the_notch():
    h, mid = 0.005, 0.0875
    for length in (0.005, 0.020, 0.070):
        g = beams.gauge_probe(mid, h, length)
        assert g["b"][0] - g["a"][0] == pytest.approx(length)
        assert g["a"][0] <= mid - 0.5 * h and g["b"][0] >= mid + 0.5 * h  # the notch's module inside
        assert round(g["a"][0] / h, 9).is_integer()  # on the face's node lines
    with pytest.raises(ValueError, match="whole number of modules"):
        beams.gauge_probe(mid, h, 0.012)


def test_a_whole_curve_beam_is_held_by_its_gauge_and_stops_past_four_times_the_opening():
    material = {"eps_p": 1.1e-4, "E": 37e9, "nu": 0.21, "Gf_mean": 143.0}
    t = whole_curves.WholeCurve(0.05, 0.5, material, 1, 0.0193)
    m = t.test.description["measure"]
    assert m["control"] == "gauge" and set(m["probes"]) == {"cmod", "gauge"}
    assert t.test.description["loading"]["opening_rate"] == pytest.approx(whole_curves.OPENING_RATE * 0.05)
    assert t.limit == pytest.approx(whole_curves.PAST * 4 * 0.0193e-3)
    stop = whole_curves.ToOpening(t.limit)
    assert stop({"gauge_m": 0.99 * t.limit}) and not stop({"gauge_m": t.limit})


def test_the_whole_curve_figure_is_a_palette_png(tmp_path):
    """Committed under results/ (a budget of binaries): 256 colours, still a picture."""
    from PIL import Image

    from conftest import picture

    path = curve_report.figure(str(tmp_path / "w.png"), "bilinear", [recorded()], XP, "x [mm]",
                               measured_peak=(PP, XP))
    assert Image.open(path).mode == "P"
    picture(path)
