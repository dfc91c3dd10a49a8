"""An input band: what a prediction's unmeasured inputs may be, and
the 5-95 % band of its answer over them and over the lattice's seeds.

- Each input is a normal distribution of a stated mean, coefficient of
  variation and source (Scatter).
- The design is a Latin hypercube (latin_hypercube): n points, each input's
  range cut into n strata of equal probability, one point in each, at a
  uniform place within it, the strata of the inputs paired at random; the
  same seed gives the same design. Its marginals are the inputs'
  distributions: each stratum holds exactly one point.
- The band (band): one run a point, each with a seed of its own, so that a
  point's answer is y_i = f(x_i) + its seed's deviation. A linear fit
  y = c0 + sum_k c_k z_k on the standard scores z_k = (x_k - mean_k) / sd_k
  gives the inputs' part, sd_in^2 = sum_k c_k^2 (independent normal inputs,
  a first-order model); the seeds' part is the variance of the committed
  prediction's seeds at the mean inputs, sd_s^2. Together the answer is
  normal, centred on the prediction's mean, of variance sd_in^2 + sd_s^2:
  5-95 % = mean -+ 1.645 sqrt(sd_in^2 + sd_s^2). Each share is its part of
  that variance. The fit's residual (n - d - 1 degrees of freedom) holds the
  points' own seeds and what is not linear: near sd_s, the linear model holds."""
from __future__ import annotations

import math
from dataclasses import dataclass
from statistics import NormalDist
from typing import Dict, List, Sequence

import numpy as np

MIN_POINTS = 12  # the design's points at least: fewer strata leave the 5-95 % tails unsampled
QUANTILES = (0.05, 0.95)


@dataclass(frozen=True)
class Scatter:
    """An input: normal, of mean `mean` and coefficient of variation `cv`; `source` says where both come from."""
    name: str
    mean: float
    cv: float
    source: str

    @property
    def sd(self) -> float:
        return self.cv * abs(self.mean)

    def ppf(self, u):
        """The input at probability u (0 < u < 1): the inverse of its distribution."""
        z = np.vectorize(NormalDist().inv_cdf)(np.asarray(u, float))
        return self.mean + self.sd * z

    def cdf(self, x):
        return np.vectorize(NormalDist(self.mean, self.sd).cdf)(np.asarray(x, float))


def cv_of_fractiles(low: float, high: float, p: float = 0.05) -> float:
    """The CV of a normal whose p and 1 - p fractiles are low and high times its
    mean (symmetric: fib MC2010's 0.7 and 1.3 f_ctm give 0.3 / 1.645 = 0.182)."""
    if not math.isclose(1 - low, high - 1):
        raise ValueError(f"fractiles {low:g} and {high:g} of the mean are not symmetric: not a normal's")
    return (high - 1) / NormalDist().inv_cdf(1 - p)


def latin_hypercube(n: int, d: int, seed: int) -> np.ndarray:
    """u[n, d] in (0, 1): in each column one point in each stratum [i/n, (i+1)/n),
    uniform within it, the columns' strata paired by independent permutations."""
    if n < 2 or d < 1:
        raise ValueError(f"a Latin hypercube needs at least 2 points and 1 input (got {n}, {d})")
    rng = np.random.default_rng(seed)
    strata = np.column_stack([rng.permutation(n) for _ in range(d)])
    return (strata + rng.uniform(size=(n, d))) / n


def design(inputs: Sequence[Scatter], n: int, seed: int) -> np.ndarray:
    """x[n, d]: the inputs of the n points of a Latin hypercube of the seed."""
    u = latin_hypercube(n, len(inputs), seed)
    return np.column_stack([s.ppf(u[:, k]) for k, s in enumerate(inputs)])


def band(inputs: Sequence[Scatter], x: np.ndarray, y: Sequence[float], seeds: Sequence[float]) -> Dict[str, object]:
    """The band of one quantity (the module's text): x[n, d] the points' inputs,
    y[n] their answers (nan: not reached, left out), seeds the committed
    prediction's answers at the mean inputs. Returns mean (the seeds'), low,
    high (5 and 95 %), sd_inputs, sd_seeds, shares ({input: share, "seeds":
    share}), centre (the fit's c0, the design's own answer at the mean
    inputs), residual (the fit's residual sd) and points (how many were used)."""
    y, seeds = np.asarray(y, float), np.asarray([s for s in seeds if not math.isnan(s)], float)
    x = np.asarray(x, float)
    kept = ~np.isnan(y)
    d = len(inputs)
    if kept.sum() < d + 2 or len(seeds) < 2:
        return {"points": int(kept.sum())}
    z = (x[kept] - [s.mean for s in inputs]) / [s.sd for s in inputs]
    a = np.column_stack([np.ones(int(kept.sum())), z])
    c, *_ = np.linalg.lstsq(a, y[kept], rcond=None)
    residual = y[kept] - a @ c
    var_in, var_s = float(np.sum(c[1:] ** 2)), float(np.var(seeds, ddof=1))
    total = var_in + var_s
    mean = float(np.mean(seeds))
    q = [NormalDist(mean, math.sqrt(total)).inv_cdf(p) if total > 0 else mean for p in QUANTILES]
    shares = {s.name: (float(c[1 + k] ** 2) / total if total > 0 else 0.0) for k, s in enumerate(inputs)}
    shares["seeds"] = var_s / total if total > 0 else 0.0
    return {"mean": mean, "low": q[0], "high": q[1], "sd_inputs": math.sqrt(var_in), "sd_seeds": math.sqrt(var_s),
            "shares": shares, "centre": float(c[0]), "slopes": [float(v) for v in c[1:]],
            "residual": float(math.sqrt(residual @ residual / (len(residual) - d - 1))), "points": int(kept.sum())}


def inputs_share(b: dict) -> float:
    """The inputs' part of a band's variance (1 - the seeds')."""
    return 1.0 - b["shares"]["seeds"]


def band_lines(names: Sequence[str], bands: Sequence[dict], labels: Sequence[str], n: int) -> List[str]:
    """Markdown: a row per quantity, its band and each part's share of its variance."""
    head = ["quantity", "prediction (seeds at the mean inputs)", "5 %", "95 %", "inputs", "seeds",
            *(f"of which {k}" for k in names), "fit's residual sd", "points"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for label, b in zip(labels, bands):
        if "mean" not in b:
            lines.append(f"| {label} | not reached by enough points ({b['points']} of {n}) |" + " |" * (len(head) - 2))
            continue
        lines.append(f"| {label} | {b['mean']:.3f} | {b['low']:.3f} | {b['high']:.3f} | {inputs_share(b):.0%} | "
                     f"{b['shares']['seeds']:.0%} | " + " | ".join(f"{b['shares'][k]:.0%}" for k in names) +
                     f" | {b['residual']:.3f} (seeds' sd {b['sd_seeds']:.3f}) | {b['points']} of {n} |")
    return lines
