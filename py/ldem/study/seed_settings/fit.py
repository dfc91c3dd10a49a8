"""The fit of at most two parameters to Table 3 (stated in advance, below)."""
from __future__ import annotations

import itertools
import os
from typing import Callable, Dict, List, Optional, Sequence

import numpy as np

from ... import io
from ..cases import case_name
from ..executors import run_cases
from ..options import FIELDS, check_tests, parse_floats
from ..tables import REFERENCE_UNIFORM
from .tables import run_rows
from .variants import DEFAULT, Variant, constant_rate, fixed, periods_rate, variant_test

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
        return periods_rate(value)
    if name not in FIELDS:
        raise ValueError(f"--fit {name}: not a parameter of ldem cube --help")
    default = getattr(DEFAULT, name)
    md = FIELDS[name].metadata
    if isinstance(default, str) and not md.get("several") and value not in md.get("choices", (value,)):
        raise ValueError(f"{name}: '{value}' is not one of {', '.join(FIELDS[name].metadata['choices'])}")
    return fixed(**{name: type(default)(value)})


def fit_variant(point: dict) -> Variant:
    """The variant of a point: its parameters (fitted and held) as fit_overrides reads them."""
    parts = [fit_overrides(k, v) for k, v in point.items()]
    return Variant("fit", ", ".join(f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}" for k, v in point.items()),
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


def size_means(rows: Sequence[dict], label: str) -> Dict[float, tuple]:
    g = [r for r in rows if r["variant"] == label]
    return {s: (float(np.mean([r["peak_stress_MPa"] for r in g if r["size_m"] == s])),
                float(np.mean([r["strain_at_peak"] for r in g if r["size_m"] == s])))
            for s in sorted({r["size_m"] for r in g})}


def run_fit(grid: Dict[str, Sequence[float]], seeds: Sequence[int], out: str, target=REFERENCE_UNIFORM, jobs: int = 1,
            threads: int = 0, held: Optional[dict] = None, log: Callable[[str], None] = print) -> dict:
    """The fit above on `grid` (one or two parameters: their values), every
    case with the `held` settings too; writes fit_runs.csv, fit.csv (J and the
    means per grid point) and fit.md; returns {"parameters", "best", "held",
    "J", "means", "points"}."""
    if not 1 <= len(grid) <= 2:
        raise ValueError("--fit: one or two parameters")
    held = dict(held or {})
    names = list(grid)
    points = [{**held, **dict(zip(names, v))} for v in itertools.product(*(grid[n] for n in names))]
    sizes = sorted(target)

    def evaluate(pts):
        vs = [fit_variant(p) for p in pts]
        pairs = [(v, variant_test(v, size, seed, threads)) for v in vs for size in sizes for seed in seeds]
        tests = list({case_name(t): t for _, t in pairs}.values())
        check_tests(tests)
        summaries = {case_name(t): s for t, s in zip(tests, run_cases(tests, out, jobs=jobs, log=log))}
        return run_rows(pairs, summaries)

    rows = evaluate(points)
    table = [{**p, "J": misfit(size_means(rows, fit_variant(p).label), target)} for p in points]
    best = dict(min(table, key=lambda r: r["J"]))
    if len(names) == 1:
        n, xs = names[0], sorted(grid[names[0]])
        i = xs.index(best[n])
        if 0 < i < len(xs) - 1:
            J = {r[n]: r["J"] for r in table}
            x = parabola_vertex(xs[i - 1:i + 2], [J[v] for v in xs[i - 1:i + 2]])
            if x not in xs:
                point = {**held, n: float(f"{x:.4g}")}
                rows += evaluate([point])
                table.append({**point, "J": misfit(size_means(rows, fit_variant(point).label), target)})
                if table[-1]["J"] < best["J"]:
                    best = dict(table[-1])
    label = fit_variant({**held, **{n: best[n] for n in names}}).label
    means = size_means(rows, label)
    io.write_table(os.path.join(out, "fit_runs.csv"), rows, list(rows[0]))
    for r in table:
        m = size_means(rows, fit_variant({**held, **{n: r[n] for n in names}}).label)
        for s in sizes:
            r[f"peak_{s:g}"], r[f"strain_{s:g}"] = m[s]
    io.write_table(os.path.join(out, "fit.csv"), table, list(table[0]))
    result = {"parameters": names, "best": {n: best[n] for n in names}, "held": held, "J": best["J"],
              "means": means, "points": table}
    io.write_text(os.path.join(out, "fit.md"), fit_table(result, target))
    return result


def fit_table(fit: dict, target=REFERENCE_UNIFORM) -> str:
    names = fit["parameters"]
    lines = ["| " + " | ".join(names) + " | J |", "|" + "---|" * (len(names) + 1)]
    lines += ["| " + " | ".join(f"{p[n]:g}" for n in names) + f" | {p['J']:.3e} |" for p in fit["points"]]
    best = ", ".join(f"{n} = {fit['best'][n]:g}" for n in names)
    held = ", ".join(f"{k} = {v}" for k, v in fit.get("held", {}).items())
    lines += ["", f"Fitted: {best} (J = {fit['J']:.3e})" + (f", with {held} held." if held else "."), "",
              "| size [m] | peak [MPa] | Table 3 | residual | strain at peak | Table 3 | residual |",
              "|---|---|---|---|---|---|---|"]
    for s, (p, e) in fit["means"].items():
        p3, e3 = target[s]
        lines.append(f"| {s:g} | {p:.3f} | {p3:.2f} | {100 * (p / p3 - 1):+.1f} % | {e:.3e} | {e3:.2e} | "
                     f"{100 * (e / e3 - 1):+.1f} % |")
    return "\n".join(lines) + "\n"


def parse_point(pairs: Sequence[str]) -> dict:
    """NAME=VALUE pairs (--hold, --study) as a point: numbers as floats, a choice (bottom_lateral=free) as its name."""
    point = {}
    for pair in pairs:
        name, sep, value = pair.partition("=")
        name = name.strip()
        if not sep or name not in FIELDS:
            raise ValueError(f"expected NAME=VALUE with NAME a parameter of ldem cube --help (got '{pair}')")
        point[name] = value.strip() if isinstance(getattr(DEFAULT, name), str) else float(value)
        fit_overrides(name, point[name])
    return point


def parse_grid(specs: Sequence[str]) -> Dict[str, List[float]]:
    """--fit NAME=v1,v2,... (once or twice) as {NAME: [values]}."""
    grid = {}
    for spec in specs:
        name, sep, values = spec.partition("=")
        if not sep:
            raise ValueError(f"--fit takes NAME=v1,v2,... (got '{spec}')")
        grid[name.strip()] = parse_floats(values, f"--fit {name.strip()}")
    return grid


