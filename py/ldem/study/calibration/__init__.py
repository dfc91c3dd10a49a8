"""`ldem study calibration`: the lattice material of a concrete from what a
laboratory reports (E, nu, f_t, and G_F or f_c), by rounds of the virtual
direct tension prism (ldem.study.concrete.calibrate, which the beams and the
validation use as well; docs/calibration.md has the reasoning)."""
from __future__ import annotations

import json

from ... import io
from ..concrete import calibrate
from ..mc2010 import lab_values
from ..options import parameter_option, seed_count
from ..registry import Study, register


def add_arguments(c) -> None:
    lab = "; the concrete's, as the laboratory reports it (default: fib MC2010's from --fc)"
    parameter_option(c, "E", "--E", lab, default=None)
    parameter_option(c, "nu", "--nu", lab, default=None)
    c.add_argument("--ft", type=float, default=None, help="direct tensile strength [Pa] (default: fib MC2010's "
                                                          "f_ctm from --fc)")
    c.add_argument("--fc", type=float, default=None, help="mean compressive strength [Pa]: for what else is not "
                                                          "given (mc2010_from_compressive_strength)")
    c.add_argument("--GF", type=float, default=None, help="total fracture energy [N/m] (default: fib MC2010's)")
    parameter_option(c, "rho", "--rho", "; the concrete's")
    parameter_option(c, "L0", "--L0", "; the module of the structure to model", default=None, required=True)
    c.add_argument("--seeds", type=int, default=3, help="prisms per round (seeds 1..N)")
    # dest "result": a file, not a study folder of cases (an interrupted calibration keeps nothing)
    c.add_argument("--out", dest="result", default="", metavar="FILE", help="write the result here (JSON)")


def cmd_calibration(args) -> int:
    """Prints each prism and round, then the result (JSON), also written to --out.
    What is not given comes from fib MC2010 and --fc (the result's "sources")."""
    given, sources = lab_values(args.E, args.nu, args.ft, args.fc, args.GF)
    result = calibrate(given["E"], given["nu"], given["f_t"], args.fc, args.GF, args.rho, args.L0,
                       range(1, seed_count(args) + 1), lambda s: print(s, flush=True))
    result["sources"] = sources
    text = json.dumps(result, indent=1)
    print(text)
    if args.result:
        io.write_text(args.result, text + "\n")
    return 0


register(Study("calibration", "the lattice material of a concrete from what a laboratory reports (E, nu, f_t, "
                              "f_c or G_F; or f_c alone, with fib MC2010), by the virtual prism", add_arguments, cmd_calibration,
               "Runs the virtual direct tension prism (seeds 1..N, to its load loss) until its E and f_t are "
               "within 1 % of the targets (docs/calibration.md); use the parameters under [material] of a "
               "specimen file with the same L0."))
