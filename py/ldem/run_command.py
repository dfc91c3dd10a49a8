"""`ldem cube` and `ldem run`, the commands that run one specimen: their
options (those of `ldem cube` generated from the fields of ldem.CubeTest, so
defaults live in one place), the run with its files, the lines it prints, and
a run taken further: --restart continues an interrupted run from its
checkpoint, bit for bit; --restart with --extend STRAIN takes a finished run
that did not separate (it stopped at its final strain or at load loss) from
its final state on to a larger final strain, as if it had never stopped.
Longer than 300 lines: both commands' options, run, printed lines and restart, one reading."""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import sys

from .helptext import HelpFormatter, add_output_flags, add_parameter_option

EXIT_FAILED = 1


def add_cube_options(p: argparse.ArgumentParser, skip=()) -> None:
    """One option per field of ldem.CubeTest (that is, per parameter of
    pkg/ldem/Parameters.hpp), grouped as declared there."""
    from .cube import CubeTest

    groups = {}
    for f in dataclasses.fields(CubeTest):
        if f.name in skip:
            continue
        group = groups.get(f.metadata["group"]) or groups.setdefault(f.metadata["group"],
                                                                     p.add_argument_group(f.metadata["group"]))
        add_parameter_option(group, f)  # the formatter adds (default: ...)


def cube_from_args(args) -> "CubeTest":
    from .cube import CubeTest

    return CubeTest(**{f.name: getattr(args, f.name) for f in dataclasses.fields(CubeTest)
                       if hasattr(args, f.name)})


def cmd_cube(args) -> int:
    _restart_or_overwrite(args)
    if args.restart:  # the test of the checkpoint (or final state), in its folder
        if args.extend is None and finished(args.restart, f"ldem cube --restart {args.restart}"):
            return 0
        for name, value in _parameters_in(args.restart, args.extend is not None).items():
            setattr(args, name, value)
        args.out = args.restart
        if args.extend is not None:
            args.final_strain, args.stop_at = args.extend, "separation"
    elif args.extend is not None:
        raise ValueError("--extend goes with --restart DIR: the finished run to take further")
    test = cube_from_args(args)
    params = test.params()  # every input checked before the warnings below and before any output
    if _kept(args, test, f"ldem cube --restart {args.out}"):
        return 0
    warn_brittle(args.command, params.material, test.L0)
    from ._core import allowed_cores

    cores = allowed_cores()
    if test.threads > cores:
        print(f"ldem cube: warning: --threads {test.threads} is more than the {cores} cores: using {cores}",
              file=sys.stderr)
    progress = False if args.no_progress else None
    from .runner import run_cube

    result = run_cube(test, out=args.out, progress=progress, plots=not args.no_plots,
                      figure_format=args.figure_format, snapshots=_snapshots(args),
                      checkpoint_every=args.checkpoint_every, restart=bool(args.restart),
                      **_continuation(args))
    return report_run(result, args, edge=test.load == "triangular")


def warn_brittle(command: str, material, L0: float) -> None:
    """The warning when the bars of the mean G_f are perfectly brittle by construction (pkg/ldem/Relations.hpp)."""
    from ._core import brittle_warning

    if (why := brittle_warning(material, L0)):
        print(f"ldem {command}: warning: {why}", file=sys.stderr)


def warn_module(command: str, test) -> None:
    """The warning when a specimen file is coarser than the module rule (ldem.module_rule)."""
    from .module_rule import bar_count, warning

    if (why := warning(test.description["shape"], test.build.L0, bar_count(test.build.mask))):
        print(f"ldem {command}: warning: {why}", file=sys.stderr)


def _parameters_in(out: str, extend: bool) -> dict:
    """The parameters of the run in folder out: of its checkpoint, or with extend of its final state."""
    from .io import CHECKPOINT, FINAL_STATE, read_checkpoint, read_summary

    name = FINAL_STATE if extend else CHECKPOINT
    try:
        return read_checkpoint(os.path.join(out, name))[1]
    except OSError as e:
        if extend:
            try:
                if read_summary(os.path.join(out, "summary.json")).get("stop_reason") == "separated":
                    raise ValueError(f"cannot extend {out}: the run separated; there is nothing further") from None
            except OSError:
                pass
        raise ValueError(f"cannot {'extend' if extend else 'restart from'} {out}: {name}: {e.strerror or e}") from None


def _continuation(args) -> dict:
    """run_cube's options for checkpoints, the final state and --extend. Under
    mpirun none (checkpoints of a split lattice are not supported)."""
    from . import parallel

    one = parallel.ranks() == 1
    if args.extend is not None and not one:
        raise ValueError("--extend: runs split over MPI ranks keep no final state")
    return dict(checkpoint_seconds=60.0 * args.checkpoint_minutes if one else 0.0, final_state=one,
                extend=args.extend is not None)


def finished(out: str, restart: str, again: bool = False) -> bool:
    """out holds a finished run (summary.json says done): --restart (or, with
    again, a run of the same parameters) says so and runs nothing, and how to
    extend it if it can be (restart: the command that restarts it)."""
    from .io import FINAL_STATE, read_summary

    try:
        done = read_summary(os.path.join(out, "summary.json")).get("status") == "done"
    except (OSError, ValueError):
        return False
    if done:
        further = f"; to take it further: {restart} --extend STRAIN" \
            if os.path.exists(os.path.join(out, FINAL_STATE)) else ""
        what = " of the same parameters: nothing to run (--overwrite runs it again)" if again else \
            ": nothing to continue"
        print(f"{out} is a finished run (summary.json: done){what}{further}")
    return done


def _kept(args, test, restart: str) -> bool:
    """Before a fresh run into args.out: True when it holds test's own finished run (said so, nothing to run);
    a finished run of other parameters is refused, naming them, unless --overwrite. A restart continues
    its folder's run and is not asked; a folder without a finished run is written as before."""
    if args.restart or args.overwrite:
        return False
    from .io import read_summary

    try:
        old = read_summary(os.path.join(args.out, "summary.json"))
    except (OSError, ValueError):
        return False
    if not isinstance(old, dict) or old.get("status") != "done":
        return False
    differ = _other_parameters(old.get("parameters") or {}, json.loads(json.dumps(test.parameters())))
    if not differ:
        return finished(args.out, restart, again=True)
    more = f" and {len(differ) - 3} more" if len(differ) > 3 else ""
    raise ValueError(f"{args.out} holds a finished run of other parameters ({'; '.join(differ[:3])}{more}): "
                     "give another --out, or --overwrite")


def _other_parameters(old: dict, new: dict) -> list:
    """What differs between the parameters of two runs ("seed 1, not 2": the folder's, then this one's), the
    thread count aside (the results do not depend on it). A parameter the folder's summary lacks ran at the
    table's default (it was declared later), as ldem rerun reads it."""
    from .cube import TABLE_DEFAULTS
    from .rerun import differences, field

    if ("description" in old) != ("description" in new):
        kinds = ("a specimen file's", "a cube's")
        return [f"{kinds['description' not in old]}, not {kinds['description' not in new]}"]
    if "description" in new:  # a file's material, loading and run are its parameters: said once, by name
        pairs = [({k: v for k, v in d.items() if k not in ("material", "loading", "run")}
                  for d in (old.get("description") or {}, new["description"])),
                 ({**TABLE_DEFAULTS, **(old.get("parameters") or {})}, new["parameters"])]
    else:
        pairs = [({**TABLE_DEFAULTS, **old}, new)]
    return [f"{path} {_said(field(a, path))}, not {_said(field(b, path))}"
            for a, b in pairs for path in differences(a, b, skip=("threads",))]


def _said(value) -> str:
    """A parameter's value in a message: a number or a word as written, anything else as its JSON, cut short."""
    if isinstance(value, (int, float, str)) and not isinstance(value, bool):
        return str(value)
    text = json.dumps(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _restart_or_overwrite(args) -> None:
    if args.restart and args.overwrite:
        raise ValueError("--overwrite runs afresh and --restart continues: give one of them")


def _snapshots(args) -> list:
    try:
        return [float(x) for x in args.snapshots.split(",") if x.strip()]
    except ValueError:
        raise ValueError(f"--snapshots takes comma-separated mean strains (got '{args.snapshots}')") from None


def report_run(result, args, edge: bool = False) -> int:
    """The lines a run prints (ldem cube, ldem run), in the specimen's own words (summary.json's labels: a
    cube's mean strain and normal stress, a beam's deflection/D and F/(bD)); exit 1 on an energy error."""
    from .cube import label_words
    from .runner import STOP_WORDS, stopped_short

    s, test = result.summary, result.test
    (strain, _), (stress, unit) = label_words(s["labels"]["strain"]), label_words(s["labels"]["stress"])
    u_min = s["min_fracture_energy_J"]  # None: the specimen declares no ligament
    of_min = lambda u: "" if u_min is None else f" ({u / u_min:.3f} U_min)"  # noqa: E731
    print(f"peak {stress} {s['peak_stress_MPa']:.4f} {unit or 'MPa'} at {strain} {s['strain_at_peak']:.4e}"
          + (f" (most-pulled edge {s['edge_strain_at_peak']:.4e})" if edge else ""))
    loss, sep = s["load_loss"], s["separation"]
    if loss:
        print(f"load lost at {strain} {loss['mean_strain']:.4e}: fracture energy {loss['fracture_energy_J']:.4g} J"
              + of_min(loss["fracture_energy_J"]))
    if sep:
        cut = "" if s["U_mincut_J"] is None or u_min is None else \
            f", cheapest cut {s['U_mincut_J'] / u_min:.3f} U_min"
        ratio = "" if u_min is None else f", U_num/U_min {s['U_ratio']:.3f} (U_min {u_min:.4g} J{cut})"
        print(f"separated at {strain} {sep['mean_strain']:.4e}: U_num {s['U_num_J']:.4g} J{ratio}")
    elif (conv := s.get("converged")):
        print(f"converged at {strain} {conv['mean_strain']:.4e} (U grew by less than "
              f"{test.converged_growth:.0%} over the last doubling of the strain): U_final "
              f"{s['U_final_J']:.4g} J{of_min(s['U_final_J'])} (not U_num: it did not separate)")
    elif s["stop_reason"] in STOP_WORDS:
        stop = STOP_WORDS[s["stop_reason"]]
        aim = stopped_short(test, s["stop_reason"])
        print(f"stopped at {stop} ({strain} {result.curve['mean_strain'][-1]:.4e})" + " before separation" * aim
              + f": the fracture energy at the end, {s['fracture_energy_J']:.4g} J{of_min(s['fracture_energy_J'])}"
              + ", is not U_num (the energy at separation)" * aim)
        if result.curve["damaged_bars"][-1] + result.curve["broken_bars"][-1] == 0:  # the peak lies beyond
            print("no bar left its elastic branch: the peak lies beyond the final strain (above: the last record's)")
    threads = f"{s['threads']} thread{'s' * (s['threads'] != 1)}"  # the run's (threads = 0: chosen, Parallel.hpp)
    where = f"{s['mpi_ranks']} MPI ranks of {threads}" if s.get("mpi_ranks", 1) > 1 else threads
    print(f"energy balance error {s['energy_balance_error']:.2e}, {s['steps']} steps of {s['dt_s']:.3e} s, "
          f"{s['wall_s']:.1f} s wall on {where}")
    if s["clamped_bars"]:
        print(f"{s['clamped_bars']} of {s['n_bars']} bars had eps_r < eps_p and were made perfectly brittle")
    if (q := s["quasi_static"])["flagged"]:
        print(f"ldem {args.command}: warning: not quasi-static: the kinetic energy at the peak is "
              f"{q['kinetic_over_work_at_peak']:.1%} of the external work (above {q['kinetic_limit']:.0%}): the peak "
              f"depends on the strain rate; lower it (summary.json: quasi_static)", file=sys.stderr)
    if q["periods_to_eps_p"] < q["rate_periods"] * (1 - 1e-9):  # (rule (c)'s own rate: N within rounding)
        print(f"ldem {args.command}: warning: the drive strains eps_p in {q['periods_to_eps_p']:.2f} periods of "
              f"its own mode (omega_d), fewer than the {q['rate_periods']:g} of rule (c): the peak may move with the rate; a strain "
              f"rate {q['periods_to_eps_p'] / q['rate_periods']:.2g} times this one meets it (summary.json: quasi_static)",
              file=sys.stderr)
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
    from .helptext import settings
    from .runner import run_cube
    from .specimen import SpecimenTest

    _restart_or_overwrite(args)
    overrides = settings(args.set)
    if args.threads is not None:
        overrides["threads"] = args.threads
    if args.extend is not None:
        if not args.restart:
            raise ValueError("--extend goes with --restart: the finished run in --out to take further")
        overrides.update(final_strain=args.extend, stop_at="separation")
    test = SpecimenTest.from_file(args.file, overrides)
    args.out = args.out or os.path.join("out", os.path.splitext(os.path.basename(args.file))[0])
    restart = f"ldem run {args.file} --out {args.out} --restart" + "".join(f" --set {s}" for s in args.set)
    if args.restart and args.extend is None and finished(args.out, restart):
        return 0
    if _kept(args, test, restart):
        return 0
    warn_brittle(args.command, test.build.cpp_params().material, test.build.L0)
    if not args.restart:  # said when the run started
        warn_module(args.command, test)
    result = run_cube(test, out=args.out, progress=False if args.no_progress else None, plots=not args.no_plots,
                      figure_format=args.figure_format, snapshots=_snapshots(args),
                      checkpoint_every=args.checkpoint_every, restart=args.restart, **_continuation(args))
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
    p.add_argument("--overwrite", action="store_true",
                   help="run even where --out holds a finished run, and replace its files (without it: a finished "
                        "run of other parameters is refused, one of the same parameters is not run again)")
    add_output_flags(p)


def what_is_kept(args) -> str:
    """What an interrupted command left, read from its files: the message says
    only what is true (ldem cube and run: the curve's rows, the checkpoint's
    step; a study: its finished cases)."""
    out = getattr(args, "out", None)
    if args.command not in ("cube", "run"):
        return f"finished cases are kept in {out}; the same command continues the others" if out else "nothing kept"
    try:
        with open(os.path.join(out, "curve.csv")) as f:
            rows = f.read().splitlines()[1:]
    except OSError:
        rows = []
    kept = f"curve.csv keeps {len(rows)} row{'s' * (len(rows) != 1)}, to step {rows[-1].split(',')[0]}" if rows else \
        "nothing ran: curve.csv has no rows"
    from .io import saved_step

    try:
        return f"{kept}; checkpoint.npz is of step {saved_step(out)}"
    except (OSError, ValueError, KeyError, EOFError):
        return kept + "; no checkpoint: it would run again from the start"


def how_to_continue(args) -> str:
    out = getattr(args, "out", None)
    if not out or not os.path.exists(os.path.join(out, "checkpoint.npz")):
        return ""
    if args.command == "cube":
        return f"; continue with: ldem cube --restart {out}"
    return f"; continue with: ldem run {args.file} --out {out} --restart" + "".join(f" --set {s}" for s in args.set)



def add_parsers(sub) -> None:
    """The subcommands cube and run."""
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
    _extend_option(c, "--restart DIR")
    c.set_defaults(func=cmd_cube)

    f = sub.add_parser("run", help="any specimen from a TOML file (examples/: beams, cylinders, dog-bones, cubes)",
                       description="Runs the specimen FILE describes (docs/specimens.md); writes what "
                                   "ldem cube writes into --out. A bad file: one line naming the key and its line, "
                                   "exit 2.", formatter_class=HelpFormatter)
    f.add_argument("file", metavar="FILE", help="the specimen's TOML file")
    f.add_argument("--out", default=None, metavar="DIR", help="output folder (default: out/FILE's name)")
    f.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a material, loading or run parameter over the file's (repeatable), e.g. --set seed=2")
    from .cube import CubeTest

    add_parameter_option(f, next(x for x in dataclasses.fields(CubeTest) if x.name == "threads"),
                         note=", over the file's run.threads", default=None)
    f.add_argument("--restart", action="store_true",
                   help="continue the run of --out's checkpoint.npz, bit for bit (the same file and --set)")
    _extend_option(f, "--restart")
    _output_options(f)
    f.set_defaults(func=cmd_run)


def _extend_option(p: argparse.ArgumentParser, restart: str) -> None:
    p.add_argument("--extend", type=float, default=None, metavar="STRAIN",
                   help=f"with {restart}: take the finished run (it stopped at its final strain or at load loss, "
                        "not separated) from its final_state.npz on to mean strain STRAIN or separation, as if it "
                        "had never stopped")
