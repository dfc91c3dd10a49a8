"""Studies: many cube tests (size x seed x load, or one parameter swept), run
in parallel processes or on a dask.distributed cluster, resumable, aggregated
into the tables of the reference study (LDEM_SPEC section 6).

    ldem study size-effect --out DIR [--sizes 0.12,0.24] [--seeds 6] [--loads uniform,triangular] [--jobs J]
    ldem study damping     --out DIR [--size 0.96] [--zetas 0.02,2]

Layout of DIR: one folder per case, DIR/cases/<name>/ (curve.csv, summary.json,
cracks.png, slice.npz), then cases.csv, summary.csv, fractal.json, the figures
and report.md (ldem.report). A case is finished when its summary.json says
"done" for exactly the same parameters; any other case folder (interrupted,
failed, other parameters) is computed again from scratch, so a study resumes
where it stopped and never recomputes a finished case.
"""
from __future__ import annotations

import csv
import dataclasses
import json
import math
import os
import shutil
import sys
import time
from typing import Callable, Dict, Iterable, List, Optional, Sequence

import numpy as np

from .cube import CubeTest

REFERENCE_UNIFORM = {  # Table 3 of the study (LDEM_SPEC section 6): size -> (peak MPa, strain at peak)
    0.12: (2.45, 1.47e-4), 0.24: (2.48, 1.41e-4), 0.48: (2.52, 1.50e-4), 0.72: (2.53, 1.50e-4),
    0.96: (2.52, 1.46e-4),
}
STUDY_SIZES = (0.12, 0.24, 0.48, 0.72, 0.96)
B0 = 0.12  # reference size of the fractal law [m]


# -- cases ---------------------------------------------------------------------
def case_name(test: CubeTest) -> str:
    """load_size_seed, then every parameter that differs from CubeTest's defaults
    (threads aside: they do not change the result)."""
    name = f"{test.load}_{test.size:g}m_s{test.seed}"
    default = CubeTest()
    for f in dataclasses.fields(CubeTest):
        if f.name in ("load", "size", "seed", "threads"):
            continue
        v = getattr(test, f.name)
        if v != getattr(default, f.name):
            name += f"_{f.name}{v:g}" if isinstance(v, float) else f"_{f.name}{v}"
    return name


def case_dir(out: str, test: CubeTest) -> str:
    """Where a study in directory out keeps the case of test."""
    return os.path.join(out, "cases", case_name(test))


def _comparable(params: dict) -> dict:
    """The parameters that decide a case's result; one declared after the case
    ran counts at its default (the run it would have made is the same)."""
    defaults = {f.name: f.default for f in dataclasses.fields(CubeTest)}
    return {k: params.get(k, d) for k, d in defaults.items() if k != "threads"}


def is_finished(case_dir: str, test: CubeTest) -> bool:
    try:
        with open(os.path.join(case_dir, "summary.json")) as f:
            s = json.load(f)
    except (OSError, ValueError):
        return False
    return (s.get("status") == "done" and _comparable(s.get("parameters", {})) == _comparable(test.parameters())
            and os.path.exists(os.path.join(case_dir, "slice.npz")))


def run_case(params: dict, case_dir: str) -> dict:
    """Runs one case into case_dir (emptied first) and returns its summary.
    A top-level function, so that worker processes and dask can call it."""
    from . import plots

    if os.path.isdir(case_dir):
        shutil.rmtree(case_dir)  # half-finished or stale: start afresh
    test = CubeTest(**params)
    result = test.run(out=case_dir, progress=False, plots=False)
    seg, state = plots.central_slice(result.sim)
    # Written last: its presence marks the case finished (with summary.json "done").
    np.savez_compressed(os.path.join(case_dir, "slice.npz"), segments=seg.astype(np.float32), states=state)
    plots.crack_figure_from_slice(seg, state, os.path.join(case_dir, "cracks.png"),
                                  title=f"{test.size:g} m, {test.load}, seed {test.seed}")
    return result.summary


def _default_threads(jobs: int) -> int:
    return max(1, (os.cpu_count() or 1) // max(1, jobs))


def run_cases(tests: Sequence[CubeTest], out: str, jobs: int = 1, scheduler: Optional[str] = None,
              progress: Optional[bool] = None, log: Callable[[str], None] = print) -> List[dict]:
    """Runs every test not finished yet (in `jobs` processes, or on the dask
    cluster at `scheduler`) and returns the summaries of all, in order."""
    from .output import prepare_dir

    if jobs < 1:
        raise ValueError(f"--jobs must be at least 1 (got {jobs})")
    prepare_dir(out)
    dirs = [case_dir(out, t) for t in tests]
    if len(set(dirs)) != len(dirs):
        raise ValueError("two cases of the study have the same parameters")
    todo = [i for i, (t, d) in enumerate(zip(tests, dirs)) if not is_finished(d, t)]
    if len(todo) < len(tests):
        log(f"{len(tests) - len(todo)} of {len(tests)} cases already finished in {out}/cases")
    bar = _Progress(len(tests), len(tests) - len(todo), progress)
    args = [(tests[i].parameters(), dirs[i]) for i in todo]

    def finished(i, summary):
        bar.step()
        log(f"  {case_name(tests[i])}: peak {summary['peak_stress_MPa']:.4f} MPa at {summary['strain_at_peak']:.4e}, "
            + (f"U_num/U_min {summary['U_ratio']:.3f}" if summary.get("separated") else "NOT separated")
            + (", ENERGY ERROR" if summary.get("energy_error") else "") + f", {summary['wall_s']:.1f} s")

    try:
        if scheduler:
            _run_on_dask(scheduler, todo, args, finished)
        elif jobs == 1 or len(todo) <= 1:
            for i, (p, d) in zip(todo, args):
                finished(i, run_case(p, d))
        else:
            _run_in_processes(jobs, todo, args, finished)
    finally:
        bar.close()
    return [load_summary(d) for d in dirs]


def _run_in_processes(jobs, todo, args, finished):
    import concurrent.futures as cf
    import multiprocessing

    # spawn, not fork: a forked OpenMP runtime can hang in the child.
    with cf.ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = {pool.submit(run_case, p, d): i for i, (p, d) in zip(todo, args)}
        try:
            for fut in cf.as_completed(futures):
                finished(futures[fut], fut.result())
        except BaseException:
            for fut in futures:
                fut.cancel()
            raise


def _run_on_dask(address, todo, args, finished):
    from distributed import Client, as_completed

    with Client(address) as client:
        futures = [client.submit(run_case, p, d, pure=False) for p, d in args]
        index = {f.key: i for f, i in zip(futures, todo)}
        for fut in as_completed(futures):
            finished(index[fut.key], fut.result())


class _Progress:
    """Overall progress over cases (tqdm on a terminal, silent otherwise)."""

    def __init__(self, total, done, enabled):
        self._bar = None
        if enabled if enabled is not None else sys.stderr.isatty():
            from tqdm import tqdm
            self._bar = tqdm(total=total, initial=done, unit="case", desc="study", file=sys.stderr)

    def step(self):
        if self._bar is not None:
            self._bar.update(1)

    def close(self):
        if self._bar is not None:
            self._bar.close()


def load_summary(case_dir: str) -> dict:
    with open(os.path.join(case_dir, "summary.json")) as f:
        return json.load(f)


def load_curve(case_dir: str) -> dict:
    data = np.genfromtxt(os.path.join(case_dir, "curve.csv"), delimiter=",", names=True)
    return {k: np.atleast_1d(data[k]) for k in data.dtype.names}


def load_curves(out: str, tests: Sequence[CubeTest]) -> Dict[tuple, List[dict]]:
    """(load, size) -> the curves of its specimens in study directory out, in test order."""
    groups: Dict[tuple, List[dict]] = {}
    for t in tests:
        groups.setdefault((t.load, t.size), []).append(load_curve(case_dir(out, t)))
    return groups


def mean_curve(curves: Sequence[dict], column: str, scale=1.0, after_end=None, n: int = 400, log_from=None):
    """Mean of a curve column over specimens on a common mean-strain grid of n
    points (linear from 0, or geometric from log_from). A specimen that stopped
    early carries on at after_end (0 for the stress of a separated specimen), or
    at its last value (the final fracture energy)."""
    top = max(c["mean_strain"][-1] for c in curves)
    grid = np.linspace(0.0, top, n) if log_from is None else np.geomspace(log_from, top, n)
    ys = [np.interp(grid, c["mean_strain"], c[column] * scale,
                    right=(c[column] * scale)[-1] if after_end is None else after_end) for c in curves]
    return grid, np.mean(ys, axis=0)


def mean_curve_peak(curves: Sequence[dict]) -> tuple:
    """(peak stress [MPa], its mean strain) of the specimens' mean stress-strain
    curve, on a grid finer than the records (about 1e-8 in strain)."""
    grid, stress = mean_curve(curves, "stress_MPa", after_end=0.0, n=20001)
    i = int(np.argmax(stress))
    return float(stress[i]), float(grid[i])


# -- the studies ---------------------------------------------------------------
def size_effect_tests(sizes: Iterable[float], seeds: int, loads: Iterable[str], **common) -> List[CubeTest]:
    return [CubeTest(size=s, load=ld, seed=k, **common) for ld in loads for s in sizes for k in range(1, seeds + 1)]


def damping_tests(size: float, zetas: Iterable[float], loads: Iterable[str], seed: int = 1,
                  **common) -> List[CubeTest]:
    return [CubeTest(size=size, load=ld, seed=seed, zeta=z, **common) for ld in loads for z in zetas]


# -- aggregation ---------------------------------------------------------------
CASE_COLUMNS = ("load", "size_m", "seed", "zeta", "strain_rate", "peak_stress_MPa", "strain_at_peak",
                "edge_strain_at_peak", "separated", "separation_strain", "U_num_J", "U_min_J", "U_ratio",
                "load_loss_strain", "U_loss_J", "U_loss_ratio", "U_mincut_J", "U_mincut_ratio",
                "energy_balance_error", "energy_error", "clamped_bars", "n_bars", "steps", "dt_s", "threads",
                "wall_s", "stop_reason")


def case_row(s: dict) -> dict:
    """One case's row: U_num is the energy at separation, empty if the run ended
    without separating (its energy at the end is never presented as U_num)."""
    p = s["parameters"]
    u_min = s["min_fracture_energy_J"]
    loss, sep = s.get("load_loss") or {}, s.get("separation") or {}
    return {"load": p["load"], "size_m": p["size"], "seed": p["seed"], "zeta": p["zeta"],
            "strain_rate": p["strain_rate"], "peak_stress_MPa": s["peak_stress_MPa"],
            "strain_at_peak": s["strain_at_peak"], "edge_strain_at_peak": s["edge_strain_at_peak"],
            "separated": bool(s["separated"]), "separation_strain": sep.get("mean_strain", ""),
            "U_num_J": s["U_num_J"] if s["separated"] else "", "U_min_J": u_min,
            "U_ratio": s["U_ratio"] if s["separated"] else "",
            "load_loss_strain": loss.get("mean_strain", ""), "U_loss_J": loss.get("fracture_energy_J", ""),
            "U_loss_ratio": loss["fracture_energy_J"] / u_min if loss else "",
            "U_mincut_J": s["U_mincut_J"], "U_mincut_ratio": s["U_mincut_J"] / u_min,
            "energy_balance_error": s["energy_balance_error"], "energy_error": bool(s["energy_error"]),
            "clamped_bars": s["clamped_bars"], "n_bars": s["n_bars"], "steps": s["steps"], "dt_s": s["dt_s"],
            "threads": s["threads"], "wall_s": s["wall_s"], "stop_reason": s["stop_reason"]}


def mean_cv(values) -> tuple:
    """Mean and coefficient of variation (sample standard deviation, n - 1, over the mean)."""
    v = np.asarray(values, dtype=float)
    m = float(v.mean())
    cv = float(v.std(ddof=1) / abs(m)) if len(v) > 1 and m != 0 else 0.0
    return m, cv


SUMMARY_COLUMNS = ("load", "size_m", "seeds", "separated", "energy_errors", "peak_stress_MPa_mean",
                   "peak_stress_MPa_cv", "strain_at_peak_mean", "strain_at_peak_cv", "edge_strain_at_peak_mean",
                   "separation_strain_mean", "U_num_J_mean", "U_min_J", "U_ratio_mean", "U_ratio_cv",
                   "U_loss_ratio_mean", "U_loss_ratio_cv",
                   "U_mincut_ratio_mean", "U_mincut_ratio_cv", "ca_corrected", "ref_peak_stress_MPa",
                   "ref_strain_at_peak", "mean_curve_peak_MPa", "mean_curve_strain_at_peak", "wall_s_mean")


def _mean_cv_or_empty(values) -> tuple:
    values = [v for v in values if v != ""]
    return mean_cv(values) if values else ("", "")


def aggregate(rows: Sequence[dict], c_a: float, curves: Optional[Dict[tuple, List[dict]]] = None) -> List[dict]:
    """One row per (load, size): means and CVs over the seeds, the corrected
    c_a = c_a x E[U_num/U_min], and Table 3's values where the study gives them.
    U_num and its ratio are averaged over the separated specimens only (the
    column `separated` counts them); `energy_errors` counts the flagged runs.
    With the specimens' curves ((load, size) -> curves), also the peak of their
    mean curve: the mean of the peaks is not the peak of the mean curve, and
    the study does not say which of the two its Table 3 gives."""
    out = []
    for load in dict.fromkeys(r["load"] for r in rows):
        for size in sorted({r["size_m"] for r in rows if r["load"] == load}):
            g = [r for r in rows if r["load"] == load and r["size_m"] == size]
            peak, peak_cv = mean_cv([r["peak_stress_MPa"] for r in g])
            strain, strain_cv = mean_cv([r["strain_at_peak"] for r in g])
            ratio, ratio_cv = _mean_cv_or_empty([r["U_ratio"] for r in g])
            loss, loss_cv = _mean_cv_or_empty([r["U_loss_ratio"] for r in g])
            cut, cut_cv = mean_cv([r["U_mincut_ratio"] for r in g])
            u_num = [r["U_num_J"] for r in g if r["U_num_J"] != ""]
            sep_strain = [r["separation_strain"] for r in g if r["separation_strain"] != ""]
            ref = REFERENCE_UNIFORM.get(round(size, 6)) if load == "uniform" else None
            out.append({"load": load, "size_m": size, "seeds": len(g),
                        "separated": sum(1 for r in g if r["separated"] in (True, "True")),
                        "energy_errors": sum(1 for r in g if r["energy_error"] in (True, "True")),
                        "peak_stress_MPa_mean": peak, "peak_stress_MPa_cv": peak_cv, "strain_at_peak_mean": strain,
                        "strain_at_peak_cv": strain_cv,
                        "edge_strain_at_peak_mean": float(np.mean([r["edge_strain_at_peak"] for r in g])),
                        "separation_strain_mean": float(np.mean(sep_strain)) if sep_strain else "",
                        "U_num_J_mean": float(np.mean(u_num)) if u_num else "", "U_min_J": g[0]["U_min_J"],
                        "U_ratio_mean": ratio, "U_ratio_cv": ratio_cv, "U_loss_ratio_mean": loss,
                        "U_loss_ratio_cv": loss_cv, "U_mincut_ratio_mean": cut, "U_mincut_ratio_cv": cut_cv,
                        "ca_corrected": c_a * ratio if ratio != "" else "",
                        "ref_peak_stress_MPa": ref[0] if ref else "", "ref_strain_at_peak": ref[1] if ref else "",
                        "mean_curve_peak_MPa": "", "mean_curve_strain_at_peak": "",
                        "wall_s_mean": float(np.mean([r["wall_s"] for r in g]))})
            if curves is not None:
                out[-1]["mean_curve_peak_MPa"], out[-1]["mean_curve_strain_at_peak"] = \
                    mean_curve_peak(curves[(load, size)])
    return out


def fit_fractal(sizes, energies, b0: float = B0) -> dict:
    """Carpinteri-Chiaia's fractal law U(b) = U(b0) (b/b0)^d, with U(b0) the
    value at the reference size b0: least squares of ln(U/U(b0)) = d ln(b/b0),
    a line through the origin, so d = sum(x y) / sum(x^2).
    Also the exponent of the energy per unit area, U/b^2 ~ b^(d - 2)."""
    b = np.asarray(sizes, dtype=float)
    u = np.asarray(energies, dtype=float)
    ref = np.isclose(b, b0)
    if not ref.any():
        raise ValueError(f"the fractal fit needs the reference size b0 = {b0} m")
    if len(b) < 2 or np.any(u <= 0):
        raise ValueError("the fractal fit needs at least two sizes with positive energies")
    u0 = float(u[ref][0])
    x, y = np.log(b / b0), np.log(u / u0)
    d = float(np.dot(x, y) / np.dot(x, x))
    resid = y - d * x
    return {"b0_m": b0, "U_b0_J": u0, "d": d, "d_specific": d - 2.0,
            "rms_log_residual": float(np.sqrt(np.mean(resid ** 2)))}


def write_csv(path: str, rows: Sequence[dict], columns: Sequence[str]) -> None:
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(columns), extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def read_csv(path: str) -> List[dict]:
    def conv(v):
        try:
            return int(v)
        except ValueError:
            try:
                return float(v)
            except ValueError:
                return v
    with open(path, newline="") as f:
        return [{k: conv(v) for k, v in r.items()} for r in csv.DictReader(f)]


# -- commands ------------------------------------------------------------------
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
    fields = {f.name: f for f in dataclasses.fields(CubeTest)}
    out = {}
    for pair in pairs:
        name, sep, value = pair.partition("=")
        name = name.strip().replace("-", "_")
        if not sep or name not in fields:
            raise ValueError(f"--set takes NAME=VALUE with NAME a field of ldem.CubeTest (got '{pair}')")
        if name in ("size", "load", "seed"):
            raise ValueError(f"--set {name}: the study sets it (use its own options)")
        try:
            out[name] = type(fields[name].default)(value)
        except ValueError:
            raise ValueError(f"--set {name}: '{value}' is not a {type(fields[name].default).__name__}") from None
    return out


def _common(args) -> dict:
    threads = args.threads if args.threads > 0 else _default_threads(1 if args.scheduler else args.jobs)
    return {"threads": threads, "strain_rate": args.strain_rate, **_settings(args.set)}


def _check_tests(tests: Sequence[CubeTest]) -> None:
    """Every case's input checked before anything runs."""
    for t in tests:
        t.modules()
        t.core_params()


def cmd_size_effect(args) -> int:
    from . import report

    sizes = _floats(args.sizes, "--sizes")
    if args.seeds < 1:
        raise ValueError(f"--seeds must be at least 1 (got {args.seeds})")
    tests = size_effect_tests(sizes, args.seeds, _loads(args.loads), **_common(args))
    _check_tests(tests)
    t0 = time.perf_counter()
    summaries = run_cases(tests, args.out, jobs=args.jobs, scheduler=args.scheduler,
                          progress=False if args.no_progress else None)
    rows = [case_row(s) for s in summaries]
    write_csv(os.path.join(args.out, "cases.csv"), rows, CASE_COLUMNS)
    curves = load_curves(args.out, tests)
    table = aggregate(rows, tests[0].c_a, curves)
    write_csv(os.path.join(args.out, "summary.csv"), table, SUMMARY_COLUMNS)
    fits = {}
    for load in dict.fromkeys(r["load"] for r in table):
        g = [r for r in table if r["load"] == load]
        g = [r for r in g if r["U_num_J_mean"] != ""]  # sizes with separated specimens
        if len(g) >= 2 and any(math.isclose(r["size_m"], B0) for r in g):
            fits[load] = fit_fractal([r["size_m"] for r in g], [r["U_num_J_mean"] for r in g])
    with open(os.path.join(args.out, "fractal.json"), "w") as f:
        json.dump(fits, f, indent=2)
    if not args.no_report:
        report.size_effect_report(args.out, tests, rows, table, fits, curves)
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
    from . import report

    zetas = _floats(args.zetas, "--zetas")
    if any(z < 0 for z in zetas):
        raise ValueError("damping ratios must be >= 0")
    common = _common(args)
    if "zeta" in common:
        raise ValueError("--set zeta: the damping study sets it (use --zetas)")
    tests = damping_tests(args.size, zetas, _loads(args.loads), seed=args.seed, **common)
    _check_tests(tests)
    summaries = run_cases(tests, args.out, jobs=args.jobs, scheduler=args.scheduler,
                          progress=False if args.no_progress else None)
    rows = [case_row(s) for s in summaries]
    write_csv(os.path.join(args.out, "damping.csv"), rows, CASE_COLUMNS)
    if not args.no_report:
        report.damping_figures(args.out, tests)
    for r in rows:
        print(f"  {r['load']:10s} zeta {r['zeta']:g}: peak {r['peak_stress_MPa']:.4f} MPa at "
              f"{r['strain_at_peak']:.4e}, U_num/U_min "
              + (f"{r['U_ratio']:.3f}" if r["separated"] else "(not separated)"))
    return 0


def add_parser(sub) -> None:
    import argparse

    p = sub.add_parser("study", help="the size-effect and damping studies of the reference paper",
                       description="Runs many cube tests (resumable, in parallel) and aggregates them.")
    kinds = p.add_subparsers(dest="study", metavar="STUDY", parser_class=type(p))
    kinds.required = True

    def common(q):
        q.add_argument("--out", required=True, metavar="DIR", help="study folder (cases/, tables, figures, report)")
        q.add_argument("--loads", default="uniform,triangular", help="comma-separated loads")
        q.add_argument("--jobs", type=int, default=1, metavar="J", help="cases run at once in separate processes")
        q.add_argument("--threads", type=int, default=0, metavar="T",
                       help="OpenMP threads per case (0: cores / jobs)")
        q.add_argument("--scheduler", default=None, metavar="ADDRESS",
                       help="send cases to this dask.distributed scheduler instead (e.g. tcp://host:8786)")
        q.add_argument("--strain-rate", dest="strain_rate", type=float, default=CubeTest().strain_rate,
                       help="vertical strain rate [1/s]")
        q.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                       help="any other CubeTest parameter for every case, e.g. --set bottom_lateral=free "
                            "(repeatable; see ldem cube --help)")
        q.add_argument("--no-progress", action="store_true", help="no progress bar")
        q.add_argument("--no-report", action="store_true", help="tables only: no figures, no report.md")

    s = kinds.add_parser("size-effect", help="sizes x seeds x loads: tables, curves, cracks, energies, fractal fit",
                         formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    common(s)
    s.add_argument("--sizes", default=",".join(f"{b:g}" for b in STUDY_SIZES), help="cube sides [m]")
    s.add_argument("--seeds", type=int, default=6, help="random specimens per size and load (seeds 1..N)")
    s.set_defaults(func=cmd_size_effect)

    d = kinds.add_parser("damping", help="one cube at several damping ratios (default: 0.96 m, 2 %% and 200 %%)",
                         formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    common(d)
    d.add_argument("--size", type=float, default=0.96, help="cube side [m]")
    d.add_argument("--seed", type=int, default=1, help="the random specimen")
    d.add_argument("--zetas", default="0.02,2", help="damping ratios on the fundamental mode (above 1: overcritical)")
    d.set_defaults(func=cmd_damping)
