"""The figures of a run (ldem.plots), checked in the matplotlib objects the
plotting functions return: a run to separation has zoom panels over its
pre-peak and softening, a specimen's axes carry its own quantities, and the
energy figure shows each energy apart. Synthetic curves: no run needed."""

import numpy as np
import pytest

import ldem
from ldem import plots
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


def test_a_run_to_separation_has_a_zoom_panel_over_its_peak_and_softening():
    curve, summary = _separation_run()
    fig = plots.curve_plot(curve, summary, "cube")
    whole, zoom = fig.axes
    assert whole.get_xlim()[1] >= 0.06  # the whole run
    assert zoom.get_xlim() == pytest.approx((0.0, plots.ZOOM * 1e-3))  # a few times the strain at load loss
    lo, hi = zoom.get_ylim()
    assert lo < 0.0 and 2.0 < hi < 2.2  # the peak inside, not the late spike's limits
    peak = [line for line in zoom.get_lines() if line.get_marker() == "o"]
    assert peak and zoom.get_xlim()[0] < peak[0].get_xdata()[0] < zoom.get_xlim()[1]


def test_a_run_that_stops_near_its_softening_has_no_zoom_panel():
    curve, summary = _separation_run()
    short = curve["mean_strain"] <= 1.5e-3  # ZOOM x the load loss (and x where the stress is 10 % of the peak) beyond
    curve = {k: v[short] for k, v in curve.items()}
    assert len(plots.curve_plot(curve, summary, "cube").axes) == 1
    summary.pop("load_loss")
    assert len(plots.curve_plot(curve, summary, "cube").axes) == 1


@pytest.mark.parametrize("loss", [None, 0.03], ids=["no load loss", "late load loss"])
def test_a_late_load_loss_zooms_to_where_the_stress_fell_below_a_tenth_of_the_peak(loss):
    """A triangular cube hinges: its load loss comes late (ZOOM x it beyond the
    run) or never, yet its whole axis hides the peak. The zoom then ends at
    ZOOM x the first strain past the peak with the stress below 10 % of it."""
    curve, summary = _separation_run()
    summary["load_loss"] = {"mean_strain": loss} if loss else None
    x, y = curve["mean_strain"], curve["stress_MPa"]
    softened = x[(x > 1e-4) & (y < 0.1 * y.max())][0]
    assert softened == pytest.approx(1e-4 + 2e-4 * np.log(10), rel=0.02)  # 2 exp(-(x - 1e-4)/2e-4) = 0.2
    whole, zoom = plots.curve_plot(curve, summary, "cube").axes
    assert zoom.get_xlim() == pytest.approx((0.0, plots.ZOOM * softened))
    assert "10% of the peak" in zoom.get_title()
    each = plots.energy_plot(curve, summary).axes[1]
    assert each.get_xlim() == pytest.approx((0.0, plots.ZOOM * softened))


def test_the_energy_figure_shows_each_energy_over_the_zoom():
    curve, summary = _separation_run()
    fig = plots.energy_plot(curve, summary)
    whole, each = fig.axes
    assert whole.get_xlim()[1] >= 0.06
    assert each.get_yscale() == "log" and each.get_xlim() == pytest.approx((0.0, plots.ZOOM * 1e-3))
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
