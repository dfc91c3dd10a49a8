"""The beam series of Grégoire, Rojas-Solano and Pijaudier-Cabot (2013),
"Failure and size effect for notched and unnotched concrete beams", as a
study (`ldem study beams`: ldem.study.beams): a blind prediction of
geometrically similar beams in three-point bending, depth D =
50, 100 and 200 mm, span 2.5 D, length 3.5 D, thickness 50 mm, notches 0, D/5
and D/2, six random specimens each, with the material taken only from the
properties the paper gives for its concrete (E = 37 GPa, nu = 0.21, f_t =
3.9 MPa, f_c = 42.3 MPa), never from the beams' measured loads.

The material, and why:
- E, nu: the paper's. The lattice is exactly isotropic at nu = 0.25 only; at
  0.21 the Nayfeh-Hefzy areas give E and nu to within a few per cent.
- G_f: the paper does not give it. fib Model Code 2010 (eq. 5.1-9):
  G_F = 73 f_cm^0.18 N/m = 143 N/m for f_cm = 42.3 MPa. CV(G_f) = 1 and
  c_a = 0.1385: the study's (LDEM_SPEC section 6), not fitted.
- eps_p: from a direct tension prism of the same concrete (50 x 50 x 100 mm,
  lower face fixed, upper face pulled, the study's cube test on a prism, three
  seeds): eps_p such that its mean strength is f_t = 3.9 MPa. One scaling from
  f_t / E, then checked (calibrate).
- L0 = 5 mm (D = 50 mm: 10 modules deep; the notches D/5 and D/2 are whole
  modules), the notch one module wide (5 mm, a saw cut's order, the same at
  every size) at mid-span, supports one node line, the loading platen one
  module wide, lateral DOFs of the left support held (a pin), of the right one
  free (a roller).
- Deflection rate 0.1 D per second, zeta 0.02 as in the study; a run stops once
  the deflection is twice that at the peak and the load below half the peak
  (PastThePeak), or at a deflection of 3e-3 D.

Cases: OUT/cases/D{mm}_n{notch}_s{seed}/ (random G_f), OUT/cases_cv0/ (uniform
G_f); tables: predictions.csv here, the size effect in tables.py."""
from __future__ import annotations

import math
import os
import statistics
from dataclasses import dataclass
from typing import Callable, List, Sequence, Tuple

from ... import io
from ...markdown import num_cell
from ..concrete import prism as tension_prism
from ..mc2010 import mc2010_fracture_energy
from ...specimen import SpecimenTest
from ..cases import Named
from ..executors import run_cases
from ..tables import mean_cv

E, NU, FT, FC = 37e9, 0.21, 3.9e6, 42.3e6
GF = mc2010_fracture_energy(FC)  # fib MC2010 eq. 5.1-9 [N/m]
L0 = 0.005
B = 0.05  # thickness [m]
MATERIAL = {"E": E, "nu": NU, "Gf_mean": GF}
DEPTHS, NOTCHES = (0.05, 0.1, 0.2), (0.0, 0.2, 0.5)
PREDICTION_COLUMNS = ["D_mm", "notch_ratio", "peak_load_kN", "cv", "seeds", "min_kN", "max_kN"]


@dataclass(frozen=True)
class Variant:
    """What a beam's run may change against the prediction's (the diagnosis
    varies one at a time). material: (name, value) pairs over MATERIAL
    (Gf_mean, Gf_cv, corr_length, law, ...); L0: the module; platen: its
    width in modules; supports: each a strip of that many node lines (held
    as the one line is: a wider one also resists the beam's rotation); rate:
    deflection rate / D [1/s]; opening_rate: a CMOD servo's opening rate / D
    [1/s] (0: the platen under displacement control); gauge: the length of a
    clip gauge across the notch's module on the lower face [m], a whole number
    of modules (probe gauge_m; the servo holds it when there is one), 0: none
    (the servo holds the notch module's opening, cmod_m); rate_periods: > 0
    drives by rule (c) instead of `rate`, eps_p in that many periods of the mode
    the drive moves (omega_d)."""
    material: Tuple[Tuple[str, object], ...] = ()
    L0: float = L0
    platen: int = 1
    supports: int = 1
    rate: float = 0.1
    opening_rate: float = 0.0
    gauge: float = 0.0
    rate_periods: float = 0.0

    def concrete(self, eps_p: float, **more) -> dict:
        """The material's parameters: the prediction's, eps_p and more, then the variant's."""
        return dict(MATERIAL, eps_p=eps_p, **more) | dict(self.material)


PREDICTION = Variant()


def prism(eps_p: float, seed: int, v: Variant = PREDICTION) -> SpecimenTest:
    """The direct tension prism 50 x 50 x 100 mm of the calibration of eps_p."""
    return tension_prism(v.concrete(eps_p), v.L0, seed)


def beam(D: float, notch: float, eps_p: float, seed: int, gf_cv: float = 1.0, v: Variant = PREDICTION) -> SpecimenTest:
    """Span 2.5 D centred on a length 3.5 D: supports at 0.5 D and 3 D. The
    notch (one module wide) and the platen (v.platen modules wide) are on the
    module at mid-span, or just right of it when mid-span is a node line (D =
    100, 200 mm: 2.5 mm off, 1 to 2 % of the span)."""
    h = v.L0
    length = 3.5 * D
    mid = (math.floor(1.75 * D / h + 1e-9) + 0.5) * h
    shape = {"kind": "box", "L0": h, "size": [length, B, D]}
    if notch > 0:
        shape["notch"] = {"depth": notch * D, "width": h, "at": mid}

    def support(x):  # one node line, or a strip of v.supports node lines
        if v.supports == 1:
            return {"face": "z-", "plane": {"x": x}}
        w = 0.5 * (v.supports - 1) * h
        return {"box": {"min": [x - w, 0.0, 0.0], "max": [x + w, B, 0.0]}}

    probes = {"cmod": {"a": [mid - 0.5 * h, 0.0, 0.0], "b": [mid + 0.5 * h, 0.0, 0.0], "direction": "x"}}
    if v.gauge > 0:
        probes["gauge"] = gauge_probe(mid, h, v.gauge)
    servo = {"control": "gauge" if v.gauge > 0 else "cmod"} if v.opening_rate > 0 else {}
    opening = {"opening_rate": v.opening_rate * D} if v.opening_rate > 0 else {}
    return SpecimenTest({
        "title": f"Gregoire 2013 beam D = {D * 1e3:g} mm, notch {notch:g} D",
        "shape": shape,
        "groups": {"left": dict(support(0.5 * D), fix=["x", "y", "z"]),
                   "right": dict(support(3.0 * D), fix=["z"]),
                   "supports": {"union": ["left", "right"]},
                   "load": {"box": {"min": [mid - 0.5 * v.platen * h, 0.0, D],
                                    "max": [mid + 0.5 * v.platen * h, B, D]},
                            "drive": {"z": -1.0}}},
        "measure": dict({"support": "supports", "loaded": "load", "area": 1.0, "gauge_length": D,  # stress = F [MN]
                         "stress_label": "load F [MN]", "strain_label": "deflection/D [-]",
                         "probes": probes}, **servo),
        "material": v.concrete(eps_p, Gf_cv=gf_cv),
        "loading": dict({"rate_periods": v.rate_periods} if v.rate_periods > 0 else {"strain_rate": v.rate},
                        **opening),
        "run": {"seed": seed, "final_strain": 3e-3, "threads": 1}})


def gauge_probe(mid: float, h: float, length: float) -> dict:
    """A clip gauge of `length` (n modules) on the lower face across the module
    centred on x = mid, its ends on the face's node lines: the n - 1 modules
    beyond that one split between the two sides, the odd one on the left."""
    n = round(length / h)
    if n < 1 or abs(n * h - length) > 1e-9 * length:
        raise ValueError(f"the gauge ({length * 1e3:g} mm) must be a whole number of modules ({h * 1e3:g} mm)")
    left = (n - 1) - (n - 1) // 2
    return {"a": [mid - (0.5 + left) * h, 0.0, 0.0], "b": [mid + (0.5 + (n - 1) // 2) * h, 0.0, 0.0],
            "direction": "x"}


class PastThePeak:
    """An observer that stops a beam's run once it is well past its peak: the
    deflection `beyond` (2) times that at the peak and the load below half the peak, once
    the supports have carried half the largest push (stress_top). (The
    load-loss test at a fraction of 0.5 would fire on the rising branch: its
    average over two fundamental periods is below half the current load early on.)
    rows: those recorded before a restart; opening: the CMOD instead of the
    deflection (under a CMOD servo the deflection may stall past the peak)."""

    def __init__(self, rows=(), opening: bool = False, beyond: float = 2.0):
        self.peak, self.at, self.pushed, self.key = 0.0, 0.0, 0.0, "cmod_m" if opening else "mean_strain"
        self.beyond = beyond
        for row in rows:
            self(row)

    def __call__(self, row) -> bool:
        if row["stress_MPa"] > self.peak:
            self.peak, self.at = row["stress_MPa"], row[self.key]
        # Not before the supports carry the load: at the start the push is still a
        # wave on its way (a specimen with far supports, the L-panel).
        self.pushed = max(self.pushed, row["stress_top_MPa"])
        carried = self.peak >= 0.5 * self.pushed > 0
        return not (carried and row[self.key] > self.beyond * self.at and row["stress_MPa"] < 0.5 * self.peak)


def beam_case(out: str, D: float, notch: float, seed: int, gf_cv: float = 1.0) -> str:
    """The folder of a beam's case in study folder out."""
    return os.path.join(out, "cases" if gf_cv == 1.0 else f"cases_cv{gf_cv:g}", f"D{D * 1e3:g}_n{notch:g}_s{seed}")


class Beam(Named):
    """One beam of the series as a study case: the SpecimenTest of beam(), run
    until PastThePeak; its folder D{mm}_n{notch}_s{seed} in cases/ (random G_f)
    or cases_cv{CV}/; seed 1 also writes the pictures and ParaView files."""

    def __init__(self, D: float, notch: float, eps_p: float, seed: int, gf_cv: float = 1.0,
                 v: Variant = PREDICTION, folder: str = ""):
        self.D, self.notch, self.eps_p, self.seed, self.gf_cv, self.v = D, notch, eps_p, seed, gf_cv, v
        default_folder, name = os.path.split(beam_case("", D, notch, seed, gf_cv))
        super().__init__(beam(D, notch, eps_p, seed, gf_cv, v), name,
                         ["curve", "summary"] + (["figures", "vtk"] if seed == 1 else []), folder or default_folder)

    def run(self, observers=(), simulation=None, previous_rows=()):
        stop = PastThePeak(previous_rows, opening=self.v.opening_rate > 0)
        return self.test.run(list(observers) + [stop], simulation, previous_rows)


def calibrate(log: Callable[[str], None] = print, v: Variant = PREDICTION) -> float:
    """eps_p such that the prisms' (seeds 1-3) mean strength is f_t: one
    scaling from f_t / E, then checked. Returns it."""
    eps = FT / E
    for it in range(2):
        peaks = [prism(eps, s, v).run().summary["peak_stress_MPa"] * 1e6 for s in (1, 2, 3)]
        mean = statistics.mean(peaks)
        log(f"eps_p {eps:.6g}: strengths {', '.join(f'{p / 1e6:.4f}' for p in peaks)} MPa, mean "
            f"{mean / 1e6:.4f} MPa ({mean / FT - 1:+.2%} of f_t)")
        if it == 0:
            eps *= FT / mean
    log(f"eps_p = {eps:.6g}")
    return eps


def series_tests(eps_p: float, seeds: int, v: Variant = PREDICTION, depths=DEPTHS, notches=NOTCHES) -> List[Beam]:
    """Every beam with random G_f, seed by seed: a series cut short has as many
    specimens of every beam."""
    return [Beam(D, n, eps_p, s, v=v) for s in range(1, seeds + 1) for D in depths for n in notches]


def calibrated_variant(material: dict) -> Variant:
    """The beams with a material of ldem.study.concrete.calibrate (its eps_p apart)."""
    return Variant(tuple((k, v) for k, v in material.items() if k != "eps_p"))


def uniform_tests(eps_p: float) -> List[Beam]:
    """The beams with a uniform G_f (CV 0, one specimen each: the field is the
    only randomness): D = 50 and 100 mm with every notch, then D = 200 mm (8
    minutes a run on one thread) with the notches 0.5 and 0.2: enough for
    Bažant's law at those notches and the unnotched slope from 50 to 100 mm."""
    beams = [(D, n) for D in DEPTHS[:2] for n in NOTCHES] + [(0.2, 0.5), (0.2, 0.2)]
    return [Beam(D, n, eps_p, 1, 0.0) for D, n in beams]


def run_beams(tests: Sequence[Beam], out: str, jobs: int = 1, log: Callable[[str], None] = print) -> List[dict]:
    """The unfinished cases, `jobs` at a time (one thread each); their summaries."""
    return run_cases(tests, out, jobs=jobs, log=log)


def finished_peaks(out: str, D: float, notch: float, seeds: int, gf_cv: float = 1.0) -> List[float]:
    """The peak loads [kN] of the beam's finished cases (the force of area 1 [MN] -> kN)."""
    peaks = []
    for seed in range(1, seeds + 1):
        path = os.path.join(beam_case(out, D, notch, seed, gf_cv), io.tables.SUMMARY)
        if os.path.exists(path):
            s = io.read_summary(path)
            if s.get("status") == "done":
                peaks.append(s["peak_stress_MPa"] * 1e3)
    return peaks


def write_predictions(out: str, seeds: int, log: Callable[[str], None] = print) -> List[dict]:
    """predictions.csv: per beam, the mean peak load [kN], CV, min and max over
    its finished specimens."""
    rows = []
    for D in DEPTHS:
        for notch in NOTCHES:
            loads = finished_peaks(out, D, notch, seeds)
            if not loads:
                log(f"D {D * 1e3:g} mm, notch {notch:g}: no specimen finished")
                continue
            mean, cv = mean_cv(loads)
            rows.append({"D_mm": D * 1e3, "notch_ratio": notch, "peak_load_kN": mean, "cv": cv,
                         "seeds": len(loads), "min_kN": min(loads), "max_kN": max(loads)})
    io.write_table(os.path.join(out, "predictions.csv"), rows, PREDICTION_COLUMNS)
    for r in rows:
        log(f"{r['D_mm']:g} mm, notch {r['notch_ratio']:g}: {r['peak_load_kN']:.3f} kN (CV {num_cell(r['cv'], '.3f')})")
    return rows
