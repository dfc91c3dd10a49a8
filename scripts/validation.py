"""Blind predictions of laboratory tests (issue 28, item 5; ldem.study.validation):
the concrete calibrated by the procedure of doc/calibration.md at the specimen
file's module, six random specimens each stopped past their peak.

    /usr/bin/python3 scripts/validation.py calibrate NAME     # OUT/material.json only
    /usr/bin/python3 scripts/validation.py predict NAME [--seeds 6] [--jobs 2]

NAME: l_panel (Winkler et al. 2001) or eccentric_notch_beam (García-Álvarez et
al. 2012); OUT: results/validation/NAME (--out). Finished cases are not run again.
"""
import argparse
import os
import sys

from ldem.study import validation

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main(argv) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["calibrate", "predict"])
    ap.add_argument("name", choices=sorted(validation.SPECIMENS))
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--jobs", type=int, default=1, help="runs at a time, one thread each")
    ap.add_argument("--out", default="")
    a = ap.parse_args(argv)
    out = a.out or os.path.join(ROOT, "results", "validation", a.name)
    log = lambda s: print(s, flush=True)  # noqa: E731
    if a.command == "calibrate":
        validation.material(ROOT, a.name, out, log)
    else:
        print(validation.predict(ROOT, a.name, out, a.seeds, a.jobs, log))


if __name__ == "__main__":
    main(sys.argv[1:])
