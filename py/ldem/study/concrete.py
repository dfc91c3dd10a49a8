"""The lattice's own concrete, measured by virtual standard tests: the
direct tension prism 50 x 50 x 100 mm of the beams' calibration, pulled to
separation, gives what a laboratory would report of the material it stands
for:
- E and nu from two gauges at mid-height (axial over 50 mm, lateral across
  the 50 mm width), fitted between 20 % and 60 % of the peak on the rising
  branch (the ends are held: mid-height is a prism's gauge zone);
- f_t, the peak stress;
- G_F, the work of fracture: the energy the bars dissipated up to separation
  over the cross-section (U_num / A), as the uniaxial tension test of RILEM
  TC 162-TDF defines it (the prism's whole softening branch; no notch, so the
  crack is free to wander). (The energy stop "converged" is fooled here: the
  energy of a prism has plateaus, as the triangular cube's.)

A material is a dict of the parameter table's material names (E, nu,
Gf_mean, Gf_cv, law, ...)."""
from __future__ import annotations

import statistics
from typing import Callable, Dict, List, Optional, Sequence

import numpy as np

from ..specimen import SpecimenTest
from .mc2010 import mc2010_fracture_energy

PRISM = (0.05, 0.05, 0.10)  # width, thickness, height [m]
PRISM_RATE = 0.05  # strain rate [1/s]: the beams' calibration's


def prism_size(L0: float) -> tuple:
    """The prism's (width, thickness, height) [m] at module L0: each side of
    PRISM rounded to the nearest whole number of modules, at least 2. The
    prism is built at the structure's own L0, and a structure's module need
    not divide 50 mm: the Malvar-Warren beams (D = 102 mm, L0 = D/8 = 12.75 mm)
    are calibrated on a prism of 4 x 4 x 8 modules, 51 x 51 x 102 mm. Where L0
    divides the sides (5, 10, 12.5 mm, ...) it is PRISM itself."""
    return tuple(max(2, round(side / L0)) * L0 for side in PRISM)


def prism(material: dict, L0: float, seed: int, stop_at: str = "load_loss") -> SpecimenTest:
    """The direct tension prism (prism_size): lower face held, upper face
    pulled; the gauges 'axial' and 'lateral' at mid-height. stop_at
    'load_loss' (enough for E, nu and f_t) or 'separation' (for G_F)."""
    w, t, h = prism_size(L0)
    return SpecimenTest({
        "title": f"direct tension prism {w * 1e3:g} x {t * 1e3:g} x {h * 1e3:g} mm, eps_p {material['eps_p']:.4g}",
        "shape": {"kind": "box", "L0": L0, "size": [w, t, h]},
        "groups": {"bottom": {"face": "z-", "fix": ["x", "y", "z"]}, "top": {"face": "z+", "drive": {"z": 1.0}}},
        "measure": {"support": "bottom", "loaded": "top", "area": w * t, "gauge_length": h, "ligament": w * t,
                    "probes": {"axial": {"a": [w / 2, t / 2, h / 4], "b": [w / 2, t / 2, 3 * h / 4], "direction": "z"},
                               "lateral": {"a": [0.0, t / 2, h / 2], "b": [w, t / 2, h / 2], "direction": "x"}}},
        "material": dict(material), "loading": {"strain_rate": PRISM_RATE},
        "run": {"seed": seed, "stop_at": stop_at, "final_strain": 3e-3 if stop_at == "load_loss" else 0.5,
                "threads": 1}})


def elastic_constants(curve: dict, peak_MPa: float, L0: float) -> tuple:
    """(E [Pa], nu) from the gauges of the prism at module L0, fitted on the
    rows of the rising branch between 20 % and 60 % of the peak (least-squares
    slopes)."""
    w, t, h = prism_size(L0)
    s = np.asarray(curve["stress_MPa"]) * 1e6
    first_peak = int(np.argmax(s))
    rows = np.arange(len(s)) <= first_peak
    band = rows & (s > 0.2 * peak_MPa * 1e6) & (s < 0.6 * peak_MPa * 1e6)
    axial = np.asarray(curve["axial_m"])[band] / (h / 2)
    lateral = np.asarray(curve["lateral_m"])[band] / w
    return float(slope(axial, s[band])), float(-slope(axial, lateral))


def slope(x: np.ndarray, y: np.ndarray) -> float:
    """The least-squares slope of y on x, by its formula (no LAPACK: the same
    bits on every BLAS)."""
    dx = x - x.mean()
    return float(np.dot(dx, y - y.mean()) / np.dot(dx, dx))


def measure(material: dict, L0: float, seeds: Sequence[int] = (1, 2, 3), stop_at: str = "load_loss",
            log: Callable[[str], None] = print) -> Dict[str, float]:
    """The lattice's E, nu and f_t (means over the seeds' prisms), and G_F if
    pulled to separation (stop_at 'separation'; None else), each seed's under
    'runs'."""
    runs: List[dict] = []
    for seed in seeds:
        r = prism(material, L0, seed, stop_at).run()
        s = r.summary
        E, nu = elastic_constants(r.curve, s["peak_stress_MPa"], L0)
        w, t, _ = prism_size(L0)
        runs.append({"seed": seed, "E": E, "nu": nu, "f_t": s["peak_stress_MPa"] * 1e6,
                     "G_F": s["U_num_J"] / (w * t) if s["separated"] else None,
                     "stop": s["stop_reason"], "energy_balance_error": s["energy_balance_error"]})
        log(f"  prism seed {seed}: E {E / 1e9:.2f} GPa, nu {nu:.3f}, f_t {runs[-1]['f_t'] / 1e6:.3f} MPa"
            + (f", G_F {runs[-1]['G_F']:.1f} N/m" if s["separated"] else "")
            + f" ({s['stop_reason']} at {r.curve['mean_strain'][-1]:.3g})")
    out = {k: statistics.mean(r[k] for r in runs) for k in ("E", "nu", "f_t")}
    energies = [r["G_F"] for r in runs]
    out["G_F"] = statistics.mean(energies) if None not in energies else None
    out["runs"] = runs
    return out


# The calibration from standard properties (docs/calibration.md has the
# reasoning and the sources). Fixed before any new blind prediction.
GF_INITIAL_SHARE = 0.4  # G_f / G_F: Bažant & Becq-Giraudon (2002), mean G_F / G_f = 2.5
KINK_STRESS = 0.2  # sigma_k / f_t of the bilinear law: fib MC2010 eq. 5.1-10
GF_CV, C_A = 1.0, 0.1385  # the study's random field and fracture area (LDEM_SPEC section 6)
TOLERANCE, ROUNDS = 0.01, 5  # the prism's E and f_t within 1 % of the targets, at most 5 rounds


def lattice_material(E: float, nu: float, eps_p: float, G_F: float, rho: float = 2400.0) -> dict:
    """The material parameters of the procedure's law: bilinear with the
    initial share and kink above, the study's field."""
    return {"E": E, "nu": nu, "rho": rho, "Gf_mean": G_F, "Gf_cv": GF_CV, "c_a": C_A, "eps_p": eps_p,
            "law": "bilinear", "Gf_ratio": GF_INITIAL_SHARE, "kink_stress": KINK_STRESS}


def next_eps_p(tried: List[tuple], f_t: float) -> float:
    """eps_p for the next prism from the (eps_p, strength) pairs tried: the
    first by proportion, then the secant through the last two (the strength
    grows less than eps_p: the more eps_p, the more bars with eps_r < eps_p
    break at their peak)."""
    (e1, f1) = tried[-1]
    if len(tried) == 1 or tried[-2][1] == f1:
        return e1 * f_t / f1
    e0, f0 = tried[-2]
    return e1 + (f_t - f1) * (e1 - e0) / (f1 - f0)


def calibrate(E: float, nu: float, f_t: float, f_c: Optional[float] = None, G_F: Optional[float] = None,
              rho: float = 2400.0,
              L0: float = 0.005, seeds: Sequence[int] = (1, 2, 3), log: Callable[[str], None] = print) -> dict:
    """The lattice material of a concrete a laboratory reports (E [Pa], nu,
    f_t [Pa] the direct tensile strength, and G_F [N/m], or f_c [Pa] for fib
    MC2010's G_F), at module L0: the procedure's law with Gf_mean = G_F, and
    rounds of the virtual prism (measure, to its load loss), each scaling the
    bars' E so that the prism's is E (its response is proportional), and
    moving eps_p towards the strength f_t (next_eps_p), until both are within
    TOLERANCE (at most ROUNDS prisms). Returns {"material": the
    parameters, "target": what was asked, "measured": the last round's E, nu,
    f_t}. No structural test is used."""
    for name, value in (("E", E), ("f_t", f_t), ("L0", L0), ("rho", rho)):
        if value <= 0:
            raise ValueError(f"{name} must be positive (got {value:g})")
    if not 0 < nu < 0.5:
        raise ValueError(f"nu must be in (0, 0.5) (got {nu:g})")
    if G_F is None and f_c is None:
        raise ValueError("give G_F, or f_c for fib MC2010's G_F")
    target = {"E": E, "nu": nu, "f_t": f_t, "G_F": G_F if G_F is not None else mc2010_fracture_energy(f_c)}
    if target["G_F"] <= 0:
        raise ValueError(f"G_F must be positive (got {target['G_F']:g} N/m)")
    material = lattice_material(E, nu, f_t / E, target["G_F"], rho)
    tried: List[tuple] = []  # (eps_p, strength) of each round
    for round_ in range(1, ROUNDS + 1):
        m = measure(material, L0, seeds, "load_loss", log)
        misses = {k: m[k] / target[k] - 1 for k in ("E", "f_t")}
        log(f"round {round_}: E {m['E'] / 1e9:.3f} GPa ({misses['E']:+.2%}), nu {m['nu']:.3f}, "
            f"f_t {m['f_t'] / 1e6:.3f} MPa ({misses['f_t']:+.2%})")
        if max(abs(x) for x in misses.values()) <= TOLERANCE or round_ == ROUNDS:
            break
        kE = E / m["E"]  # the strength scales with E eps_p (F_p = E A eps_p)
        strength = m["f_t"] * kE  # what the prism would give at the scaled E
        tried.append((material["eps_p"], strength))
        material = dict(material, E=material["E"] * kE, eps_p=next_eps_p(tried, f_t))
    return {"material": material, "target": target, "measured": {k: m[k] for k in ("E", "nu", "f_t")},
            "L0": L0, "seeds": list(seeds)}
