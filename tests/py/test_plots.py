"""The figures of a run (ldem.plots), checked in the matplotlib objects the
plotting functions return: a run far past its peak has zoom panels that
hold the peak, each line says what it marks, a specimen's axes carry its own quantities, and the
energy figure shows each energy apart. Synthetic curves: no run needed."""

import numpy as np
import pytest

import ldem
from ldem import plots, report
from conftest import ROOT


def _separation_run(n: int = 2000):
    """A cube-like curve: elastic to a peak at strain 1e-4, softening to a load
    loss at 1e-3, then near zero load (and a late spike) out to separation at 0.06."""
    x = np.linspace(0.0, 0.06, n) ** 2 / 0.06  # rows dense at small strains, as a run's are
    stress = np.where(x < 1e-4, 2.0 * x / 1e-4, 2.0 * np.exp(-(x - 1e-4) / 2e-4))
    stress += 1.5 * np.exp(-((x - 0.035) / 5e-4) ** 2)  # the late spike of the whole run's axis
    work = np.cumsum(stress) * 1e-3
    curve = {"mean_strain": x, "stress_MPa": stress, "stress_top_MPa": stress, "external_work_J": work,
             "elastic_J": 0.1 * stress, "kinetic_J": 1e-4 * stress, "damping_J": 0.1 * work,
             "fracture_J": 0.9 * work - 0.1 * stress}
    summary = {"peak_stress_MPa": 2.0, "strain_at_peak": x[np.argmax(stress)], "energy_balance_error": 1e-4,
               "load_loss": {"mean_strain": 1e-3}, "separation": {"mean_strain": 0.06}}
    return curve, summary


def test_a_run_far_past_its_peak_has_a_zoom_panel_that_holds_the_peak():
    curve, summary = _separation_run()
    fig = plots.curve_plot(curve, summary, "cube")
    whole, zoom = fig.axes
    assert whole.get_xlim()[1] >= 0.06  # the whole run
    reach = plots.ZOOM * summary["strain_at_peak"]
    assert zoom.get_xlim() == pytest.approx((0.0, reach))  # a few times the strain at the peak
    lo, hi = zoom.get_ylim()
    assert lo < 0.0 and 2.0 < hi < 2.2  # the peak inside, not the late spike's limits
    peak = [line for line in zoom.get_lines() if line.get_marker() == "o"]
    assert peak and peak[0].get_xdata()[0] == pytest.approx(reach / plots.ZOOM)  # a quarter of the axis, not a sliver


def test_a_load_loss_a_few_times_past_the_run_s_end_still_zooms_on_the_peak():
    """The dog-bone's case (issue 40): the run ends at 3.5 x its load loss but
    50 x its strain at the peak; a zoom to a few times the load loss's strain
    still squeezed the peak. The zoom follows the peak, the load loss aside."""
    curve, summary = _separation_run()
    short = curve["mean_strain"] <= 5e-3
    curve = {k: v[short] for k, v in curve.items()}
    whole, zoom = plots.curve_plot(curve, summary, "cube").axes
    assert zoom.get_xlim() == pytest.approx((0.0, plots.ZOOM * summary["strain_at_peak"]))
    assert plots.ZOOM * summary["strain_at_peak"] < 0.1 * whole.get_xlim()[1]


def test_a_run_that_stops_near_its_peak_has_no_zoom_panel():
    curve, summary = _separation_run()
    near = curve["mean_strain"] <= 0.99 * plots.FAR * plots.ZOOM * summary["strain_at_peak"]
    curve = {k: v[near] for k, v in curve.items()}
    assert len(plots.curve_plot(curve, summary, "cube").axes) == 1
    each = plots.energy_plot(curve, summary).axes[1]
    assert each.get_xlim()[1] == pytest.approx(curve["mean_strain"][-1])  # the whole run: no zoom


def test_each_vertical_line_says_what_it_marks():
    """The load loss and the separation, in both panels where they fall inside,
    labelled with what they are (not a bare '10 % of the peak' on a strain)."""
    curve, summary = _separation_run()
    summary["parameters"] = {"stop_fraction": 0.2}
    whole, zoom = plots.curve_plot(curve, summary, "cube").axes
    marks = {line.get_label(): line.get_xdata()[0] for line in whole.get_lines() if line.get_linestyle() in (":", "--", "-.")
             and len(line.get_xdata()) == 2 and line.get_xdata()[0] == line.get_xdata()[1]}
    assert marks == {"load lost: averaged stress < 0.2 x the peak": 1e-3,
                     "separated: no intact bars join the loaded faces": 0.06}
    labels = [t.get_text() for t in whole.get_legend().get_texts()]
    assert set(marks) <= set(labels) and "support (reaction)" in labels and any(t.startswith("peak 2.000 MPa")
                                                                                 for t in labels)
    assert not any("10%" in t for ax in (whole, zoom) for t in [ax.get_title()] + [x.get_label() for x in ax.get_lines()])


def test_the_peak_is_labelled_in_the_specimen_s_own_unit():
    """An L-panel's load is in MN (its stress_label "load F [MN]"): the peak's legend says MN, with
    four significant digits (0.007728, not 0.008 MPa); a cube's stays in MPa."""
    curve, summary = _separation_run()
    summary["peak_stress_MPa"] = 0.0077283
    whole = plots.curve_plot(curve, summary, "panel", labels=("load-point displacement [-]", "load F [MN]")).axes[0]
    assert "peak 0.007728 MN at 0.000101" in [t.get_text() for t in whole.get_legend().get_texts()]
    summary["peak_stress_MPa"] = 2.3461
    whole = plots.curve_plot(curve, summary, "cube").axes[0]
    assert "peak 2.346 MPa at 0.000101" in [t.get_text() for t in whole.get_legend().get_texts()]


def test_the_energy_figure_shows_each_energy_over_the_zoom():
    curve, summary = _separation_run()
    fig = plots.energy_plot(curve, summary)
    whole, each = fig.axes
    assert whole.get_xlim()[1] >= 0.06
    assert each.get_yscale() == "log" and each.get_xlim() == pytest.approx((0.0, plots.ZOOM * 1e-4), rel=0.01)
    assert {line.get_label() for line in each.get_lines()} == {"external work", "elastic", "fracture",
                                                              "damping", "kinetic"}
    kinetic = next(line for line in each.get_lines() if line.get_label() == "kinetic")
    assert kinetic.get_ydata().max() > each.get_ylim()[0]  # above the axis' floor: seen


def test_a_beam_s_axes_are_its_own_quantities():
    """examples/beam_3pb_cmod.toml: F/(bD) against deflection/D, and against the CMOD in mm."""
    test = ldem.SpecimenTest.from_file(f"{ROOT}/examples/beam_3pb_cmod.toml")
    curve, summary = _separation_run(200)
    curve["cmod_m"] = curve["mean_strain"] * 1e-2
    fig = plots.curve_plot(curve, summary, test.describe(), plots.axis_labels(test))
    labels = [(ax.get_xlabel(), ax.get_ylabel()) for ax in fig.axes]
    assert labels[0] == ("deflection/D [-]", "F/(bD) [MPa]") and labels[-1] == ("CMOD [mm]", "F/(bD) [MPa]")
    for x, y in labels:
        assert "stress" not in y and "mean strain" not in x and "probe" not in x


def test_a_beam_s_cmod_panel_has_an_inset_on_its_peak():
    """The CMOD runs to 60 x its value at the peak: an inset to ZOOM x it."""
    test = ldem.SpecimenTest.from_file(f"{ROOT}/examples/beam_3pb_cmod.toml")
    curve, summary = _separation_run(200)
    curve["cmod_m"] = curve["mean_strain"] * 1e-2
    cmod = plots.curve_plot(curve, summary, test.describe(), plots.axis_labels(test)).axes[2]
    (inset,) = cmod.child_axes
    at_peak = 1e3 * curve["cmod_m"][np.argmax(curve["stress_MPa"])]  # mm
    assert inset.get_xlim() == pytest.approx((0.0, plots.ZOOM * at_peak)) and inset.get_ylim()[1] > 2.0


def test_a_cube_keeps_normal_stress_and_mean_strain():
    assert plots.axis_labels(ldem.CubeTest()) == (plots.STRAIN_LABEL, plots.STRESS_LABEL)


def test_the_crack_picture_draws_undamaged_bars_faint_and_thin_on_a_dense_slice(tmp_path):
    """40 modules across: lines thinner than on a 12-module cube; undamaged bars beneath, faint."""
    x = np.arange(41) * 0.01
    seg = np.array([[[a, 0.0], [a + 0.01, 0.0]] for a in x[:-1]])
    state = np.zeros(len(seg), np.uint8)
    state[20] = 2
    fig = plots.crack_figure_from_slice(seg, state, str(tmp_path / "cracks.png"))
    undamaged, damaged, broken = fig.axes[0].collections
    assert undamaged.get_alpha() < broken.get_alpha() == 1.0
    assert broken.get_linewidths()[0] < 1.8 * 0.6  # thinned as sqrt(12 / 40)
    assert (tmp_path / "cracks.png").stat().st_size > 0


@pytest.mark.parametrize("modules", [(81, 10), (12, 12), (40, 20)], ids=["slender beam", "cube", "panel"])
def test_the_crack_picture_s_legend_clears_the_axes_and_its_labels(tmp_path, modules):
    """The legend sits below the x label, apart from the axes, on a slender
    beam's flat slice as on a cube's (it overlapped the beam's label)."""
    nx, nz = modules
    seg = np.array([[[i * 0.01, k * 0.01], [(i + 1) * 0.01, k * 0.01]] for i in range(nx) for k in range(nz + 1)])
    fig = plots.crack_figure_from_slice(seg, np.zeros(len(seg), np.uint8), str(tmp_path / "cracks.png"))
    r = fig.canvas.get_renderer()
    legend = fig.legends[0].get_window_extent(r)
    for artist in (fig.axes[0], fig.axes[0].xaxis.label, *fig.axes[0].get_xticklabels()):
        box = artist.get_window_extent(r)
        assert not legend.overlaps(box) and legend.y1 <= box.y0, artist
    assert legend.y0 >= 0  # inside the figure


def _luminance(rgb) -> float:
    """Relative luminance (WCAG 2): 0 black, 1 white."""
    c = np.asarray(rgb[:3], float)
    c = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return float(c @ [0.2126, 0.7152, 0.0722])


def test_undamaged_bars_stand_out_on_white(tmp_path):
    """The faint undamaged colour, blended on white, has a contrast ratio of at
    least 2 (the study's pure cyan had 1.25: barely seen)."""
    seg = np.array([[[0.0, 0.0], [0.01, 0.0]], [[0.01, 0.0], [0.02, 0.0]]])
    fig = plots.crack_figure_from_slice(seg, np.zeros(2, np.uint8), str(tmp_path / "cracks.png"))
    undamaged = fig.axes[0].collections[0]
    a = undamaged.get_alpha()
    seen = a * np.asarray(undamaged.get_edgecolor()[0][:3]) + (1 - a)  # over white
    assert 1.05 / (_luminance(seen) + 0.05) >= 2.0


def test_the_study_s_curves_and_mean_curves_zoom_on_the_peak(tmp_path):
    """curves_LOAD and mean_curves_LOAD: a zoom to ZOOM x the strain at the
    peak, where the mean is drawn on its own grid (the whole run's 400 points,
    1.5e-4 apart over 0.06, would cut the peak at 1e-4 down to 1.56 MPa)."""
    curve, summary = _separation_run()
    weaker = dict(curve, stress_MPa=0.9 * curve["stress_MPa"])
    groups = {("uniform", 0.04): [curve, weaker], ("uniform", 0.08): [weaker]}
    reach = plots.ZOOM * summary["strain_at_peak"]
    fig = report.specimen_curves_figure(groups, "uniform", [0.04, 0.08], str(tmp_path / "curves.png"))
    whole, zoom = fig.axes[0], fig.axes[2]  # the first size: the whole run, its zoom below (2 x 2, by rows)
    assert whole.get_xlim()[1] >= 0.06 and zoom.get_xlim() == pytest.approx((0.0, reach))
    mean = next(line for line in zoom.get_lines() if line.get_label() == "mean of the 2 at equal strain")
    assert mean.get_ydata().max() == pytest.approx(0.95 * 2.0, rel=0.01)
    assert [t.get_text() for t in whole.get_legend().get_texts()] == [
        "specimen, seed 1", "specimen, seed 2", "mean of the 2 at equal strain"]
    fig = report.mean_curves_figure(groups, "uniform", [0.04, 0.08], str(tmp_path / "mean_curves.png"))
    whole, zoom = fig.axes
    assert zoom.get_xlim() == pytest.approx((0.0, reach))
    assert [line.get_ydata().max() for line in zoom.get_lines()] == pytest.approx([1.9, 1.8], rel=0.01)
    # The whole run on a log strain axis shows the peaks too (a linear grid to 0.06 would step over them).
    assert whole.get_xscale() == "log"
    assert [line.get_ydata().max() for line in whole.get_lines()] == pytest.approx([1.9, 1.8], rel=0.03)
    assert [t.get_text() for t in whole.get_legend().get_texts()] == ["0.04 m: mean of 2 specimens",
                                                                      "0.08 m: mean of 1 specimen"]
    near = curve["mean_strain"] <= 0.99 * plots.FAR * reach  # a run that stops near its peak: no zoom
    short = {k: [{c: v[near] for c, v in x.items()} for x in g] for k, g in groups.items()}
    assert len(report.specimen_curves_figure(short, "uniform", [0.04, 0.08], str(tmp_path / "c.png")).axes) == 2
    assert len(report.mean_curves_figure(short, "uniform", [0.04, 0.08], str(tmp_path / "m.png")).axes) == 1
