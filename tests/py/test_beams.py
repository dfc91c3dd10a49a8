"""The notched-beam series (issue 13 items 5 and 6): the beams of the study
ldem.study.beams (`ldem study beams`) are the paper's geometry, and its
tables recover Bažant's law from points that follow it."""
import numpy as np
import pytest

from ldem.study.beams import cases as beams, tables as beam_tables


def test_bazant_s_law_is_recovered_from_points_on_it():
    se = beam_tables
    D = np.repeat([0.05, 0.1, 0.2], 6)
    B, D0 = 1.2, 0.08
    sigma = B * se.FT / 1e6 / np.sqrt(1 + D / D0)
    fit = se.bazant_fit(D, sigma)
    assert fit[0] == pytest.approx(B, rel=1e-9) and fit[2] == pytest.approx(D0, rel=1e-9)
    assert fit[1] < 1e-6 and fit[3] < 1e-9  # no scatter, no interval
    # Scatter widens the intervals and they hold the truth.
    rng = np.random.default_rng(1)
    B1, dB, D01, dD0 = se.bazant_fit(D, sigma * (1 + 0.03 * rng.standard_normal(D.size)))
    assert abs(B1 - B) < dB and abs(D01 - D0) < dD0 and dB > 0.01


@pytest.mark.parametrize("D, notch", [(0.05, 0.5), (0.1, 0.2), (0.1, 0.0)])
def test_the_beams_are_the_paper_s(D, notch):
    g = beams
    sim = g.beam(D, notch, 1e-4, 1).simulation()
    x = np.column_stack([sim.lattice.x0, sim.lattice.y0, sim.lattice.z0])
    mass = np.asarray(sim.lattice.mass)
    solid = x[mass > 0]
    assert np.allclose(solid.max(axis=0) - solid.min(axis=0), [3.5 * D, g.B, D])
    # Supports 2.5 D apart on the lower face, the platen on the upper face at mid-span.
    left, right, load = (x[np.asarray(sim.group(n))] for n in ("left", "right", "load"))
    assert np.allclose(right[:, 0] - 3.0 * D, 0) and np.allclose(left[:, 0] - 0.5 * D, 0)
    assert np.allclose(left[:, 2], 0) and np.allclose(load[:, 2], D)
    assert abs(load[:, 0].mean() - 1.75 * D) <= 0.5 * g.L0 + 1e-12
    # The notch: no module (centre node without mass) below notch x D at mid-span; none missing without one.
    mid = load[:, 0].mean()
    below = (np.abs(x[:, 0] - mid) < 0.4 * g.L0) & (x[:, 2] < (notch or 0.2) * D)
    assert below.sum() == round((notch or 0.2) * D / g.L0) * round(g.B / g.L0)
    assert np.all(mass[below] == 0) if notch > 0 else np.all(mass[below] > 0)
    # The CMOD probe reads the mouth across that module on the lower face.
    (name, a, b, dim), = sim.measures["probes"]
    assert name == "cmod" and dim == 0 and x[b, 0] - x[a, 0] == pytest.approx(g.L0)
    assert x[a, 2] == 0 and x[b, 2] == 0 and x[a, 0] < mid < x[b, 0]

