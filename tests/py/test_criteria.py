"""Criteria (a)-(c) of a quasi-static load (ldem.criteria), on synthetic curves whose answer is known."""
import math

import numpy as np
import pytest

from ldem import criteria

T = 1.0  # the drive's period


def snap_back(dt=0.01, ring=0.02):
    """A load rising to 1 at t = 5, flat to t = 8 with a ringing of amplitude `ring` at the period T,
    falling linearly to 0 between t = 8 and 8.5 (below 0.9 at 8.05, below 0.1 at 8.45), then ringing at
    0.3 of the peak dying over 1 T, and a ringing of `ring` after, to t = 20."""
    t = np.arange(0.0, 20.0 + dt / 2, dt)
    F = np.where(t < 5, t / 5, 1.0)
    F = np.where(t >= 8, np.clip(1 - (t - 8) / 0.5, 0, 1), F)
    F = F + ring * np.sin(2 * math.pi * t / T) * (t >= 5)
    F = F + 0.3 * np.exp(-(t - 8.5) / T) * np.sin(2 * math.pi * t / T) * (t >= 8.5)
    return t, F


def test_the_judged_stretches_are_the_peak_to_the_fall_and_from_three_periods_after_it():
    t, F = snap_back()
    w = criteria.judged(t, F, T)
    ip = int(np.argmax(F))
    i90 = ip + int(np.flatnonzero(F[ip:] < 0.9 * F[ip])[0])
    i10 = ip + int(np.flatnonzero(F[ip:] < 0.1 * F[ip])[0])
    # each judged record's running-mean window lies wholly in one of the two stretches
    first = (t - T / 2 >= t[ip]) & (t + T / 2 < t[i90])
    second = t - T / 2 >= t[i10] + 3 * T
    assert np.array_equal(w, first | second)
    assert first.sum() > 100 and second.sum() > 500  # both stretches are there
    assert not w[(t > t[i90] - T / 2) & (t < t[i10] + 3.5 * T)].any()  # neither the fall nor its ringing


def test_a_ringing_of_two_percent_reads_its_rms_and_the_fall_does_not_count():
    t, F = snap_back(ring=0.02)
    a = criteria.ringing(t, F, T)
    assert a == pytest.approx(0.02 / math.sqrt(2), rel=0.03)  # a sine's rms over the peak (1.02)
    judged_all = F - criteria.running_mean(t, F, T)
    after = (np.arange(len(F)) >= int(np.argmax(F))) & ~np.isnan(judged_all)
    whole = math.sqrt(np.mean(judged_all[after] ** 2)) / F.max()
    assert whole > 3 * a  # the fall and its free ringing, were they judged, would fail (a)


def test_a_run_without_a_fall_is_judged_from_its_peak_on():
    t = np.linspace(0, 10, 1001)
    F = np.minimum(t, 5.0)
    w = criteria.judged(t, F, T)
    ip = int(np.argmax(F))
    assert np.array_equal(w, (np.arange(len(t)) >= ip) & (t - T / 2 >= t[ip]))
    assert criteria.ringing(t, F, T) == pytest.approx(0.0, abs=1e-12)


def test_the_peak_comes_periods_after_the_smooth_start():
    t, F = snap_back(ring=0.0)
    assert criteria.periods_after_start(t, F, T, ramp_time=1.0) == pytest.approx(4.0, abs=0.02)


def test_the_rate_effect_is_judged_on_three_seeds_or_more_against_their_standard_error():
    one = criteria.rate_effect([1.05], [1.0], 0.01)
    assert one["verdict"] == "not judged" and one["mean"] == pytest.approx(0.05)
    assert criteria.rate_effect([1.005, 1.008, 1.002], [1, 1, 1], 0.01)["verdict"] == "pass"
    fail = criteria.rate_effect([1.05, 1.052, 1.048], [1, 1, 1], 0.01)
    assert fail["verdict"] == "fail" and fail["sem"] == pytest.approx(0.002 / math.sqrt(3), rel=1e-6)
    noisy = criteria.rate_effect([1.00, 1.06, 0.99], [1, 1, 1], 0.01)  # mean 1.67 %, two SE 4.4 %
    assert noisy["verdict"] == "within the seeds' noise"
    with pytest.raises(ValueError, match="2 runs at the rate against 3"):
        criteria.rate_effect([1, 1], [1, 1, 1], 0.01)


def test_the_energies_compared_are_at_the_load_loss_where_both_have_one_else_at_the_shorter_end():
    longer = {"loss": None, "strain": np.array([0.0, 1.0, 2.0]), "fracture": np.array([0.0, 1.0, 3.0])}
    shorter = {"loss": None, "strain": np.array([0.0, 1.5]), "fracture": np.array([0.0, 1.2])}
    assert criteria.energies_compared(longer, shorter) == pytest.approx((2.0, 1.2))  # at strain 1.5
    assert criteria.energies_compared(shorter, longer) == pytest.approx((1.2, 2.0))
    lost = dict(longer, loss=0.7)
    assert criteria.energies_compared(lost, dict(shorter, loss=0.5)) == (0.7, 0.5)
    assert criteria.energies_compared(lost, shorter) == pytest.approx((2.0, 1.2))  # one loss alone: the curves
