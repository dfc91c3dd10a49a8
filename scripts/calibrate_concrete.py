"""The lattice material of a concrete from what a laboratory reports
(doc/calibration.md): E, nu, the direct tensile strength f_t, f_c, and G_F if
measured (else fib MC2010's), at the module L0 of the structure to model.
Runs the virtual direct tension prism (three seeds, to separation) until its
E, f_t and G_F are within 1 % of the targets; prints the parameters and
writes them as JSON.

    /usr/bin/python3 scripts/calibrate_concrete.py --E 37e9 --nu 0.21 --ft 3.9e6 --L0 0.005 \\
        (--fc 42.3e6 | --GF 143) [--rho 2400] [--seeds 3] [--out material.json]

Use the parameters under [material] of a specimen file (ldem run) with the same L0.
"""
import argparse
import json
import sys

from ldem.study import concrete


def main(argv) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--E", type=float, required=True, help="Young's modulus [Pa]")
    ap.add_argument("--nu", type=float, required=True, help="Poisson's ratio")
    ap.add_argument("--ft", type=float, required=True, help="direct tensile strength [Pa]")
    ap.add_argument("--fc", type=float, default=None, help="mean compressive strength [Pa] (for G_F if not given)")
    ap.add_argument("--GF", type=float, default=None, help="total fracture energy [N/m] (default: fib MC2010's)")
    ap.add_argument("--rho", type=float, default=2400.0, help="density [kg/m^3]")
    ap.add_argument("--L0", type=float, required=True, help="module of the structure [m]")
    ap.add_argument("--seeds", type=int, default=3, help="prisms per round")
    ap.add_argument("--out", default="", help="write the result here (JSON)")
    a = ap.parse_args(argv)
    try:
        result = concrete.calibrate(a.E, a.nu, a.ft, a.fc, a.GF, a.rho, a.L0, range(1, a.seeds + 1),
                                    lambda s: print(s, flush=True))
    except ValueError as e:
        sys.exit(f"calibrate_concrete: {e}")
    text = json.dumps(result, indent=1)
    print(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
