"""The variants of the seed-settings study: each setting the reference study
does not report is a family of variants of the cube's quasi-static default
("base"), and a variant at a size and seed is a CubeTest stopped past its peak."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Dict, List, Sequence

from ...cube import CubeTest
from ..cases import case_name

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


def periods_rate(periods: float) -> Callable[[float], dict]:
    """Rule (c)'s rate at a size: the mean strain grows by eps_p in `periods`
    fundamental periods of that cube, rate = eps_p omega_1 / (2 pi N), a
    constant drive (constant_rate). The same N at every size loads each cube in
    the same number of its own wave transits (omega_1 ~ c / H)."""
    return lambda size: constant_rate(float(f"{DEFAULT.eps_p * omega1(size) / (2 * math.pi * periods):.6g}"))(size)


def axial_omega(size: float) -> float:
    """The frequency of the uniform drive's own field u = z eps e_z as a mode
    (its Rayleigh quotient): omega_d^2 = u'Ku / u'Mu = E H A eps^2 / (rho A H^3 eps^2 / 3),
    omega_d = sqrt(3 E / rho) / H."""
    return math.sqrt(3 * DEFAULT.E / DEFAULT.rho) / size


def fixed_damping(size: float) -> dict:
    """The 0.12 m cube's D_f = 2 zeta omega_1 at every size: zeta stated on its omega_1."""
    return {"damping_omega": omega1(SIZES[0])}


_OMEGA1: Dict[float, float] = {}


def omega1(size: float) -> float:
    """omega_1 of the default cube of this size (its set-up's modal analysis; kept for the process)."""
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
    "rate": [Variant("rate", f"constant {r:g} /s", constant_rate(r)) for r in (0.01, 0.03, 0.1, 0.3, 1.0)],
    # The rate scaled with the size: rule (c)'s N = 3 (quasi-static), then faster.
    "periods": [Variant("periods", f"constant, eps_p in {n:g} T_1 (rule (c) N = {n:g})", periods_rate(n))
                for n in (3.0, 1.0, 0.3)],
    "smooth start": [Variant("smooth start", "constant 0.1 /s, smooth start of 2 T_1 (the default's)",
                             fixed(**CONSTANT, strain_rate=0.1))],
    "damping": [Variant("damping", "zeta 1 % on omega_1", fixed(zeta=0.01)),
                Variant("damping", "zeta 2 % on the drive's axial mode sqrt(3E/rho)/H",
                        lambda size: {"damping_omega": axial_omega(size)}),
                Variant("damping", "zeta 2 % on the 0.12 m cube's omega_1 (one D_f at every size)", fixed_damping)],
    "upper face": [Variant("upper face", "lateral DOFs fixed", fixed(top_lateral="fixed"))],
    # Beside the constant drive of rule (c) (the periods row N = 3), not the paced
    # base: on rollers the pace holds the drive at a sixteenth for the whole long
    # nonlinear rise, 190,000 steps to twice the peak's strain at 0.96 m.
    "lower face": [Variant("lower face", "on rollers (lateral DOFs free), constant, eps_p in 3 T_1",
                           lambda size: {**periods_rate(3.0)(size), "bottom_lateral": "free"})],
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
