#!/usr/bin/python3
"""Issue 41, item 3: is a run's recorded load quasi-static? From a run's
curve.csv and summary.json (the load-cell records, as written):

  (a) after the peak, the rms of the load's distance from its running mean over
      one period T of the mode the drive moves (T = 2 pi / omega_d, summary.json's
      omega_d_rad_s; omega1_rad_s for a run from before it was reported), in % of the peak;
  (b) given a second run of the same specimen at a quarter of the rate, the
      change of the peak and of the fracture energy: at the load loss where
      both runs have one (the cubes, stopped there), else at the same strain;
  (c) how many periods T after the smooth start the peak comes.

    /usr/bin/python3 dev/criteria.py RUN [QUARTER_RATE_RUN] [--label NAME] [--until STRAIN]

Prints one table row (markdown). (a) is taken over each run's own record
after its peak; (b)'s energy, where it is not at the load loss, at the end of
the shorter curve. `--until` ends both at that strain. `--fall` adds (a) split
at the load's fall from 90 % to 10 % of the peak: over the records whose mean's
window ends before the fall, and over those whose window starts after it.
"""
import argparse, csv, json, math
import numpy as np


def load(out):
    rows = list(csv.DictReader(open(out + "/curve.csv")))
    s = json.load(open(out + "/summary.json"))
    col = lambda k: np.array([float(r[k]) for r in rows])
    return {"t": col("time_s"), "F": col("stress_MPa"), "e": col("mean_strain"), "Uf": col("fracture_J"), "s": s}


def drive_period(r):
    """T = 2 pi / omega_d, the period that times the drive (its smooth start, rule (c))."""
    s = r["s"]
    return 2 * math.pi / s.get("omega_d_rad_s", s["omega1_rad_s"])


def running_mean(t, F, T):
    """The mean of F over [t - T/2, t + T/2] (trapezoids on the records), NaN where the window leaves the curve."""
    m = np.full_like(F, np.nan)
    c = np.concatenate([[0.0], np.cumsum(0.5 * (F[1:] + F[:-1]) * np.diff(t))])
    for i, ti in enumerate(t):
        a, b = ti - T / 2, ti + T / 2
        if a < t[0] or b > t[-1]:
            continue
        m[i] = (np.interp(b, t, c) - np.interp(a, t, c)) / T
    return m


def residual(r):
    """T, the peak's record, and F - its running mean over T with the records before the peak masked."""
    T = drive_period(r)
    ip = int(np.argmax(r["F"]))
    d = r["F"] - running_mean(r["t"], r["F"], T)
    d[:ip] = np.nan
    return T, ip, d


def rms_over_peak(r, d, window):
    """rms of d over the window's records where it is defined, over the peak (NaN: none)."""
    w = window & ~np.isnan(d)
    return math.sqrt(np.mean(d[w] ** 2)) / r["F"].max() if np.any(w) else float("nan")


def ringing(r, until):
    """(a): rms(F - mean over T) after the peak, over the peak, to strain `until` (None: the run's end)."""
    _, _, d = residual(r)
    return rms_over_peak(r, d, r["e"] < until if until else True)


def ringing_around_fall(r):
    """(a) before and after the fall from 90 % to 10 % of the peak: over the records whose mean's
    window ends before it, and those whose window starts after it (NaN where there is none)."""
    T, ip, d = residual(r)
    t, F = r["t"], r["F"]
    after = np.arange(len(F)) >= ip
    i90, i10 = (np.flatnonzero(after & (F < x * F[ip]))[:1] for x in (0.9, 0.1))
    if not (len(i90) and len(i10)):
        return rms_over_peak(r, d, after), float("nan")
    return rms_over_peak(r, d, t + T / 2 < t[i90[0]]), rms_over_peak(r, d, t - T / 2 > t[i10[0]])


def periods_after_start(r):
    """(c): (t_peak - t_ramp) / T."""
    T = drive_period(r)
    return (r["t"][int(np.argmax(r["F"]))] - r["s"]["ramp_time_s"]) / T


def energy_at(r, strain, at_loss):
    """The fracture energy at the load loss (at_loss: both runs have one), else at the strain."""
    return r["s"]["load_loss"]["fracture_energy_J"] if at_loss else float(np.interp(strain, r["e"], r["Uf"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run")
    ap.add_argument("quarter", nargs="?")
    ap.add_argument("--label", default="")
    ap.add_argument("--until", type=float, default=None)
    ap.add_argument("--fall", action="store_true")
    a = ap.parse_args()
    r = load(a.run)
    q = load(a.quarter) if a.quarter else None
    until = a.until or min(r["e"][-1], q["e"][-1] if q else r["e"][-1])
    peak = r["F"].max()
    cells = [a.label or a.run, f"{r['s']['peak_stress_MPa']:.5g}", f"{ringing(r, a.until) * 100:.2f} %",
             f"{periods_after_start(r):.1f}"]
    if a.fall:
        cells += [f"{x * 100:.2f} %" for x in ringing_around_fall(r)]
    if q:
        at_loss = bool(r["s"].get("load_loss") and q["s"].get("load_loss"))  # else both at the same strain
        cells += [f"{(peak / q['F'].max() - 1) * 100:+.2f} %",
                  f"{(energy_at(r, until, at_loss) / energy_at(q, until, at_loss) - 1) * 100:+.2f} %",
                  f"{ringing(q, a.until) * 100:.2f} %", f"{periods_after_start(q):.1f}"]
    cells += [f"{r['s']['steps']}", f"{r['s']['wall_s']:.0f} s"]
    print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
