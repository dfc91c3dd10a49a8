"""The settings the reference study does not report, one at a time: what each
does to the uniform cube's peak and its strain at 0.12 and 0.96 m, against
Table 3's flat peaks (LDEM_SPEC section 6).

The study gives no strain rate ("constant strain rate", a displacement that
"increases smoothly in time"), nor the mode its damping ratio is stated on,
nor the upper nodes' lateral freedom, nor how its Weibull field of G_f is drawn
(per bar or per module, correlation length, lower bound). Each setting below
is a family of variants of the cube's quasi-static default ("base"); every run
stops past its peak (stop_at past_peak at PEAK_STOP_RATIO x the strain at the
peak so far), where the peak and its strain are known.

    ldem study seed-settings --out DIR [--sizes 0.12,0.96] [--seeds 3] [--settings rate,damping,..] [--jobs J]

writes DIR/cases/ (a folder per run), runs.csv (a row per run),
sensitivity.csv and sensitivity.md (per variant: the means at each size, the
ratio of the largest to the smallest size's peak, their change against base)
and ratio.png (that ratio against each variant, beside Table 3's)."""
from __future__ import annotations

import itertools
import math
import os
import sys
from dataclasses import dataclass
from typing import Callable, Dict, List, Sequence

import numpy as np

from .. import io
from ..cube import CubeTest
from .cases import case_name
from .executors import run_cases
from .options import FIELDS, add_seeds, check_tests, parse_floats, parse_names, parameter_option, seed_count
from .registry import Study, register
from .tables import REFERENCE_UNIFORM

PEAK_STOP_RATIO = 2.0  # past_peak: the run ends at twice the strain at the peak so far
SIZES = (0.12, 0.96)
DEFAULT = CubeTest()

# A constant drive: the cube's pace near the peak (crack_pace, crack_secant) off.
CONSTANT = {"crack_pace": 1.0, "crack_secant": 0.0}


def constant_rate(rate: float) -> Callable[[float], dict]:
    """The drive at a constant strain rate, its smooth start (a rising velocity,
    ConstantRateDrive.hpp) over eps_p / (4 rate): the rate is reached by a mean
    strain of eps_p / 8 at any rate, before any bar cracks."""
    return lambda size: {**CONSTANT, "strain_rate": rate, "ramp_time": float(f"{DEFAULT.eps_p / (4 * rate):.6g}")}


def axial_omega(size: float) -> float:
    """The frequency of the uniform drive's own field u = z eps e_z as a mode
    (its Rayleigh quotient): omega_d^2 = u'Ku / u'Mu = E H A eps^2 / (rho A H^3 eps^2 / 3),
    omega_d = sqrt(3 E / rho) / H."""
    return math.sqrt(3 * DEFAULT.E / DEFAULT.rho) / size


def fixed_damping(size: float) -> dict:
    """The 0.12 m cube's D_f = 2 zeta omega_1 at every size: zeta stated on its omega_1."""
    return {"damping_omega": smallest_omega1()}


_OMEGA1: Dict[float, float] = {}


def smallest_omega1(size: float = SIZES[0]) -> float:
    """omega_1 of the default cube of this size (its set-up's modal analysis)."""
    if size not in _OMEGA1:
        _OMEGA1[size] = CubeTest(size=size).simulation().omega1
    return _OMEGA1[size]


def fixed(**kw) -> Callable[[float], dict]:
    return lambda size: dict(kw)


@dataclass(frozen=True)
class Variant:
    setting: str   # the family: rate, damping, ...
    label: str     # what the variant is, in a table's words
    overrides: Callable[[float], dict]  # its CubeTest parameters beside the base's, at a size


SETTINGS: Dict[str, List[Variant]] = {
    "base": [Variant("base", "the cube's quasi-static default (paced, 0.02 /s)", fixed())],
    "rate": [Variant("rate", "rule (c): eps_p in 3 periods T_1, constant", fixed(**CONSTANT, rate_periods=3.0))]
    + [Variant("rate", f"constant {r:g} /s", constant_rate(r)) for r in (0.01, 0.03, 0.1, 0.3, 1.0)],
    "smooth start": [Variant("smooth start", "constant 0.1 /s, smooth start of 2 T_1 (the default's)",
                             fixed(**CONSTANT, strain_rate=0.1))],
    "damping": [Variant("damping", "zeta 1 % on omega_1", fixed(zeta=0.01)),
                Variant("damping", "zeta 2 % on the drive's axial mode sqrt(3E/rho)/H",
                        lambda size: {"damping_omega": axial_omega(size)}),
                Variant("damping", "zeta 2 % on the 0.12 m cube's omega_1 (one D_f at every size)", fixed_damping)],
    "upper face": [Variant("upper face", "lateral DOFs fixed", fixed(top_lateral="fixed"))],
    "lower face": [Variant("lower face", "on rollers (lateral DOFs free)", fixed(bottom_lateral="free"))],
    "draw": [Variant("draw", "G_f per module", fixed(Gf_draw="module"))],
    "correlation": [Variant("correlation", f"correlation length {lc:g} m", fixed(corr_length=lc))
                    for lc in (0.03, 0.09)],
    "weibull": [Variant("weibull", f"lower bound G_f >= {a:g} N/m (mean and CV kept)", fixed(Gf_min=a))
                for a in (4.0, 20.0, 50.0)],
}


def variant_test(v: Variant, size: float, seed: int, threads: int = 0) -> CubeTest:
    return CubeTest(size=size, seed=seed, load="uniform", threads=threads, stop_at="past_peak",
                    peak_stop_strain_ratio=PEAK_STOP_RATIO, **v.overrides(size))


def variants(settings: Sequence[str]) -> List[Variant]:
    return [v for s in dict.fromkeys(["base", *settings]) for v in SETTINGS[s]]


def plan(settings: Sequence[str], sizes: Sequence[float], seeds: Sequence[int], threads: int = 0):
    """[(variant, test)] for every variant, size and seed, and the distinct tests to run."""
    pairs = [(v, variant_test(v, size, seed, threads)) for v in variants(settings) for size in sizes for seed in seeds]
    distinct = list({case_name(t): t for _, t in pairs}.values())
    return pairs, distinct


def run_rows(pairs, summaries: Dict[str, dict]) -> List[dict]:
    """A row per (variant, size, seed): the run's peak, its strain, its cost."""
    rows = []
    for v, t in pairs:
        s = summaries[case_name(t)]
        rows.append({"setting": v.setting, "variant": v.label, "size_m": t.size, "seed": t.seed,
                     "peak_stress_MPa": s["peak_stress_MPa"], "strain_at_peak": s["strain_at_peak"],
                     "strain_rate": s["parameters"]["strain_rate"] if "parameters" in s else t.strain_rate,
                     "energy_balance_error": s["energy_balance_error"], "steps": s.get("steps", ""),
                     "wall_s": s.get("wall_s", ""), "case": case_name(t)})
    return rows


def _mean_se(values) -> tuple:
    v = np.asarray(values, dtype=float)
    return float(v.mean()), (float(v.std(ddof=1) / math.sqrt(len(v))) if len(v) > 1 else float("nan"))


def sensitivity(rows: Sequence[dict]) -> List[dict]:
    """Per variant: the mean peak and strain at each size (with the standard error
    over the seeds), the ratio of the largest size's mean peak to the smallest's
    (its standard error propagated), and both against base's."""
    sizes = sorted({r["size_m"] for r in rows})
    lo, hi = sizes[0], sizes[-1]
    out = []
    for label in dict.fromkeys(r["variant"] for r in rows):
        g = [r for r in rows if r["variant"] == label]
        row = {"setting": g[0]["setting"], "variant": label, "seeds": len({r["seed"] for r in g})}
        for size in sizes:
            at = [r for r in g if r["size_m"] == size]
            row[f"peak_{size:g}"], row[f"peak_se_{size:g}"] = _mean_se([r["peak_stress_MPa"] for r in at])
            row[f"strain_{size:g}"], row[f"strain_se_{size:g}"] = _mean_se([r["strain_at_peak"] for r in at])
        a, b = row[f"peak_{lo:g}"], row[f"peak_{hi:g}"]
        row["peak_ratio"] = b / a
        row["peak_ratio_se"] = row["peak_ratio"] * math.hypot(row[f"peak_se_{lo:g}"] / a, row[f"peak_se_{hi:g}"] / b)
        row["strain_ratio"] = row[f"strain_{hi:g}"] / row[f"strain_{lo:g}"]
        out.append(row)
    return out


def table3_ratio(lo: float, hi: float) -> tuple:
    """Table 3's ratio of peaks and of strains at the peak, largest size over smallest."""
    (p0, e0), (p1, e1) = REFERENCE_UNIFORM[lo], REFERENCE_UNIFORM[hi]
    return p1 / p0, e1 / e0


def sensitivity_table(sens: Sequence[dict]) -> str:
    sizes = sorted(float(k[5:]) for k in sens[0] if k.startswith("peak_") and not k.startswith("peak_se")
                   and k != "peak_ratio" and not k.startswith("peak_ratio"))
    lo, hi = sizes[0], sizes[-1]
    base = next(r for r in sens if r["setting"] == "base")
    head = "| setting | variant | " + " | ".join(f"peak {s:g} m [MPa] | strain at peak {s:g} m" for s in sizes)
    head += f" | peak {hi:g} / {lo:g} m | strain {hi:g} / {lo:g} m |"
    lines = [head, "|" + "---|" * (4 + 2 * len(sizes))]
    for r in sens:
        cells = []
        for s in sizes:
            p, e = r[f"peak_{s:g}"], r[f"strain_{s:g}"]
            dp, de = 100 * (p / base[f"peak_{s:g}"] - 1), 100 * (e / base[f"strain_{s:g}"] - 1)
            cells.append(f"{p:.3f} ± {r[f'peak_se_{s:g}']:.3f} ({dp:+.1f} %) | {e:.3e} ({de:+.0f} %)")
        lines.append(f"| {r['setting']} | {r['variant']} | " + " | ".join(cells)
                     + f" | {r['peak_ratio']:.3f} ± {r['peak_ratio_se']:.3f} | {r['strain_ratio']:.2f} |")
    if (lo, hi) == (0.12, 0.96):
        pr, er = table3_ratio(lo, hi)
        lines.append(f"| Table 3 | the study | " + " | ".join(
            f"{REFERENCE_UNIFORM[s][0]:.2f} | {REFERENCE_UNIFORM[s][1]:.2e}" for s in sizes)
            + f" | {pr:.3f} | {er:.2f} |")
    return "\n".join(lines) + "\n"


def ratio_figure(sens: Sequence[dict], path: str, fmt: str = "png") -> str:
    """The ratio of the largest to the smallest size's mean peak per variant
    (bars: one standard error over the seeds), Table 3's as a line."""
    from ..plots import plt, save
    sizes = sorted({float(k[5:]) for k in sens[0] if k.startswith("peak_0") or k.startswith("peak_1")})
    lo, hi = sizes[0], sizes[-1]
    fig, ax = plt.subplots(figsize=(7.5, 0.32 * len(sens) + 1.4))
    y = np.arange(len(sens))[::-1]
    ax.errorbar([r["peak_ratio"] for r in sens], y, xerr=[r["peak_ratio_se"] for r in sens], fmt="o", color="C0")
    base = next(r for r in sens if r["setting"] == "base")
    ax.axvline(base["peak_ratio"], color="0.5", ls=":", label="base (quasi-static default)")
    if lo in REFERENCE_UNIFORM and hi in REFERENCE_UNIFORM:
        ax.axvline(table3_ratio(lo, hi)[0], color="C3", ls="--", label="Table 3 of the study")
    ax.set_yticks(y, [f"{r['setting']}: {r['variant']}" for r in sens], fontsize=7)
    ax.set_xlabel(f"mean peak at {hi:g} m / mean peak at {lo:g} m (uniform load)")
    ax.legend(loc="lower right", fontsize=7)
    save(fig, f"{path}.{fmt}", palette=True)
    return f"{path}.{fmt}"


def run_seed_settings(settings: Sequence[str], sizes: Sequence[float], seeds: Sequence[int], out: str, jobs: int = 1,
                      threads: int = 0, fmt: str = "png", log: Callable[[str], None] = print) -> List[dict]:
    """Runs the unfinished cases; writes runs.csv, sensitivity.csv/.md and the figure; returns the sensitivity rows."""
    pairs, tests = plan(settings, sizes, seeds, threads)
    check_tests(tests)
    summaries = {case_name(t): s for t, s in zip(tests, run_cases(tests, out, jobs=jobs, log=log))}
    rows = run_rows(pairs, summaries)
    io.write_table(os.path.join(out, "runs.csv"), rows, list(rows[0]))
    sens = sensitivity(rows)
    io.write_table(os.path.join(out, "sensitivity.csv"), sens, list(sens[0]))
    io.write_text(os.path.join(out, "sensitivity.md"), sensitivity_table(sens))
    ratio_figure(sens, os.path.join(out, "ratio"), fmt)
    return sens


# The fit (committed before it runs; docs/results.md, results/seed-settings/README.md):
# at most two parameters, each on a grid of values given in advance; at every
# grid point the five sizes of Table 3 run with seeds 1..n (n >= 3), each case
# the sensitivity study's (stopped past its peak); the misfit of a point is
#   J = (1/5) sum_sizes [(P/P_3 - 1)^2 + (e/e_3 - 1)^2],
# P and e the seeds' mean peak and strain at the peak, P_3 and e_3 Table 3's.
# The fit is the grid point of least J; on one parameter, refined by the
# vertex of the parabola through it and its two neighbours (kept within them),
# which is then run and reported as the fitted value with its residuals.
def fit_overrides(name: str, value) -> Callable[[float], dict]:
    """A fitted parameter's value as a variant: strain_rate is a constant drive
    (constant_rate), rate_periods too; any other parameter of CubeTest beside
    the quasi-static default."""
    if name == "strain_rate":
        return constant_rate(value)
    if name == "rate_periods":
        return fixed(**CONSTANT, rate_periods=value)
    if name not in FIELDS:
        raise ValueError(f"--fit {name}: not a parameter of ldem cube --help")
    return fixed(**{name: type(getattr(DEFAULT, name))(value)})


def fit_variant(point: Dict[str, float]) -> Variant:
    parts = [fit_overrides(k, v) for k, v in point.items()]
    return Variant("fit", ", ".join(f"{k} {v:g}" for k, v in point.items()),
                   lambda size: {k: v for f in parts for k, v in f(size).items()})


def misfit(means: Dict[float, tuple], target: Dict[float, tuple]) -> float:
    """J of the fit: the mean over the sizes of the squared relative residuals of peak and strain at the peak."""
    return float(np.mean([(means[s][0] / target[s][0] - 1) ** 2 + (means[s][1] / target[s][1] - 1) ** 2
                          for s in target]))


def parabola_vertex(x, y) -> float:
    """The vertex of the parabola through three points (x sorted), kept within [x0, x2]."""
    (x0, x1, x2), (y0, y1, y2) = x, y
    d = (x0 - x1) * (x0 - x2) * (x1 - x2)
    a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / d
    b = (x2 * x2 * (y0 - y1) + x1 * x1 * (y2 - y0) + x0 * x0 * (y1 - y2)) / d
    return x1 if a <= 0 else float(min(max(-b / (2 * a), x0), x2))


def _size_means(rows: Sequence[dict], label: str) -> Dict[float, tuple]:
    g = [r for r in rows if r["variant"] == label]
    return {s: (float(np.mean([r["peak_stress_MPa"] for r in g if r["size_m"] == s])),
                float(np.mean([r["strain_at_peak"] for r in g if r["size_m"] == s])))
            for s in sorted({r["size_m"] for r in g})}


def run_fit(grid: Dict[str, Sequence[float]], seeds: Sequence[int], out: str, target=REFERENCE_UNIFORM, jobs: int = 1,
            threads: int = 0, log: Callable[[str], None] = print) -> dict:
    """The fit above on `grid` (one or two parameters: their values); writes
    fit_runs.csv, fit.csv (J and the means per grid point) and fit.md; returns
    {"parameters", "best", "J", "means", "points"}."""
    if not 1 <= len(grid) <= 2:
        raise ValueError("--fit: one or two parameters")
    names = list(grid)
    points = [dict(zip(names, v)) for v in itertools.product(*(grid[n] for n in names))]
    sizes = sorted(target)

    def evaluate(pts):
        vs = [fit_variant(p) for p in pts]
        pairs = [(v, variant_test(v, size, seed, threads)) for v in vs for size in sizes for seed in seeds]
        tests = list({case_name(t): t for _, t in pairs}.values())
        check_tests(tests)
        summaries = {case_name(t): s for t, s in zip(tests, run_cases(tests, out, jobs=jobs, log=log))}
        return run_rows(pairs, summaries)

    rows = evaluate(points)
    table = [{**p, "J": misfit(_size_means(rows, fit_variant(p).label), target)} for p in points]
    best = dict(min(table, key=lambda r: r["J"]))
    if len(names) == 1:
        n, xs = names[0], sorted(grid[names[0]])
        i = xs.index(best[n])
        if 0 < i < len(xs) - 1:
            J = {r[n]: r["J"] for r in table}
            x = parabola_vertex(xs[i - 1:i + 2], [J[v] for v in xs[i - 1:i + 2]])
            if x not in xs:
                point = {n: float(f"{x:.4g}")}
                rows += evaluate([point])
                table.append({**point, "J": misfit(_size_means(rows, fit_variant(point).label), target)})
                if table[-1]["J"] < best["J"]:
                    best = dict(table[-1])
    label = fit_variant({n: best[n] for n in names}).label
    means = _size_means(rows, label)
    io.write_table(os.path.join(out, "fit_runs.csv"), rows, list(rows[0]))
    for r in table:
        m = _size_means(rows, fit_variant({n: r[n] for n in names}).label)
        for s in sizes:
            r[f"peak_{s:g}"], r[f"strain_{s:g}"] = m[s]
    io.write_table(os.path.join(out, "fit.csv"), table, list(table[0]))
    result = {"parameters": names, "best": {n: best[n] for n in names}, "J": best["J"], "means": means,
              "points": table}
    io.write_text(os.path.join(out, "fit.md"), fit_table(result, target))
    return result


def fit_table(fit: dict, target=REFERENCE_UNIFORM) -> str:
    names = fit["parameters"]
    lines = ["| " + " | ".join(names) + " | J |", "|" + "---|" * (len(names) + 1)]
    lines += ["| " + " | ".join(f"{p[n]:g}" for n in names) + f" | {p['J']:.3e} |" for p in fit["points"]]
    best = ", ".join(f"{n} = {fit['best'][n]:g}" for n in names)
    lines += ["", f"Fitted: {best} (J = {fit['J']:.3e}).", "",
              "| size [m] | peak [MPa] | Table 3 | residual | strain at peak | Table 3 | residual |",
              "|---|---|---|---|---|---|---|"]
    for s, (p, e) in fit["means"].items():
        p3, e3 = target[s]
        lines.append(f"| {s:g} | {p:.3f} | {p3:.2f} | {100 * (p / p3 - 1):+.1f} % | {e:.3e} | {e3:.2e} | "
                     f"{100 * (e / e3 - 1):+.1f} % |")
    return "\n".join(lines) + "\n"


def parse_grid(specs: Sequence[str]) -> Dict[str, List[float]]:
    """--fit NAME=v1,v2,... (once or twice) as {NAME: [values]}."""
    grid = {}
    for spec in specs:
        name, sep, values = spec.partition("=")
        if not sep:
            raise ValueError(f"--fit takes NAME=v1,v2,... (got '{spec}')")
        grid[name.strip()] = parse_floats(values, f"--fit {name.strip()}")
    return grid


def add_arguments(a) -> None:
    a.add_argument("--out", required=True, metavar="DIR",
                   help="study folder (cases/, runs.csv, sensitivity.csv, sensitivity.md, ratio.png)")
    a.add_argument("--sizes", default=",".join(f"{s:g}" for s in SIZES),
                   help="comma-separated cube sizes [m]; the ratio is the largest's peak over the smallest's")
    add_seeds(a, "size and variant")
    a.set_defaults(seeds=3)
    names = [s for s in SETTINGS if s != "base"]
    a.add_argument("--settings", default=",".join(names),
                   help="comma-separated settings, each a family of variants beside base, of: " + ", ".join(names))
    a.add_argument("--jobs", type=int, default=1, metavar="J", help="cases run at once in separate processes")
    parameter_option(a, "threads", note="; per case")
    a.add_argument("--figure-format", default="png", choices=("png", "pdf", "svg"), help="format of the figure")
    a.add_argument("--fit", action="append", default=[], metavar="NAME=V1,V2,...",
                   help="run no sensitivity study: fit this parameter (once or twice: at most two) on these values "
                        "to Table 3's five sizes (strain_rate and rate_periods: a constant drive); writes fit.csv, "
                        "fit.md, fit_runs.csv")


def cmd_seed_settings(args) -> int:
    if args.fit:
        grid = parse_grid(args.fit)
        for name, values in grid.items():
            for v in values:
                fit_overrides(name, v)
        fit = run_fit(grid, range(1, seed_count(args) + 1), args.out, jobs=args.jobs, threads=args.threads,
                      log=lambda s: print(s, file=sys.stderr))
        print(fit_table(fit), end="")
        return 0
    names = parse_names(args.settings, [s for s in SETTINGS if s != "base"], "setting",
                        "some of " + ", ".join(s for s in SETTINGS if s != "base"))
    sizes = parse_floats(args.sizes, "--sizes")
    if len(sizes) < 2:
        raise ValueError("--sizes needs at least two sizes: the study compares the largest with the smallest")
    sens = run_seed_settings(names, sizes, range(1, seed_count(args) + 1), args.out, args.jobs, args.threads,
                             args.figure_format, log=lambda s: print(s, file=sys.stderr))
    print(sensitivity_table(sens), end="")
    return 0


register(Study("seed-settings", "the settings the study does not report, one at a time: the uniform cube's peak "
                                "and its strain at 0.12 and 0.96 m against Table 3", add_arguments,
               cmd_seed_settings))
