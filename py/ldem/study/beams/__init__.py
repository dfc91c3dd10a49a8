"""`ldem study beams`: the Grégoire et al. (2013) beams (ldem.study.beams.cases has
the why of each choice), one sub-command per step, each in the study folder
OUT (default results/beams/gregoire2013, from where it is run):

    ldem study beams calibrate                                      eps_p on the tension prism
    ldem study beams predict --eps-p E [--out OUT] [--seeds 6] [--jobs J] [--notches 0,0.2,0.5] [--rate-periods N]
                                                                    cases/, predictions.csv
    ldem study beams uniform --eps-p E [--out OUT] [--jobs J]       G_f CV 0: cases_cv0/
    ldem study beams curves [--out OUT] [--seeds 6]                 curves/*.csv, curves.png
    ldem study beams compare [--out OUT] [--data DIR]               comparison.md|png (comparison)
    ldem study beams size-effect [--out OUT]                        size_effect.md|csv|png, cracks.png
    ldem study beams diagnose [--factors A,B] [--seeds 6] [--jobs J]   OUT/diagnosis/ (diagnosis)
    ldem study beams calibrated [--seeds 6] [--seeds-200 2] [--jobs J]  OUT/calibrated/
    ldem study beams whole-curves [--seeds 6] [--jobs J]            OUT/whole_curves/ (whole_curves)
    ldem study beams transfer [--on D50_n0,...] [--predict ...] [--L0 M] [--seeds 6] [--jobs J]   OUT/transfer/
    ldem study beams convergence [--seeds 3] [--jobs J] [--beams ...] [--L0 ...]   OUT/convergence/ (convergence)

Cases are resumed and run side by side as every study's (J at a time, one
thread each); a finished case is not run again."""
from __future__ import annotations

import json
import os

from .convergence import (PLAN as CONVERGENCE_PLAN, SEEDS as CONVERGENCE_SEEDS, plan as convergence_plan,
                          run as run_convergence)
from .comparison import compare as compare_beams, comparison_figure, comparison_rows, default_data, table_lines
from .diagnosis import BY_NAME, FACTORS, markdown as diagnosis_markdown, run as run_diagnosis
from .report import cracks_mosaic, curves_figure, size_effect_figure
from .tables import write_curve_tables, write_size_effect
from .cases import (DEPTHS, E, FC, FT, L0, NOTCHES, NU, Variant, calibrate as calibrate_eps_p, calibrated_variant,
                    run_beams, series_tests, uniform_tests, write_predictions)
from ..concrete import calibrate as calibrate_concrete
from ..options import add_seeds, parameter_option, parse_floats, parse_names, seed_count
from ..registry import Study, register
from .transfer import report as transfer_report, transfer as run_transfer
from .whole_curves import beam_name, measured_beams, run as run_whole_curves

OUT = os.path.join("results", "beams", "gregoire2013")
CALIBRATED_NOTE = ("The nine beams with the concrete of the calibration procedure (docs/calibration.md: "
                   "bilinear law, G_f = 0.4 G_F, E and f_t from the virtual prism), **after the diagnosis, not "
                   "blind**: the procedure was written after the blind prediction was compared with these "
                   "measurements. Written by `ldem study beams calibrated`.")


def log(s: str) -> None:
    print(s, flush=True)


def eps_p(args) -> float:
    if not args.eps_p > 0:
        raise ValueError(f"--eps-p must be positive (got {args.eps_p}; ldem study beams calibrate finds it)")
    return args.eps_p


def predict(args) -> None:
    """Runs the cases not yet finished, then writes predictions.csv from all of them."""
    seeds = seed_count(args)
    eps_p(args)
    notches = parse_floats(args.notches, "--notches")
    if any(n not in NOTCHES for n in notches):
        raise ValueError(f"--notches: each one of {', '.join(f'{n:g}' for n in NOTCHES)} (got {args.notches})")
    if args.rate_periods < 0:
        raise ValueError(f"--rate-periods must be >= 0 (got {args.rate_periods})")
    if args.jobs > 0:
        v = Variant(rate_periods=args.rate_periods)
        run_beams(series_tests(args.eps_p, seeds, v, notches=notches), args.out, args.jobs)
    write_predictions(args.out, seeds)


def uniform(args) -> None:
    run_beams(uniform_tests(eps_p(args)), args.out, args.jobs)


def curves(args) -> None:
    curves_figure(args.out, write_curve_tables(args.out, seed_count(args)))


def compare(args) -> None:
    try:
        rows = compare_beams(args.out, args.data)
    except FileNotFoundError as e:
        raise ValueError(str(e)) from None
    for r in rows:
        print(f"  D = {r['D_mm']:g} mm, notch {r['notch']:g} D: predicted {r['predicted_kN']:.3f} kN, "
              f"measured {r['measured_kN']:.3f} kN ({r['difference_pct']:+.1f} %)")
    print(f"wrote {args.out}/comparison.md and comparison.png")


def size_effect(args) -> None:
    found = write_size_effect(args.out)
    if found is None:
        raise ValueError(f"{args.out}: no finished case")
    lines, *fits = found
    size_effect_figure(args.out, *fits)
    cracks_mosaic(args.out)
    print("\n".join(lines))


def diagnose(args) -> None:
    names = parse_names(args.factors, BY_NAME, "factor", ", ".join(BY_NAME))
    rows = run_diagnosis(os.path.join(args.out, "diagnosis"), names, seed_count(args), args.jobs, log)
    print("\n".join(diagnosis_markdown(rows)))


def calibrated(args) -> None:
    """The procedure's material (OUT/material.json), the beams with it (D50 and
    D100 with --seeds, D200 with --seeds-200), their table and comparison."""
    out, seeds = args.out, max(seed_count(args), args.seeds_200)
    path = os.path.join(out, "material.json")
    if not os.path.exists(path):
        result = calibrate_concrete(E, NU, FT, FC, L0=L0, log=print)
        os.makedirs(out, exist_ok=True)
        with open(path, "w") as f:
            json.dump(result, f, indent=1)
    with open(path) as f:
        m = json.load(f)["material"]
    v = calibrated_variant(m)
    tests = series_tests(m["eps_p"], args.seeds, v, DEPTHS[:2])
    tests += series_tests(m["eps_p"], args.seeds_200, v, DEPTHS[2:])
    run_beams(tests, out, args.jobs)
    write_predictions(out, seeds)
    curves_figure(out, write_curve_tables(out, seeds))
    data = args.data or default_data(out)
    rows = comparison_rows(out, data)
    comparison_figure(out, data, rows, "the calibrated concrete, after the diagnosis, not blind")
    text = "\n".join(["# Grégoire et al. (2013) with the calibrated concrete", "", CALIBRATED_NOTE, "",
                      *table_lines(rows), "",
                      "![calibrated concrete against the measurements](comparison.png)", ""])
    with open(os.path.join(out, "comparison.md"), "w") as f:
        f.write(text)
    print(text)


def calibrated_material(out: str) -> str:
    """OUT/../calibrated/material.json, the calibrated concrete."""
    material = os.path.join(os.path.dirname(os.path.abspath(out)), "calibrated", "material.json")
    if not os.path.isfile(material):
        raise ValueError(f"{material} not found: `ldem study beams calibrated` writes it")
    return material


def whole(args) -> None:
    """The measured beams' whole curves with the calibrated concrete."""
    print(run_whole_curves(args.out, calibrated_material(args.out), args.data or default_data(args.out),
                           seed_count(args), args.jobs))


def calibrate_on_one(args) -> None:
    """Calibrate on each beam of --on in turn, predict the others (transfer/PROTOCOL.md)."""
    data = args.data or default_data(args.out)
    names = {beam_name(*b): b for b in measured_beams(data)}
    on = [names[n] for n in parse_names(args.on, names, "beam", ", ".join(names))]
    if args.start and not os.path.isfile(args.start):
        raise ValueError(f"--start {args.start} not found (a material JSON: `ldem study calibration --out` writes one)")
    with open(args.start or calibrated_material(args.out)) as f:
        start = json.load(f)["material"]
    predict = None if args.predict is None else \
        [names[n] for n in parse_names(args.predict, names, "beam", ", ".join(names))]
    for b in on:
        run_transfer(args.out, data, b, start, seed_count(args), args.jobs, log, args.L0, predict)
    print(transfer_report(args.out, data, on, seed_count(args), predict))


def converge(args) -> None:
    """The peak against the module (convergence), at the concrete fitted on D50_n0.5 (--fit)."""
    fit = args.fit or os.path.join(os.path.dirname(os.path.abspath(args.out)), "transfer", "on_D50_n0.5", "fit.json")
    if not os.path.isfile(fit):
        raise ValueError(f"{fit} not found (the fit of `ldem study beams transfer --on D50_n0.5`)")
    beams = parse_names(args.beams, [beam_name(*b) for b in CONVERGENCE_PLAN], "beam", "D50_n0.5, D50_n0, D100_n0.2")
    try:
        modules = [float(v) * 1e-3 for v in args.L0s.split(",") if v.strip()]
    except ValueError:
        raise ValueError(f"--L0 takes comma-separated modules in mm (got '{args.L0s}')") from None
    which = convergence_plan(beams, modules)
    if not which:
        raise ValueError(f"--beams {args.beams} --L0 {args.L0s}: no run of the plan (ldem.study.beams.convergence.PLAN)")
    print(run_convergence(args.out, fit, args.data or default_data(args.out), seed_count(args), args.jobs, which))


def _jobs(p, note: str = "") -> None:
    p.add_argument("--jobs", type=int, default=1, metavar="J", help="runs at a time, one thread each" + note)


def _data(p) -> None:
    p.add_argument("--data", default=None, metavar="DIR",
                   help="the measurements (measured.csv, D50_*_load_cmod.csv; default ../shared/data/gregoire2013 "
                        "beside the repository holding OUT)")


def add_arguments(b) -> None:
    sub = b.add_subparsers(dest="beams_command", metavar="COMMAND", required=True)

    def command(name, run, line, out=OUT):
        p = sub.add_parser(name, help=line, description=line, formatter_class=b.formatter_class)
        p.set_defaults(beams_run=run)
        if out:
            p.add_argument("--out", default=out, metavar="OUT", help="the study folder")
        return p

    command("calibrate", lambda a: calibrate_eps_p(log), "eps_p such that the tension prisms' mean strength "
            "is f_t (seeds 1-3): the value predict and uniform take", out="")
    p = command("predict", predict, "the beams with random G_f, --seeds specimens each (OUT/cases/), then "
                                    "predictions.csv")
    u = command("uniform", uniform, "the beams with a uniform G_f (CV 0, one specimen each: OUT/cases_cv0/)")
    for q in (p, u):
        parameter_option(q, "eps_p", "--eps-p", "; `ldem study beams calibrate` finds it", required=True,
                         default=None)
    add_seeds(p, "beam")
    p.add_argument("--notches", default=",".join(f"{n:g}" for n in NOTCHES), metavar="N,...",
                   help="notch depths / D of the beams to run (default: all three)")
    p.add_argument("--rate-periods", type=float, default=0.0, metavar="N",
                   help="drive by rule (c): eps_p in N periods of the mode the drive moves (omega_d), in place of "
                        "the study's 0.1 D per second (0: that rate)")
    _jobs(p, " (0: only the table, from the cases finished)")
    _jobs(u)
    add_seeds(command("curves", curves, "curves/D{mm}_n{notch}.csv and curves.png from the finished cases"), "beam")
    _data(command("compare", compare, "runs nothing: the prediction in OUT against the measurements: "
                                      "comparison.md|png"))
    command("size-effect", size_effect, "Bažant's law fitted per notch, the unnotched slope, the uniform-G_f "
                                        "beams beside them: size_effect.md|csv|png, cracks.png")
    g = command("diagnose", diagnose, "one factor at a time against the prediction: OUT/diagnosis/")
    g.add_argument("--factors", default=",".join(f.name for f in FACTORS),
                   help="comma-separated, of: " + ", ".join(f.name for f in FACTORS))
    add_seeds(g, "beam")
    _jobs(g)
    q = command("calibrated", calibrated, "the nine beams with the calibration procedure's concrete: "
                                          "OUT/calibrated/", os.path.join(OUT, "calibrated"))
    q.add_argument("--seeds", type=int, default=6, help="specimens of the D = 50 and 100 mm beams")
    q.add_argument("--seeds-200", type=int, default=2, help="specimens of the D = 200 mm beams")
    _jobs(q)
    _data(q)
    w = command("whole-curves", whole, "the measured beams under a clip gauge's servo to 4.4 times the measured "
                                       "CMOD at the peak, the calibrated concrete: OUT/whole_curves/",
                os.path.join(OUT, "whole_curves"))
    add_seeds(w, "beam")
    _jobs(w)
    _data(w)
    t = command("transfer", calibrate_on_one, "calibrate on one measured beam, predict the other two, by "
                                              "OUT/PROTOCOL.md: OUT/on_{beam}/, OUT/transfer.md", os.path.join(OUT, "transfer"))
    t.add_argument("--on", default="D50_n0,D50_n0.5,D100_n0.2", help="the beams to calibrate on, in turn")
    t.add_argument("--start", default="", metavar="MATERIAL.json", help="the fit's start (default: "
                   "../calibrated/material.json beside OUT, the calibrated concrete)")
    t.add_argument("--predict", default=None, help="the beams to predict (default: every other measured one)")
    parameter_option(t, "L0", "--L0", "; of every run (the gauges must be whole modules)", default=L0)
    add_seeds(t, "predicted beam")
    _jobs(t)
    _data(t)
    c = command("convergence", converge, "the peak against the module L0, the concrete fitted on "
                                            "D50_n0.5 at 5 mm: OUT/convergence.md|csv, the module rule",
                os.path.join(OUT, "convergence"))
    c.add_argument("--beams", default="", help="comma-separated, of D50_n0.5, D50_n0, D100_n0.2 (default: all)")
    c.add_argument("--L0", dest="L0s", default="", metavar="MM", help="comma-separated modules [mm] of the plan "
                   "(default: all: 5, 2.5, 1.667 and 1.25 at D = 50 mm, 5 and 2.5 at D = 100 mm)")
    c.add_argument("--fit", default="", metavar="FIT.json", help="the concrete (default: "
                   "../transfer/on_D50_n0.5/fit.json beside OUT)")
    c.add_argument("--seeds", type=int, default=CONVERGENCE_SEEDS, help="specimens per beam and module")
    _jobs(c)
    _data(c)


def cmd_beams(args) -> int:
    args.beams_run(args)
    return 0


register(Study("beams", "the notched beams of Gregoire et al. (2013): calibration, runs, predictions, size effect, "
                        "comparison, diagnosis", add_arguments, cmd_beams,
               "The notched beams of Gregoire et al. (2013), one sub-command per step, in the study folder OUT "
               f"(default {OUT}): calibrate finds eps_p; predict and uniform run the beams; curves, size-effect "
               "and compare write tables and figures from the finished cases; diagnose runs one factor at a time "
               "against the prediction, calibrated the beams with the calibration procedure's concrete. "
               "`ldem study beams COMMAND --help` says more of each."))
