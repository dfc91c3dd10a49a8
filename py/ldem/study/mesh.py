"""The mesh study (issue 15): large cubes computed with coarse modules of side
L, each carrying the law that the study's "tentative criterion" gives for L,
against the fine lattice (L0 = 0.02 m) of the size-effect study.

The criterion (LDEM_SPEC section 6): a module of side L carries the
stress-strain law of a specimen of side L, with the fracture-area coefficient
corrected by the diffuse cracking measured at that size,
c_a(L) = c_a x E[U_num/U_min](L). The law of a coarse bar is the study's
triangle, fixed by eps_p, the G_f field and c_a; `criterion_law` maps the
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

(`calibrated_law`), so that what the coarse mesh adds or loses by itself
(brittler bars clamped, a softer surface layer, cracking of its own) is
measured instead of assumed to vanish."""
from __future__ import annotations

import math
import os
from typing import Dict, List, Optional, Sequence

from .. import io
from ..cube import CubeTest
from .located import MESH_CASE_COLUMNS, finished_rows, read_earlier, run_located
from .mesh_report import write_mesh_report
from .mesh_tables import FINE_L0, SUMMARY_COLUMNS, TRIANGULAR_FINAL_STRAIN, VARIANTS, summarize
from .tables import case_row, mean_cv

MESH_SIZES = (0.48, 0.72, 0.96)      # the cubes predicted with coarse modules [m]
COARSE_MODULES = (0.04, 0.06, 0.08, 0.12)
CALIBRATION_SIZE = 0.24              # the calibrated variant's cube: fine results exist, never a target [m]
UNIFORM_FINAL_STRAIN = 3.0           # a cube of a few modules separates late (0.04 m, seed 2: at a mean strain of 1.06)

LAW_COLUMNS = ("module_m", "seeds", "separated", "peak_stress_MPa_mean", "peak_stress_MPa_cv", "strain_at_peak_mean",
               "strain_at_peak_cv", "U_ratio_mean", "U_ratio_cv", "eps_p", "Gf_mean", "Gf_cv", "c_a",
               "calibration_peak_ratio", "calibration_U_ratio", "calibrated_eps_p", "calibrated_c_a")


def _round(x: float, digits: int = 4) -> float:
    return float(f"{x:.{digits}g}")


def criterion_law(fine_rows: Sequence[dict], base: CubeTest) -> dict:
    """The coarse bars' law for modules of side L from the rows (case_row) of
    the fine uniform cubes of side L: the statistics it used and the law
    (eps_p, Gf_mean, Gf_cv, c_a), as in the module's docstring."""
    separated = [r for r in fine_rows if r["separated"] in (True, "True")]
    if len(separated) < 2:
        raise ValueError(f"{len(separated)} of the fine cubes of side {fine_rows[0]['size_m']:g} m separated: "
                         "the criterion needs E[U_num/U_min] and its CV over at least two")
    peak, peak_cv = mean_cv([r["peak_stress_MPa"] for r in fine_rows])
    strain, strain_cv = mean_cv([r["strain_at_peak"] for r in fine_rows])
    ratio, ratio_cv = mean_cv([r["U_ratio"] for r in separated])
    return {"module_m": fine_rows[0]["size_m"], "seeds": len(fine_rows), "separated": len(separated),
            "peak_stress_MPa_mean": peak, "peak_stress_MPa_cv": peak_cv, "strain_at_peak_mean": strain,
            "strain_at_peak_cv": strain_cv, "U_ratio_mean": ratio, "U_ratio_cv": ratio_cv,
            "eps_p": _round(peak * 1e6 / base.E), "Gf_mean": base.Gf_mean, "Gf_cv": _round(ratio_cv),
            "c_a": _round(base.c_a * ratio)}


def calibrated_law(fine_rows: Sequence[dict], coarse_rows: Sequence[dict], base: CubeTest) -> dict:
    """The calibrated variant's eps_p and c_a for one module size, from the
    fine and the coarse (plain law) cubes of CALIBRATION_SIZE: ratios of their
    mean peaks and of their mean U_num/U_min (separated specimens)."""
    def means(rows):
        sep = [r["U_ratio"] for r in rows if r["separated"] in (True, "True")]
        if len(sep) < 2:
            raise ValueError(f"{len(sep)} calibration cubes separated: the calibrated variant needs two")
        return mean_cv([r["peak_stress_MPa"] for r in rows])[0], mean_cv(sep)[0]
    (fine_peak, fine_u), (coarse_peak, coarse_u) = means(fine_rows), means(coarse_rows)
    return {"calibration_peak_ratio": fine_peak / coarse_peak, "calibration_U_ratio": fine_u / coarse_u,
            "calibrated_eps_p": _round(base.eps_p * fine_peak / coarse_peak),
            "calibrated_c_a": _round(base.c_a * fine_u / coarse_u)}


def variant_law(variant: str, law: dict, base: CubeTest) -> dict:
    """The CubeTest fields a variant changes: none (plain), eps_p and G_f's
    statistics (law), c_a (c_a), all of them (criterion), or eps_p and c_a
    from the calibration (calibrated)."""
    keys = {"plain": (), "law": ("eps_p", "Gf_mean", "Gf_cv"), "c_a": ("c_a",),
            "criterion": ("eps_p", "Gf_mean", "Gf_cv", "c_a"), "calibrated": ("calibrated_eps_p", "calibrated_c_a")}
    if variant not in keys:
        raise ValueError(f"unknown variant '{variant}' (expected one of {', '.join(VARIANTS)})")
    fields = {k: k.replace("calibrated_", "") for k in keys[variant]}
    return {f: law[k] for k, f in fields.items() if law[k] != getattr(base, f)}


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

