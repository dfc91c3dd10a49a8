"""The `ldem` command line. `ldem cube` runs one cube tension test; its options
are generated from the fields of ldem.CubeTest, so defaults live in one place."""
from __future__ import annotations

import argparse
import dataclasses
import os
import sys

EXIT_BAD_INPUT = 2
EXIT_FAILED = 1


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error (no usage dump) and exit code 2."""

    def error(self, message):
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


def _option(name: str) -> str:
    return "--" + name.replace("_", "-")


def add_cube_options(p: argparse.ArgumentParser, skip=()) -> None:
    from .cube import CubeTest

    for f in dataclasses.fields(CubeTest):
        if f.name in skip:
            continue
        md = f.metadata
        unit = f" [{md['unit']}]" if md["unit"] else ""
        kw = {"choices": md["choices"]} if "choices" in md else {}
        p.add_argument(_option(f.name), dest=f.name, type=type(f.default), default=f.default,
                       metavar=f.name.upper() if not kw else None,
                       help=f"{md['help']}{unit} (default: {f.default})", **kw)


def cube_from_args(args) -> "CubeTest":
    from .cube import CubeTest

    return CubeTest(**{f.name: getattr(args, f.name) for f in dataclasses.fields(CubeTest)
                       if hasattr(args, f.name)})


def cmd_cube(args) -> int:
    test = cube_from_args(args)
    progress = False if args.no_progress else None
    result = test.run(out=args.out, progress=progress, plots=not args.no_plots)
    s = result.summary
    print(f"peak stress {s['peak_stress_MPa']:.4f} MPa at mean strain {s['strain_at_peak']:.4e}")
    print(f"U_num/U_min {s['U_ratio']:.3f} ({s['fracture_energy_J']:.4g} J / {s['min_fracture_energy_J']:.4g} J), "
          f"energy balance error {s['energy_balance_error']:.2e}, stop: {s['stop_reason']}, "
          f"{s['steps']} steps of {s['dt_s']:.3e} s, {s['wall_s']:.1f} s wall")
    if s["clamped_bars"]:
        print(f"{s['clamped_bars']} of {s['n_bars']} bars had eps_r < eps_p and were made perfectly brittle")
    print(f"wrote {args.out}/: curve.csv summary.json" + ("" if args.no_plots else
                                                           " curve.png energies.png cracks.png bars.vtu"))
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="ldem", description="Truss-like lattice DEM (Riera-Iturrioz) for fracture of concrete.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    c = sub.add_parser("cube", help="one cube tension test (peak stress, curve, crack picture)",
                       description="Pulls a concrete cube in tension until it splits; writes curve.csv, "
                                   "summary.json, curve.png, energies.png, cracks.png and bars.vtu into --out.",
                       formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    add_cube_options(c)
    c.add_argument("--out", default=os.path.join("out", "cube"), metavar="DIR", help="output folder")
    c.add_argument("--no-progress", action="store_true", help="no progress bar")
    c.add_argument("--no-plots", action="store_true", help="write curve.csv and summary.json only")
    c.set_defaults(func=cmd_cube)
    return p


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    from . import _core

    try:
        return args.func(args)
    except ValueError as e:  # bad input, found before anything runs
        print(f"ldem {args.command}: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except _core.InstabilityError as e:
        print(f"ldem {args.command}: failed: {e} (rows so far are kept in the output folder)", file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt:
        print(f"ldem {args.command}: interrupted (rows so far are kept in the output folder)", file=sys.stderr)
        return 130
