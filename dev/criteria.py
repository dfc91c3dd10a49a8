#!/usr/bin/python3
"""Criteria (a)-(c) of a run, and of its quarter-rate twin (ldem.criteria), from
each run's curve.csv and summary.json; one markdown row:

    PYTHONPATH=build/python /usr/bin/python3 dev/criteria.py RUN [QUARTER_RATE_RUN] [--label NAME]

(a) over the judged records only (from the peak to the fall, and from 3 T after
it); with --fall also its value over the whole record after the peak, as
reported. (b) here is one pair: the table's verdict takes the mean of three
seeds or more (ldem.criteria.rate_effect). Energies at the load loss where both
runs have one, else at the end of the shorter curve."""
import argparse, csv, json, math

import numpy as np

from ldem import criteria


def load(out):
    rows = list(csv.DictReader(open(out + "/curve.csv")))
    s = json.load(open(out + "/summary.json"))
    col = lambda k: np.array([float(r[k]) for r in rows])
    T = 2 * math.pi / s.get("omega_d_rad_s", s["omega1_rad_s"])  # the drive's period where reported
    loss = (s.get("load_loss") or {}).get("fracture_energy_J")
    return {"t": col("time_s"), "F": col("stress_MPa"), "strain": col("mean_strain"), "fracture": col("fracture_J"),
            "loss": loss, "s": s, "T": T}


def whole(r):
    """(a) over every record after the peak, the fall included: reported, not judged."""
    return criteria.rms_distance(r["t"], r["F"], r["T"], np.arange(len(r["F"])) >= int(np.argmax(r["F"])))


def row(r, label, q=None, fall=False):
    cells = [label, f"{r['s']['peak_stress_MPa']:.5g}", f"{criteria.ringing(r['t'], r['F'], r['T']) * 100:.2f} %",
             f"{criteria.periods_after_start(r['t'], r['F'], r['T'], r['s']['ramp_time_s']):.1f}"]
    if fall:
        cells.append(f"{whole(r) * 100:.2f} %")
    if q:
        er, eq = criteria.energies_compared(r, q)
        cells += [f"{(r['F'].max() / q['F'].max() - 1) * 100:+.2f} %", f"{(er / eq - 1) * 100:+.2f} %",
                  f"{criteria.ringing(q['t'], q['F'], q['T']) * 100:.2f} %"]
    return "| " + " | ".join(cells + [f"{r['s']['steps']}", f"{r['s']['wall_s']:.0f} s"]) + " |"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run")
    ap.add_argument("quarter", nargs="?")
    ap.add_argument("--label", default="")
    ap.add_argument("--fall", action="store_true", help="also (a) over the whole record after the peak")
    a = ap.parse_args()
    print(row(load(a.run), a.label or a.run, load(a.quarter) if a.quarter else None, a.fall))


if __name__ == "__main__":
    main()
