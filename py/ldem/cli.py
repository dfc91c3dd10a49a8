"""The `ldem` command line: its parser (the commands that run a specimen, cube
and run, are ldem.run_command's; bench, rerun, and study's), and main(), which
turns every failure into one line and an exit code."""
from __future__ import annotations

import argparse
import dataclasses
import os
import signal
import sys


from .bench import cmd_bench
from .rerun import RERUN_SKIPS, cmd_rerun  # noqa: F401 (RERUN_SKIPS: the fields a rerun does not compare)
from .cube import CubeTest
from .helptext import EXIT_BAD_INPUT, ArgumentParser, HelpFormatter, add_parameter_option
from .run_command import EXIT_FAILED, add_parsers, how_to_continue, what_is_kept
from .signals import Terminated, raise_on_signals


CUBE_FIELDS = {f.name: f for f in dataclasses.fields(CubeTest)}


def build_parser() -> argparse.ArgumentParser:
    from . import __version__
    from .cube import provenance

    p = ArgumentParser(prog="ldem", description="Truss-like lattice DEM (Riera-Iturrioz) for fracture of concrete.")
    commit = provenance()["git_commit"]
    p.add_argument("--version", action="version", version=f"ldem {__version__}" + (f" (git {commit})" if commit else ""))
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=ArgumentParser)
    sub.required = True

    add_parsers(sub)

    b = sub.add_parser("bench", help="time the time step of an N^3 cube (one line of JSON)",
                       description="Builds an N^3 cube (default material), runs S steps of uniform loading R "
                                   "times and prints modules, bars, nodes, steps, threads, ns_per_bar_step "
                                   "(median of the R repetitions), peak_rss_bytes and bytes_per_bar.",
                       formatter_class=HelpFormatter)
    b.add_argument("--modules", type=int, default=24, metavar="N", help="modules per side")
    b.add_argument("--steps", type=int, default=200, metavar="S", help="steps per repetition")
    add_parameter_option(b, CUBE_FIELDS["threads"])  # ldem-bench's threads are a run's: the table's words
    b.add_argument("--repeats", type=int, default=5, metavar="R", help="repetitions (the median is reported)")
    b.add_argument("--damaged", action="store_true",
                   help="then pull the cube to load loss and time the same steps from there (damaged_* fields)")
    b.set_defaults(func=cmd_bench)

    r = sub.add_parser("rerun", help="run a result's folder again from its summary.json and compare",
                       description="Reads DIR/summary.json (its parameters and provenance), runs the same test (a "
                                   "cube, a study's case or an ldem run specimen) into --out (default DIR/rerun) and "
                                   "compares the curve and every field of the summary but when, where and how fast "
                                   "it ran (it names them): exit 0 if they are identical, 1 if not.",
                       formatter_class=HelpFormatter)
    r.add_argument("dir", metavar="DIR", help="a folder written by ldem cube or ldem run (or a study's case folder)")
    r.add_argument("--out", default=None, metavar="OUT", help="where the rerun writes (default: DIR/rerun)")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    r.set_defaults(func=cmd_rerun)

    from . import study
    study.add_parser(sub)
    return p


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    from . import _core

    raise_on_signals()  # the command's work starts: a signal is heard where it is, and its files say what is kept
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
    except MemoryError:  # past the estimate's check (pkg/ldem/Lattice.hpp, checkFits): the specimen did not fit after all
        print(f"ldem {args.command}: error: out of memory building the specimen: it does not fit this process",
              file=sys.stderr)
        return EXIT_BAD_INPUT
    except _core.InstabilityError as e:
        print(f"ldem {args.command}: failed: {e} (rows so far are kept in the output folder)", file=sys.stderr)
        return EXIT_FAILED
    except OSError as e:  # a full disk, a file size limit, a folder gone
        where = f"cannot write {e.filename}" if e.filename else "cannot write"
        print(f"ldem {args.command}: failed: {where}: {e.strerror or e} (summary.json does not say done)",
              file=sys.stderr)
        return EXIT_FAILED
    except (KeyboardInterrupt, RuntimeError) as e:
        # A signal while a class is made (in an import done where it is needed: matplotlib's where pictures
        # are drawn) comes wrapped in Python 3.11's RuntimeError "Error calling __set_name__".
        e = e if isinstance(e, KeyboardInterrupt) else e.__cause__
        if not isinstance(e, KeyboardInterrupt):
            raise
        how = "terminated (SIGTERM)" if isinstance(e, Terminated) else "interrupted"
        print(f"ldem {args.command}: {how}: {what_is_kept(args)}{how_to_continue(args)}",
              file=sys.stderr)
        return 128 + (signal.SIGTERM if isinstance(e, Terminated) else signal.SIGINT)
