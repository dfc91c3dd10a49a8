"""The mesh study: large cubes computed with coarse modules of side L, each
carrying the law that the study's "tentative criterion" gives for L,
against the fine lattice (L0 = 0.02 m) of the size-effect study.

The criterion (LDEM_SPEC section 6): a module of side L carries the
stress-strain law of a specimen of side L, with the fracture-area coefficient
corrected by the diffuse cracking measured at that size,
c_a(L) = c_a x E[U_num/U_min](L). The law of a coarse bar is the study's
triangle, fixed by eps_p, the G_f field and c_a; `tables.criterion_law` maps the
fine cubes of side L (uniform load, six seeds, to separation) onto them:

    eps_p(L)   = mean peak stress(L) / E        a coarse bar starts to soften at
                                                the stress where a fine cube of
                                                its size peaks (a fine bar at
                                                E eps_p: identity at L = L0)
    E[G_f](L)  = E[G_f]                         the material's energy per unit
                                                area; the size dependence of
                                                the energy goes through c_a
    CV(G_f)(L) = CV(U_num)(L)                   a coarse bar's energy scatters
                                                as the energy to split a fine
                                                cube of its size
    c_a(L)     = c_a x E[U_num/U_min](L)        the study's correction

The strain at the peak and the CV of the peak are reported, not mapped: the
bar is linear with the material's E up to eps_p (matching the peak stress
fixes eps_p; matching its strain too would need another E), and eps_p is not
random in the model. Values are rounded to 4 significant digits.

Variants (the ablation): plain (the fine law on the coarse mesh), law (eps_p
and CV(G_f) only), c_a (the corrected c_a only), criterion (all); and a
proposal, calibrated: the coarse lattice's own peak and cracking measured on
a cube of CALIBRATION_SIZE (never a target), against the fine lattice's,

    eps_p'(L) = eps_p x fine peak / coarse peak          (of the 0.24 m cube)
    c_a'(L)   = c_a x fine U_num/U_min / coarse U_num/U_min
    CV(G_f)   = the material's

(`tables.calibrated_law`), so that what the coarse mesh adds or loses by itself
(brittler bars clamped, a softer surface layer, cracking of its own) is
measured instead of assumed to vanish."""
from __future__ import annotations

import math
import os
from typing import Dict, List, Optional, Sequence

from ... import io
from ...cube import CubeTest
from ..located import MESH_CASE_COLUMNS, finished_rows, read_earlier, run_located
from .report import write_mesh_report
from ..options import (add_common, add_rerun_options, add_seeds, common_settings, parse_floats,
                       parse_loads, parse_names, run_options, seed_count, values_option)
from ..registry import Study, register
from .tables import (FINE_L0, SUMMARY_COLUMNS, TRIANGULAR_FINAL_STRAIN, VARIANTS, calibrated_law, criterion_law,
                     summarize, variant_law)
from ..tables import case_row

MESH_SIZES = (0.48, 0.72, 0.96)      # the cubes predicted with coarse modules [m]
COARSE_MODULES = (0.04, 0.06, 0.08, 0.12)
CALIBRATION_SIZE = 0.24              # the calibrated variant's cube: fine results exist, never a target [m]
UNIFORM_FINAL_STRAIN = 3.0           # a cube of a few modules separates late (0.04 m, seed 2: at a mean strain of 1.06)

LAW_COLUMNS = ("module_m", "seeds", "separated", "peak_stress_MPa_mean", "peak_stress_MPa_cv", "strain_at_peak_mean",
               "strain_at_peak_cv", "U_ratio_mean", "U_ratio_cv", "eps_p", "Gf_mean", "Gf_cv", "c_a",
               "calibration_peak_ratio", "calibration_U_ratio", "calibrated_eps_p", "calibrated_c_a")


def load_settings(load: str, reference: bool = False) -> dict:
    """What a load changes in a case: triangular cubes stop past the peak;
    uniform ones run to separation however late, except the fine references,
    which keep the size-effect study's settings (they separate by 0.05)."""
    if load == "triangular":
        return {"final_strain": TRIANGULAR_FINAL_STRAIN}
    return {} if reference else {"final_strain": UNIFORM_FINAL_STRAIN}


def law_tests(modules: Sequence[float], seeds: int, **common) -> List[CubeTest]:
    """The fine uniform cubes of side L (L0 = 0.02 m) the criterion reads."""
    return [CubeTest(size=m, L0=FINE_L0, load="uniform", seed=k, **{**load_settings("uniform"), **common})
            for m in modules for k in range(1, seeds + 1)]


def fine_tests(sizes, loads, seeds: int, **common) -> List[CubeTest]:
    return [CubeTest(size=s, L0=FINE_L0, load=ld, seed=k, **{**load_settings(ld, reference=True), **common})
            for s in sizes for ld in loads for k in range(1, seeds + 1)]


def _divides(part: float, whole: float) -> bool:
    return math.isclose(whole / part, round(whole / part), rel_tol=0, abs_tol=1e-9)


def check_grid(sizes: Sequence[float], modules: Sequence[float]) -> None:
    """Before anything runs: each module side L a multiple of the fine L0 (its
    law comes from a fine cube of side L), each size a multiple of each L."""
    for m in modules:
        if m <= 0 or not _divides(FINE_L0, m):
            raise ValueError(f"module {m:g} m: the criterion reads a fine cube of that side, which must be a "
                             f"positive multiple of L0 = {FINE_L0:g} m")
        for s in sizes:
            if not _divides(m, s):
                raise ValueError(f"a {s:g} m cube cannot be cut into modules of {m:g} m")


def coarse_tests(sizes, modules, variants, loads, seeds: int, laws: Dict[float, dict], **common) -> List[tuple]:
    """(variant, test) for every coarse case; a variant whose law equals
    another's (e.g. c_a when the correction is 1) is still its own case."""
    base = CubeTest(**common)
    out = []
    check_grid(sizes, modules)
    for s in sizes:
        for m in modules:
            for v in variants:
                law = variant_law(v, laws[m], base)
                out += [(v, CubeTest(size=s, L0=m, load=ld, seed=k, **{**load_settings(ld), **common, **law}))
                        for ld in loads for k in range(1, seeds + 1)]
    return out


def read_laws(out: str) -> Dict[float, dict]:
    """laws.csv of study folder out: module side -> its law."""
    return {r["module_m"]: r for r in io.read_table(os.path.join(out, "laws.csv"))}


def calibration_tests(modules, seeds: int, size: float = CALIBRATION_SIZE, **common) -> List[CubeTest]:
    """The fine cubes of the calibration size, then the coarse ones (plain law) per module."""
    return (fine_tests([size], ["uniform"], seeds, **common)
            + [CubeTest(size=size, L0=m, load="uniform", seed=k, **{**load_settings("uniform"), **common})
               for m in modules for k in range(1, seeds + 1)])


def run_laws(modules, seeds: int, out: str, references=(), run: bool = True, calibrate: bool = True,
             calibration_size: float = CALIBRATION_SIZE, common: Optional[dict] = None, **kw) -> Dict[float, dict]:
    """Runs (or finds) the fine cubes of side L (and, with calibrate, the
    calibration cubes), writes laws.csv and returns L -> law."""
    common = dict(common or {})
    base = CubeTest(**common)
    tests = law_tests(modules, seeds, **common)
    cal = calibration_tests(modules, seeds, calibration_size, **common) if calibrate else []
    summaries = run_located(tests + cal, out, references, run=run, **kw)

    def finished(tests_, summaries_):
        return [(t, case_row(s)) for t, (s, _) in zip(tests_, summaries_) if s is not None]
    law_rows, cal_rows = finished(tests, summaries[:len(tests)]), finished(cal, summaries[len(tests):])
    laws = {}
    for m in modules:
        fine = [r for t, r in law_rows if t.size == m]
        if fine:
            laws[m] = criterion_law(fine, base)
        cal_fine = [r for t, r in cal_rows if t.L0 == FINE_L0]
        cal_coarse = [r for t, r in cal_rows if t.L0 == m]
        if m in laws and cal_fine and cal_coarse:
            laws[m].update(calibrated_law(cal_fine, cal_coarse, base))
    io.prepare_dir(out)
    io.write_table(os.path.join(out, "laws.csv"), list(laws.values()), LAW_COLUMNS)
    missing = [m for m in modules if m not in laws or (calibrate and "calibrated_c_a" not in laws[m])]
    if missing:
        raise ValueError(f"the cubes that give the law of modules of {', '.join(f'{m:g}' for m in missing)} m "
                         "are not finished: "
                         "run without --report-only first")
    return laws


def run_mesh(out: str, sizes=MESH_SIZES, modules=COARSE_MODULES, variants=VARIANTS, loads=("uniform", "triangular"),
             seeds: int = 6, references: Sequence[str] = (), run: bool = True, report: bool = True,
             common: Optional[dict] = None, fmt: str = "png", calibration_size: float = CALIBRATION_SIZE,
             law_seeds: int = 6, earlier: str = "", **kw) -> List[dict]:
    """The whole study: the fine cubes of side L and their laws (laws.csv;
    law_seeds specimens each, whatever the seeds of the targets), the
    fine references (found in `references`, size-effect study folders, or run
    here), the coarse cases; cases.csv, summary.csv and (with report)
    report.md with its figures. With run False nothing is computed: the
    tables cover the finished cases. earlier: the folder of an earlier run,
    whose laws.csv gives the laws (its law cubes are not run again) and whose
    cases.csv rows are kept (finished_rows). Returns the summary rows."""
    common = dict(common or {})
    calibrate = "calibrated" in variants
    check_grid(sizes, modules)
    if calibrate:
        check_grid([calibration_size], modules)
        if any(math.isclose(calibration_size, s) for s in sizes):
            raise ValueError(f"the calibration cube ({calibration_size:g} m) must not be one of the cubes predicted")
    done = read_earlier(earlier, ("laws.csv", "cases.csv"))
    if earlier:
        laws = earlier_laws(earlier, modules, calibrate, out)
    else:
        laws = run_laws(modules, law_seeds, out, references, run=run, calibrate=calibrate,
                        calibration_size=calibration_size, common=common, **kw)
    fine = fine_tests(sizes, loads, seeds, **common)
    coarse = coarse_tests(sizes, modules, variants, loads, seeds, laws, **common)
    roles = [("fine", "fine")] * len(fine) + [("coarse", v) for v, _ in coarse]
    rows, kept = finished_rows(fine + [t for _, t in coarse], roles, out, references, done, run=run, **kw)
    io.write_table(os.path.join(out, "cases.csv"), rows, MESH_CASE_COLUMNS)
    table = summarize(rows)
    io.write_table(os.path.join(out, "summary.csv"), table, SUMMARY_COLUMNS)
    if report:
        write_mesh_report(out, laws, table, rows, len(fine) + len(coarse) - len(rows), fmt, kept, earlier)
    return table


def earlier_laws(folder: str, modules, calibrate: bool, out: str) -> Dict[float, dict]:
    """The laws of an earlier run's laws.csv for `modules`, written to out's."""
    found = read_laws(folder)
    laws = {}
    for m in modules:
        law = next((w for L, w in found.items() if math.isclose(L, m)), None)
        if law is None or (calibrate and law.get("calibrated_c_a", "") == ""):
            raise ValueError(f"--earlier {folder}: its laws.csv has no {'calibrated ' if calibrate else ''}law "
                             f"for modules of {m:g} m")
        laws[m] = law
    io.prepare_dir(out)
    io.write_table(os.path.join(out, "laws.csv"), list(laws.values()), LAW_COLUMNS)
    return laws



def add_arguments(m) -> None:
    add_common(m)
    values_option(m, "size", "--sizes", MESH_SIZES, "; the cubes to predict")
    values_option(m, "L0", "--modules", COARSE_MODULES, "; the coarse modules L")
    m.add_argument("--variants", default=",".join(VARIANTS),
                   help="plain: the fine law; law: eps_p and CV(G_f) from the fine cube of side L; "
                        "c_a: the corrected c_a only; criterion: both; calibrated: eps_p and c_a from the "
                        "coarse and the fine lattice on the calibration cube")
    add_seeds(m)
    m.add_argument("--law-seeds", dest="law_seeds", type=int, default=6,
                   help="specimens of each cube that gives a law (fine cubes of side L, calibration cubes)")
    m.add_argument("--reference", action="append", default=[], metavar="DIR",
                   help="a size-effect study folder whose finished fine cases are used instead of running "
                        "them (repeatable)")
    m.add_argument("--calibration-size", dest="calibration_size", type=float, default=CALIBRATION_SIZE,
                   help="the cube on which the calibrated variant measures the coarse lattice against the fine [m]")
    add_rerun_options(m, "its laws.csv gives the laws (no law cube runs) and the cases of its cases.csv "
                                 "are not run again and enter the tables as they are")


def cmd_mesh(args) -> int:
    variants = parse_names(args.variants, VARIANTS, "variant", "some of " + ", ".join(VARIANTS))
    for ref in args.reference:
        if not os.path.isdir(os.path.join(ref, "cases")):
            raise ValueError(f"--reference {ref}: not a study folder (no cases/ in it)")
    common = common_settings(args)
    for name in ("L0", "eps_p", "Gf_mean", "Gf_cv", "c_a"):
        if name in common:
            raise ValueError(f"--set {name}: the mesh study sets it (from the criterion)")
    if args.law_seeds < 2:
        raise ValueError(f"--law-seeds must be at least 2: the law needs a mean and a CV (got {args.law_seeds})")
    table = run_mesh(args.out, parse_floats(args.sizes, "--sizes"), parse_floats(args.modules, "--modules"),
                     variants, parse_loads(args.loads), seed_count(args), args.reference,
                     run=not args.report_only, report=not args.no_report, common=common, fmt=args.figure_format,
                     calibration_size=args.calibration_size, law_seeds=args.law_seeds, earlier=args.earlier,
                     **run_options(args))
    print(f"mesh study: wrote {args.out}/laws.csv, cases.csv, summary.csv"
          + ("" if args.no_report else ", report.md and figures"))
    for t in table:
        print(f"  {t['load']:10s} {t['size_m']:.2f} m, L {t['module_m']:.3f} m, {t['variant']:9s}: "
              f"peak {t['peak_stress_MPa_mean']:.3f} MPa" + (f" ({t['peak_vs_fine']:.3f} of fine)"
                                                              if t["peak_vs_fine"] != "" else "")
              + ("" if t["U_ratio_mean"] == "" else f", U_num/U_min {t['U_ratio_mean']:.3f}")
              + ("" if t["U_vs_fine"] == "" else f" ({t['U_vs_fine']:.3f} of fine)"))
    return 0


register(Study("mesh", "large cubes with coarse modules and the study's criterion, against the fine lattice",
               add_arguments, cmd_mesh, "Fine cubes of side L give the law of a coarse module of side L "
                                        "(ldem.study.mesh says why); coarse runs of each variant against the fine lattice."))
