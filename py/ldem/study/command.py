"""`ldem study size-effect`, `damping`, `mesh`, `refinement` and `beams`: options,
input checks, the printed summary."""
from __future__ import annotations

import os
import time
from typing import List, Sequence

from ..helptext import HelpFormatter, add_output_flags
from ..cube import CubeTest, settings
from .beam_comparison import compare as compare_beams
from .beam_report import cracks_mosaic, curves_figure, size_effect_figure
from .beam_tables import write_curve_tables, write_size_effect
from .beams import run_beams, series_tests, uniform_tests, write_predictions
from .cases import damping_tests, size_effect_tests
from .damping import run_damping
from .executors import default_threads
from .located import read_earlier
from .mesh import CALIBRATION_SIZE, COARSE_MODULES, MESH_SIZES, VARIANTS, run_mesh
from .refinement import CORR_LENGTHS, REFINEMENT, refinement_tests, run_refinement
from .size_effect import STUDY_SIZES, run_size_effect


def _floats(text: str, what: str) -> List[float]:
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise ValueError(f"{what} must be a comma-separated list of numbers (got '{text}')") from None
    if not values:
        raise ValueError(f"{what} is empty")
    return values


def _loads(text: str) -> List[str]:
    loads = [x.strip() for x in text.split(",") if x.strip()]
    for ld in loads:
        if ld not in ("uniform", "triangular"):
            raise ValueError(f"unknown load '{ld}' (expected uniform or triangular)")
    return loads


def _settings(pairs: Sequence[str]) -> dict:
    """--set NAME=VALUE pairs as CubeTest fields of the right type."""
    out = settings(pairs)
    for name in ("size", "load", "seed"):
        if name in out:
            raise ValueError(f"--set {name}: the study sets it (use its own options)")
    return out


def _common(args) -> dict:
    """The settings every case of the study gets. Threads per case: --threads;
    0 means this machine's cores over --jobs, or, on a dask cluster, one thread
    per case (dask runs cases side by side on the workers, whose cores are not
    this machine's)."""
    if args.threads > 0:
        threads = args.threads
    else:
        threads = 1 if args.scheduler else default_threads(args.jobs)
    return {"threads": threads, "strain_rate": args.strain_rate, **_settings(args.set)}


def _check_tests(tests: Sequence[CubeTest]) -> None:
    """Every case's input checked before anything runs."""
    for t in tests:
        t.params()


def cmd_size_effect(args) -> int:
    sizes = _floats(args.sizes, "--sizes")
    tests = size_effect_tests(sizes, _seeds(args), _loads(args.loads), **_common(args))
    _check_tests(tests)
    t0 = time.perf_counter()
    table, fits = run_size_effect(tests, args.out, jobs=args.jobs, scheduler=args.scheduler,
                                  progress=False if args.no_progress else None, report=not args.no_report,
                                  figure_format=args.figure_format)
    print(f"study: {len(tests)} cases in {time.perf_counter() - t0:.0f} s; wrote {args.out}/summary.csv, cases.csv"
          + ("" if args.no_report else ", report.md and figures"))
    for r in table:
        print(f"  {r['load']:10s} {r['size_m']:.2f} m: peak {r['peak_stress_MPa_mean']:.3f} MPa "
              f"(cv {r['peak_stress_MPa_cv']:.3f}) at {r['strain_at_peak_mean']:.3e}, "
              + (f"U_num/U_min {r['U_ratio_mean']:.3f}" if r["separated"] else "U_num -")
              + f" ({r['separated']} of {r['seeds']} separated), at load loss "
              + (f"{r['U_loss_ratio_mean']:.3f}" if r["U_loss_ratio_mean"] != "" else "-")
              + f", cheapest cut {r['U_mincut_ratio_mean']:.3f}"
              + (f", {r['energy_errors']} ENERGY ERRORS" if r["energy_errors"] else ""))
    for load, fit in fits.items():
        print(f"  fractal fit ({load}): d = {fit['d']:.3f} (energy per unit area: b^{fit['d_specific']:.3f})")
    return 0


def cmd_damping(args) -> int:
    zetas = _floats(args.zetas, "--zetas")
    if any(z < 0 for z in zetas):
        raise ValueError("damping ratios must be >= 0")
    common = _common(args)
    if "zeta" in common:
        raise ValueError("--set zeta: the damping study sets it (use --zetas)")
    tests = damping_tests(args.size, zetas, _loads(args.loads), seed=args.seed, **common)
    _check_tests(tests)
    rows = run_damping(tests, args.out, jobs=args.jobs, scheduler=args.scheduler,
                       progress=False if args.no_progress else None, report=not args.no_report,
                       figure_format=args.figure_format)
    for r in rows:
        print(f"  {r['load']:10s} zeta {r['zeta']:g}: peak {r['peak_stress_MPa']:.4f} MPa at "
              f"{r['strain_at_peak']:.4e}, U_num/U_min "
              + (f"{r['U_ratio']:.3f}" if r["separated"] else "(not separated)"))
    return 0


def _run_options(args) -> dict:
    return {"jobs": args.jobs, "scheduler": args.scheduler, "progress": False if args.no_progress else None}


def _seeds(args) -> int:
    if args.seeds < 1:
        raise ValueError(f"--seeds must be at least 1 (got {args.seeds})")
    return args.seeds


def cmd_mesh(args) -> int:
    variants = [v.strip() for v in args.variants.split(",") if v.strip()]
    for v in variants:
        if v not in VARIANTS:
            raise ValueError(f"unknown variant '{v}' (expected some of {', '.join(VARIANTS)})")
    for ref in args.reference:
        if not os.path.isdir(os.path.join(ref, "cases")):
            raise ValueError(f"--reference {ref}: not a study folder (no cases/ in it)")
    common = _common(args)
    for name in ("L0", "eps_p", "Gf_mean", "Gf_cv", "c_a"):
        if name in common:
            raise ValueError(f"--set {name}: the mesh study sets it (from the criterion)")
    if args.law_seeds < 2:
        raise ValueError(f"--law-seeds must be at least 2: the law needs a mean and a CV (got {args.law_seeds})")
    table = run_mesh(args.out, _floats(args.sizes, "--sizes"), _floats(args.modules, "--modules"), variants,
                     _loads(args.loads), _seeds(args), args.reference, run=not args.report_only,
                     report=not args.no_report, common=common, fmt=args.figure_format,
                     calibration_size=args.calibration_size, law_seeds=args.law_seeds, earlier=args.earlier,
                     **_run_options(args))
    print(f"mesh study: wrote {args.out}/laws.csv, cases.csv, summary.csv"
          + ("" if args.no_report else ", report.md and figures"))
    for t in table:
        print(f"  {t['load']:10s} {t['size_m']:.2f} m, L {t['module_m']:.3f} m, {t['variant']:9s}: "
              f"peak {t['peak_stress_MPa_mean']:.3f} MPa" + (f" ({t['peak_vs_fine']:.3f} of fine)"
                                                              if t["peak_vs_fine"] != "" else "")
              + ("" if t["U_ratio_mean"] == "" else f", U_num/U_min {t['U_ratio_mean']:.3f}")
              + ("" if t["U_vs_fine"] == "" else f" ({t['U_vs_fine']:.3f} of fine)"))
    return 0


def cmd_refinement(args) -> int:
    sizes = _floats(args.sizes, "--sizes")
    grid = {s: (tuple(_floats(args.L0s, "--L0s")) if args.L0s else REFINEMENT.get(s, ())) for s in sizes}
    for s, modules in grid.items():
        if not modules:
            raise ValueError(f"no default modules for a {s:g} m cube: give --L0s")
    common = _common(args)
    if "L0" in common or "corr_length" in common:
        raise ValueError("--set L0 / corr_length: the refinement study sets them (use --L0s, --corr-lengths)")
    tests = refinement_tests(grid, _floats(args.corr_lengths, "--corr-lengths"), _loads(args.loads),
                             _seeds(args), **common)
    _check_tests(tests)
    table = run_refinement(tests, args.out, run=not args.report_only, report=not args.no_report,
                           fmt=args.figure_format, earlier=read_earlier(args.earlier), **_run_options(args))
    print(f"refinement study: wrote {args.out}/cases.csv, summary.csv"
          + ("" if args.no_report else ", report.md and refinement.png"))
    for t in table:
        print(f"  {t['load']:10s} {t['size_m']:.2f} m, L0 {t['module_m']:g} m, l_c {t['corr_length_m']:g} m: "
              f"peak {t['peak_stress_MPa_mean']:.3f} MPa at {t['strain_at_peak_mean']:.3e}"
              + ("" if t["U_ratio_mean"] == "" else f", U_num/U_min {t['U_ratio_mean']:.3f}"))
    return 0


def cmd_beams(args) -> int:
    """The Gregoire et al. (2013) beams (ldem.study.beams): the unfinished cases,
    then predictions.csv, the curve tables and the size effect; with --compare,
    only the comparison of the committed prediction with the measurements."""
    if args.compare is not None:
        try:
            rows = compare_beams(args.out, args.compare or None)
        except FileNotFoundError as e:
            raise ValueError(str(e)) from None
        for r in rows:
            print(f"  D = {r['D_mm']:g} mm, notch {r['notch']:g} D: predicted {r['predicted_kN']:.3f} kN, "
                  f"measured {r['measured_kN']:.3f} kN ({r['difference_pct']:+.1f} %)")
        print(f"wrote {args.out}/comparison.md and comparison.png")
        return 0
    if args.eps_p is None or not (args.eps_p > 0):
        raise ValueError(f"--eps-p must be positive (got {args.eps_p}; scripts/gregoire2013.py calibrate finds it)")
    tests = uniform_tests(args.eps_p) if args.uniform else series_tests(args.eps_p, _seeds(args))
    run_beams(tests, args.out, args.jobs)
    write_predictions(args.out, args.seeds)
    curves_figure(args.out, write_curve_tables(args.out, args.seeds))
    found = write_size_effect(args.out)
    if found is not None:
        size_effect_figure(args.out, *found[1:])
        cracks_mosaic(args.out)
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("study", help="the size-effect and damping studies of the reference paper",
                       description="Runs many cube tests (resumable, in parallel) and aggregates them.")
    kinds = p.add_subparsers(dest="study", metavar="STUDY", parser_class=type(p))
    kinds.required = True

    def common(q):
        q.add_argument("--out", required=True, metavar="DIR", help="study folder (cases/, tables, figures, report)")
        q.add_argument("--loads", default="uniform,triangular", help="comma-separated loads")
        q.add_argument("--jobs", type=int, default=1, metavar="J", help="cases run at once in separate processes")
        q.add_argument("--threads", type=int, default=0, metavar="T",
                       help="OpenMP threads per case (0: this machine's cores / jobs; with --scheduler, 1)")
        q.add_argument("--scheduler", default=None, metavar="ADDRESS",
                       help="send cases to this dask.distributed scheduler instead (e.g. tcp://host:8786)")
        q.add_argument("--strain-rate", dest="strain_rate", type=float, default=CubeTest().strain_rate,
                       help="vertical strain rate [1/s]")
        q.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                       help="any other CubeTest parameter for every case, e.g. --set bottom_lateral=free "
                            "(repeatable; see ldem cube --help)")
        q.add_argument("--no-report", action="store_true", help="tables only: no figures, no report.md")
        add_output_flags(q)

    s = kinds.add_parser("size-effect", help="sizes x seeds x loads: tables, curves, cracks, energies, fractal fit",
                         formatter_class=HelpFormatter)
    common(s)
    s.add_argument("--sizes", default=",".join(f"{b:g}" for b in STUDY_SIZES), help="cube sides [m]")
    s.add_argument("--seeds", type=int, default=6, help="random specimens per size and load (seeds 1..N)")
    s.set_defaults(func=cmd_size_effect)

    d = kinds.add_parser("damping", help="one cube at several damping ratios (default: 0.96 m, 2 %% and 200 %%)",
                         formatter_class=HelpFormatter)
    common(d)
    d.add_argument("--size", type=float, default=0.96, help="cube side [m]")
    d.add_argument("--seed", type=int, default=1, help="the random specimen")
    d.add_argument("--zetas", default="0.02,2", help="damping ratios on the fundamental mode (above 1: overcritical)")
    d.set_defaults(func=cmd_damping)

    m = kinds.add_parser("mesh", help="large cubes with coarse modules and the study's criterion, "
                         "against the fine lattice", formatter_class=HelpFormatter,
                         description="Fine cubes of side L give the law of a coarse module of side L "
                                     "(ldem/study/mesh.py); coarse runs of each variant against the fine lattice.")
    common(m)
    m.add_argument("--sizes", default=",".join(f"{b:g}" for b in MESH_SIZES), help="cube sides to predict [m]")
    m.add_argument("--modules", default=",".join(f"{b:g}" for b in COARSE_MODULES), help="coarse module sides L [m]")
    m.add_argument("--variants", default=",".join(VARIANTS),
                   help="plain: the fine law; law: eps_p and CV(G_f) from the fine cube of side L; "
                        "c_a: the corrected c_a only; criterion: both; calibrated: eps_p and c_a from the "
                        "coarse and the fine lattice on the calibration cube")
    m.add_argument("--seeds", type=int, default=6, help="random specimens per case (seeds 1..N)")
    m.add_argument("--law-seeds", dest="law_seeds", type=int, default=6,
                   help="specimens of each cube that gives a law (fine cubes of side L, calibration cubes)")
    m.add_argument("--reference", action="append", default=[], metavar="DIR",
                   help="a size-effect study folder whose finished fine cases are used instead of running "
                        "them (repeatable)")
    m.add_argument("--calibration-size", dest="calibration_size", type=float, default=CALIBRATION_SIZE,
                   help="the cube on which the calibrated variant measures the coarse lattice against the fine [m]")
    m.add_argument("--report-only", action="store_true", help="run nothing: tables and report of the finished cases")
    m.add_argument("--earlier", default="", metavar="DIR",
                   help="the folder of an earlier run (a committed study keeps its tables, not its case folders): "
                        "its laws.csv gives the laws (no law cube runs) and the cases of its cases.csv are not run "
                        "again and enter the tables as they are")
    m.set_defaults(func=cmd_mesh)

    r = kinds.add_parser("refinement", help="the same cubes with modules finer than the study's",
                         formatter_class=HelpFormatter)
    common(r)
    r.set_defaults(loads="uniform")
    r.add_argument("--sizes", default=",".join(f"{b:g}" for b in REFINEMENT), help="cube sides [m]")
    r.add_argument("--L0s", default="", metavar="L0,...",
                   help="module sides for every size (default: 0.02,0.01,0.0075,0.005 for 0.12 m; "
                        "0.02,0.01,0.005 for 0.24 m)")
    r.add_argument("--corr-lengths", dest="corr_lengths", default=",".join(f"{x:g}" for x in CORR_LENGTHS),
                   help="correlation lengths of G_f [m] (0: one draw per bar)")
    r.add_argument("--seeds", type=int, default=6, help="random specimens per case (seeds 1..N)")
    r.add_argument("--report-only", action="store_true", help="run nothing: tables and report of the finished cases")
    r.add_argument("--earlier", default="", metavar="DIR",
                   help="the folder of an earlier run (a committed study keeps its tables, not its case folders): "
                        "the cases of its cases.csv are not run again and enter the tables as they are")
    r.set_defaults(func=cmd_refinement)

    b = kinds.add_parser("beams", help="the notched beams of Gregoire et al. (2013): runs, predictions, size effect",
                         formatter_class=HelpFormatter)
    b.add_argument("--out", required=True, metavar="DIR", help="study folder (cases/, tables, figures)")
    b.add_argument("--eps-p", dest="eps_p", type=float, help="eps_p of the calibration [-] (required to run)")
    b.add_argument("--seeds", type=int, default=6, help="random specimens per beam (seeds 1..N)")
    b.add_argument("--jobs", type=int, default=1, metavar="J", help="cases run at once, one thread each")
    b.add_argument("--uniform", action="store_true", help="the beams with a uniform G_f (cases_cv0/) instead")
    b.add_argument("--compare", nargs="?", const="", default=None, metavar="DATA",
                   help="run nothing: compare DIR's prediction with the measurements in DATA (default "
                        "../shared/data/gregoire2013 beside the repository holding DIR): comparison.md|png")
    b.set_defaults(func=cmd_beams)
