"""Is a run's recorded load quasi-static? The criteria of docs/model.md (section 5), on a
run's records (time t, load F) and its drive's period T:

  (a) the rms of the load's distance from its running mean over one period T,
      in % of the peak, judged only where the drive controls the specimen: from
      the peak to the start of its fall (the load first below 90 % of the peak),
      and again from 3 T after the fall ends (the load first below 10 %). A
      displacement drive cannot follow a fall faster than a period, and neither
      can a laboratory's: the fall and its free ringing are reported, not judged.
  (b) the peak and the fracture energy at a quarter of the rate, judged on the
      mean of at least three seeds against the standard error of that mean: one
      pair is not evidence (a step 1.25 % shorter moves a panel's energy as much
      as a quarter of the rate).
  (c) how many periods after the smooth start the peak comes.
"""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

FALL_FROM, FALL_TO = 0.9, 0.1  # the fall: from the load first below 90 % of the peak to first below 10 %
AFTER_FALL_PERIODS = 3.0       # the free ringing after the fall, not judged
MIN_SEEDS = 3                  # (b): fewer seeds judge nothing


def running_mean(t, F, T):
    """The mean of F over [t - T/2, t + T/2] (trapezoids on the records); NaN where the window leaves the curve."""
    t, F = np.asarray(t, float), np.asarray(F, float)
    m = np.full_like(F, np.nan)
    c = np.concatenate([[0.0], np.cumsum(0.5 * (F[1:] + F[:-1]) * np.diff(t))])
    inside = (t - T / 2 >= t[0]) & (t + T / 2 <= t[-1])
    m[inside] = (np.interp(t[inside] + T / 2, t, c) - np.interp(t[inside] - T / 2, t, c)) / T
    return m


def judged(t, F, T):
    """(a)'s records: those whose running-mean window [t - T/2, t + T/2] lies from the peak to the start
    of the fall, or from AFTER_FALL_PERIODS x T after its end on. With no fall, all from the peak on."""
    t, F = np.asarray(t, float), np.asarray(F, float)
    ip = int(np.argmax(F))
    after = np.arange(len(F)) >= ip
    start = np.flatnonzero(after & (F < FALL_FROM * F[ip]))
    end = np.flatnonzero(after & (F < FALL_TO * F[ip]))
    if not len(start):
        return after & (t - T / 2 >= t[ip])
    before = (t - T / 2 >= t[ip]) & (t + T / 2 < t[start[0]])
    if not len(end):
        return before
    return before | (t - T / 2 >= t[end[0]] + AFTER_FALL_PERIODS * T)


def rms_distance(t, F, T, records) -> float:
    """rms(F - its running mean over T) over the records (a mask) where the mean is defined, over the
    peak; NaN where none is."""
    F = np.asarray(F, float)
    d = F - running_mean(t, F, T)
    w = np.asarray(records, bool) & ~np.isnan(d)
    return math.sqrt(float(np.mean(d[w] ** 2))) / float(F.max()) if np.any(w) else float("nan")


def ringing(t, F, T) -> float:
    """(a): the rms distance over the judged records."""
    return rms_distance(t, F, T, judged(t, F, T))


def periods_after_start(t, F, T, ramp_time: float) -> float:
    """(c): (t_peak - t_ramp) / T."""
    return (float(np.asarray(t)[int(np.argmax(F))]) - ramp_time) / T


def energies_compared(rate: dict, quarter: dict) -> tuple:
    """(b)'s fracture energies of a run and its quarter-rate twin, each a dict of "loss" (the energy at
    its load loss, None without one), "strain" and "fracture" (its curve): at the load loss where both
    have one (a cube stopped there), else at the shorter curve's last mean strain."""
    if rate["loss"] is not None and quarter["loss"] is not None:
        return rate["loss"], quarter["loss"]
    until = min(rate["strain"][-1], quarter["strain"][-1])
    return tuple(float(np.interp(until, r["strain"], r["fracture"])) for r in (rate, quarter))


def rate_effect(at_rate: Sequence[float], at_quarter: Sequence[float], target: float) -> dict:
    """(b) over seeds: the mean of the relative changes x/q - 1 of each seed's pair, its standard error, and
    the verdict: 'pass' where |mean| <= target, 'fail' where |mean| exceeds it by more than two standard
    errors, 'within the seeds' noise' between, 'not judged' with fewer than MIN_SEEDS pairs."""
    if len(at_rate) != len(at_quarter):
        raise ValueError(f"{len(at_rate)} runs at the rate against {len(at_quarter)} at a quarter of it")
    d = np.asarray(at_rate, float) / np.asarray(at_quarter, float) - 1
    n = len(d)
    mean = float(np.mean(d)) if n else float("nan")
    sem = float(np.std(d, ddof=1) / math.sqrt(n)) if n > 1 else float("nan")
    if n < MIN_SEEDS:
        verdict = "not judged"
    elif abs(mean) <= target:
        verdict = "pass"
    elif abs(mean) - 2 * sem > target:
        verdict = "fail"
    else:
        verdict = "within the seeds' noise"
    return {"seeds": n, "mean": mean, "sem": sem, "target": target, "verdict": verdict}
