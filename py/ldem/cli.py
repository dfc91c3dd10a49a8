"""The `ldem` command line. `ldem cube` runs one cube tension test; its options
are generated from the fields of ldem.CubeTest, so defaults live in one place."""
from __future__ import annotations

import argparse
import dataclasses
import os
import signal
import sys


from .bench import cmd_bench
from .rerun import RERUN_KEYS, cmd_rerun  # noqa: F401 (RERUN_KEYS: what a rerun compares)
from .helptext import HelpFormatter, add_output_flags

EXIT_BAD_INPUT, EXIT_FAILED = 2, 1


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error (no usage dump) and exit code 2."""

    def error(self, message):
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n")


def _option(name: str) -> str:
    return "--" + name.replace("_", "-")


def add_cube_options(p: argparse.ArgumentParser, skip=()) -> None:
    """One option per field of ldem.CubeTest (that is, per parameter of
    pkg/ldem/Parameters.hpp), grouped as declared there."""
    from .cube import CubeTest

    groups = {}
    for f in dataclasses.fields(CubeTest):
        if f.name in skip:
            continue
        md = f.metadata
        group = groups.get(md["group"]) or groups.setdefault(md["group"], p.add_argument_group(md["group"]))
        unit = f" [{md['unit']}]" if md["unit"] else ""
        kw = {"choices": md["choices"]} if "choices" in md else {}
        domain = "" if kw else f"; {md['domain']}"
        group.add_argument(_option(f.name), dest=f.name, type=type(f.default), default=f.default,
                           metavar=f.name.upper() if not kw else None,
                           help=f"{md['help']}{unit}{domain}".replace("%", "%%"), **kw)  # the formatter adds (default: ...)


def cube_from_args(args) -> "CubeTest":
    from .cube import CubeTest

    return CubeTest(**{f.name: getattr(args, f.name) for f in dataclasses.fields(CubeTest)
                       if hasattr(args, f.name)})


def cmd_cube(args) -> int:
    if args.restart and finished(args.restart):
        return 0
    if args.restart:  # the test of the checkpoint, in its folder
        from .io import read_checkpoint

        try:
            _, parameters, _ = read_checkpoint(os.path.join(args.restart, "checkpoint.npz"))
        except OSError as e:
            raise ValueError(f"cannot restart from {args.restart}: {e.strerror or e}") from None
        args.out = args.restart
        for name, value in parameters.items():
            setattr(args, name, value)
    test = cube_from_args(args)
    test.params()  # every input checked before the warnings below and before any output
    cores = os.cpu_count() or 1
    if test.threads > cores:
        print(f"ldem cube: warning: --threads {test.threads} is more than the {cores} cores: using {cores}",
              file=sys.stderr)
    progress = False if args.no_progress else None
    from .runner import run_cube

    result = run_cube(test, out=args.out, progress=progress, plots=not args.no_plots,
                      figure_format=args.figure_format, snapshots=_snapshots(args),
                      checkpoint_every=args.checkpoint_every, restart=bool(args.restart),
                      checkpoint_seconds=_checkpoint_seconds(args))
    return report_run(result, args, edge=test.load == "triangular")


def _checkpoint_seconds(args) -> float:
    """--checkpoint-minutes in s; none under mpirun (checkpoints of a split lattice are not supported)."""
    from . import parallel

    return 60.0 * args.checkpoint_minutes if parallel.ranks() == 1 else 0.0


def finished(out: str) -> bool:
    """out holds a finished run (summary.json says done): --restart says so and runs nothing."""
    from .io import read_summary

    try:
        done = read_summary(os.path.join(out, "summary.json")).get("status") == "done"
    except (OSError, ValueError):
        return False
    if done:
        print(f"{out} is a finished run (summary.json: done): nothing to continue")
    return done


def _snapshots(args) -> list:
    try:
        return [float(x) for x in args.snapshots.split(",") if x.strip()]
    except ValueError:
        raise ValueError(f"--snapshots takes comma-separated mean strains (got '{args.snapshots}')") from None


def report_run(result, args, edge: bool = False) -> int:
    """The lines a run prints (ldem cube, ldem run); exit 1 on an energy error."""
    s, test = result.summary, result.test
    print(f"peak stress {s['peak_stress_MPa']:.4f} MPa at mean strain {s['strain_at_peak']:.4e}"
          + (f" (most-pulled edge {s['edge_strain_at_peak']:.4e})" if edge else ""))
    loss, sep = s["load_loss"], s["separation"]
    if loss:
        print(f"load lost at mean strain {loss['mean_strain']:.4e}: fracture energy {loss['fracture_energy_J']:.4g} J "
              f"({loss['fracture_energy_J'] / s['min_fracture_energy_J']:.3f} U_min)")
    if sep:
        cut = "" if s["U_mincut_J"] is None else \
            f", cheapest cut {s['U_mincut_J'] / s['min_fracture_energy_J']:.3f} U_min"
        print(f"separated at mean strain {sep['mean_strain']:.4e}: U_num {s['U_num_J']:.4g} J, "
              f"U_num/U_min {s['U_ratio']:.3f} (U_min {s['min_fracture_energy_J']:.4g} J{cut})")
    elif test.stop_at == "separation":
        stop = "the final strain" if s["stop_reason"] == "final_strain" else "an observer's request"
        print(f"stopped at {stop} (mean strain {result.curve['mean_strain'][-1]:.4e}) before separation: the "
              f"fracture energy at the end, {s['fracture_energy_J']:.4g} J, is not U_num")
    ranks = f" on {s['mpi_ranks']} MPI ranks" if s.get("mpi_ranks", 1) > 1 else ""
    print(f"energy balance error {s['energy_balance_error']:.2e}, {s['steps']} steps of {s['dt_s']:.3e} s, "
          f"{s['wall_s']:.1f} s wall{ranks}")
    if s["clamped_bars"]:
        print(f"{s['clamped_bars']} of {s['n_bars']} bars had eps_r < eps_p and were made perfectly brittle")
    if (q := s["quasi_static"])["flagged"]:
        print(f"ldem {args.command}: warning: not quasi-static: the kinetic energy at the peak is "
              f"{q['kinetic_over_work_at_peak']:.1%} of the external work (above {q['kinetic_limit']:.0%}): the peak "
              f"depends on the strain rate; lower it (summary.json: quasi_static)", file=sys.stderr)
    f = args.figure_format
    print(f"wrote {args.out}/: curve.csv summary.json"
          + ("" if args.no_plots else f" curve.{f} energies.{f} cracks.{f} bars.pvd crack.pvd"))
    if s["energy_error"]:
        print(f"ldem {args.command}: failed: energy balance error {s['energy_balance_error']:.2e} is above the tolerance "
              f"{test.energy_tolerance:g}: energy was created or lost by the integration; the results are "
              f"not trustworthy (summary.json says energy_error)", file=sys.stderr)
        return EXIT_FAILED
    return 0


def cmd_run(args) -> int:
    from .cube import settings
    from .runner import run_cube
    from .specimen import SpecimenTest

    overrides = settings(args.set)
    if args.threads is not None:
        overrides["threads"] = args.threads
    test = SpecimenTest.from_file(args.file, overrides)
    args.out = args.out or os.path.join("out", os.path.splitext(os.path.basename(args.file))[0])
    if args.restart and finished(args.out):
        return 0
    result = run_cube(test, out=args.out, progress=False if args.no_progress else None, plots=not args.no_plots,
                      figure_format=args.figure_format, snapshots=_snapshots(args),
                      checkpoint_every=args.checkpoint_every, restart=args.restart,
                      checkpoint_seconds=_checkpoint_seconds(args))
    return report_run(result, args)


def _output_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--checkpoint-every", type=int, default=0, metavar="ROWS",
                   help="write checkpoint.npz (the whole state) every ROWS curve rows; 0: never")
    p.add_argument("--checkpoint-minutes", type=float, default=10.0, metavar="M",
                   help="also every M minutes of wall time, and at SIGTERM or Ctrl-C (0: not on the clock); "
                        "removed when the run is finished")
    p.add_argument("--snapshots", default="", metavar="STRAINS",
                   help="mean strains at which to write bars_NNNN.vtu and crack_NNNN.vtu for ParaView "
                        "(comma-separated; the end state is always written)")
    p.add_argument("--no-plots", action="store_true", help="write curve.csv and summary.json only")
    add_output_flags(p)


def build_parser() -> argparse.ArgumentParser:
    from . import __version__
    from .cube import provenance

    p = _Parser(prog="ldem", description="Truss-like lattice DEM (Riera-Iturrioz) for fracture of concrete.")
    commit = provenance()["git_commit"]
    p.add_argument("--version", action="version", version=f"ldem {__version__}" + (f" (git {commit})" if commit else ""))
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    c = sub.add_parser("cube", help="one cube tension test (peak stress, curve, crack picture)",
                       description="Pulls a concrete cube in tension until it separates in two pieces; writes curve.csv, "
                                   "summary.json, curve.png, energies.png, cracks.png and the ParaView series "
                                   "(bars.pvd, crack.pvd) into --out.",
                       formatter_class=HelpFormatter)
    add_cube_options(c)
    c.add_argument("--out", default=os.path.join("out", "cube"), metavar="DIR", help="output folder")
    _output_options(c)
    c.add_argument("--restart", default=None, metavar="DIR",
                   help="continue the run of DIR/checkpoint.npz in DIR, with its parameters, bit for bit as if it "
                        "had never stopped (other parameters are ignored)")
    c.set_defaults(func=cmd_cube)

    f = sub.add_parser("run", help="any specimen from a TOML file (examples/: beams, cylinders, dog-bones, cubes)",
                       description="Runs the specimen FILE describes (README 'Specimens from a file'); writes what "
                                   "ldem cube writes into --out. A bad file: one line naming the key and its line, "
                                   "exit 2.", formatter_class=HelpFormatter)
    f.add_argument("file", metavar="FILE", help="the specimen's TOML file")
    f.add_argument("--out", default=None, metavar="DIR", help="output folder (default: out/FILE's name)")
    f.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a material, loading or run parameter over the file's (repeatable), e.g. --set seed=2")
    f.add_argument("--threads", type=int, default=None, metavar="T",
                   help="OpenMP threads, over the file's run.threads (0: OMP_NUM_THREADS if set, else all cores)")
    f.add_argument("--restart", action="store_true",
                   help="continue the run of --out's checkpoint.npz, bit for bit (the same file and --set)")
    _output_options(f)
    f.set_defaults(func=cmd_run)

    b = sub.add_parser("bench", help="time the time step of an N^3 cube (one line of JSON)",
                       description="Builds an N^3 cube (default material), runs S steps of uniform loading R "
                                   "times and prints modules, bars, nodes, steps, threads, ns_per_bar_step "
                                   "(median of the R repetitions), peak_rss_bytes and bytes_per_bar.",
                       formatter_class=HelpFormatter)
    b.add_argument("--modules", type=int, default=24, metavar="N", help="modules per side")
    b.add_argument("--steps", type=int, default=200, metavar="S", help="steps per repetition")
    b.add_argument("--threads", type=int, default=0, metavar="T", help="OpenMP threads (0: all cores)")
    b.add_argument("--repeats", type=int, default=5, metavar="R", help="repetitions (the median is reported)")
    b.add_argument("--damaged", action="store_true",
                   help="then pull the cube to load loss and time the same steps from there (damaged_* fields)")
    b.set_defaults(func=cmd_bench)

    r = sub.add_parser("rerun", help="run a result's folder again from its summary.json and compare",
                       description="Reads DIR/summary.json (its parameters and provenance), runs the same test into "
                                   "--out (default DIR/rerun) and compares the curve and the summary's numbers: exit 0 "
                                   "if they are identical, 1 if not.",
                       formatter_class=HelpFormatter)
    r.add_argument("dir", metavar="DIR", help="a folder written by ldem cube (or a study's case folder)")
    r.add_argument("--out", default=None, metavar="OUT", help="where the rerun writes (default: DIR/rerun)")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    r.set_defaults(func=cmd_rerun)

    from . import study
    study.add_parser(sub)
    return p


class Terminated(KeyboardInterrupt):
    """SIGTERM, handled as Ctrl-C: the run stops at its next record, its summary says interrupted."""


def _terminate(signum, frame):
    raise Terminated()


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    from . import _core

    signal.signal(signal.SIGTERM, _terminate)
    # Under mpirun, rank 0 speaks for all (read from mpirun's environment: MPI
    # itself starts only when a lattice is split, so `ldem bench` leaves it to ldem-bench).
    rank = int(os.environ.get("OMPI_COMM_WORLD_RANK") or os.environ.get("PMIX_RANK") or 0)
    if rank > 0:
        sys.stdout = open(os.devnull, "w")
    try:
        return args.func(args)
    except ValueError as e:  # bad input, found before anything runs (every MPI rank finds the same: rank 0 says it)
        if rank == 0:
            print(f"ldem {args.command}: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except _core.InstabilityError as e:
        print(f"ldem {args.command}: failed: {e} (rows so far are kept in the output folder)", file=sys.stderr)
        return EXIT_FAILED
    except OSError as e:  # a full disk, a file size limit, a folder gone
        where = f"cannot write {e.filename}" if e.filename else "cannot write"
        print(f"ldem {args.command}: failed: {where}: {e.strerror or e} (summary.json does not say done)",
              file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt as e:
        how = "terminated (SIGTERM)" if isinstance(e, Terminated) else "interrupted"
        print(f"ldem {args.command}: {how} (rows so far are kept in the output folder){_how_to_continue(args)}",
              file=sys.stderr)
        return 128 + (signal.SIGTERM if isinstance(e, Terminated) else signal.SIGINT)


def _how_to_continue(args) -> str:
    out = getattr(args, "out", None)
    if not out or not os.path.exists(os.path.join(out, "checkpoint.npz")):
        return ""
    if args.command == "cube":
        return f"; continue with: ldem cube --restart {out}"
    return f"; continue with: ldem run {args.file} --out {out} --restart" + "".join(f" --set {s}" for s in args.set)


def console() -> None:
    """The `ldem` command of a pip installation (py/bin/ldem for the others)."""
    sys.exit(main())

