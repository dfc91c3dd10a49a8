"""What fib Model Code 2010 gives of a concrete from its mean compressive
strength f_c alone (section 5.1), for the calibration (concrete.calibrate) of a
concrete whose laboratory reported less than E, nu, f_t and G_F."""
from __future__ import annotations

from typing import Optional

import numpy as np

MC2010_GF_SOURCE = "fib MC2010 eq. 5.1-9"


def mc2010_fracture_energy(f_c: float) -> float:
    """G_F [N/m] from the mean compressive strength f_c [Pa]: fib Model Code
    2010 eq. 5.1-9, G_F = 73 f_cm^0.18 (f_cm in MPa)."""
    if f_c <= 0:
        raise ValueError(f"f_c must be positive (got {f_c:g} Pa)")
    return 73.0 * (f_c / 1e6) ** 0.18


def mc2010_from_compressive_strength(f_c: float) -> dict:
    """What fib Model Code 2010 gives from the mean compressive strength f_c [Pa]
    alone (section 5.1), for a concrete of which nothing else was measured:
    - f_ck = f_cm - 8 MPa (eq. 5.1-1);
    - E = E_ci = 21.5 GPa (f_cm/10)^(1/3) (eq. 5.1-21, quartzite aggregate,
      alpha_E = 1): the tangent modulus at the origin. The reduced E_c of
      eq. 5.1-23 allows for the plastic strain of a cylinder in compression;
      a bending test's tension side stays below f_t, far from it;
    - f_t = f_ctm, the mean axial tensile strength: 0.30 f_ck^(2/3) up to C50,
      2.12 ln(1 + f_cm/10) above (eqs. 5.1-3a, 5.1-3b; MPa);
    - G_F = 73 f_cm^0.18 (eq. 5.1-9);
    - nu = 0.2 (section 5.1.7.3).
    Returns {"E", "nu", "f_t", "G_F"} in Pa and N/m, and "sources"."""
    if f_c <= 0:
        raise ValueError(f"f_c must be positive (got {f_c:g} Pa)")
    fcm = f_c / 1e6
    fck = fcm - 8.0
    if fck <= 0:
        raise ValueError(f"f_c = {fcm:g} MPa: f_ck = f_cm - 8 MPa is not positive, outside fib MC2010")
    f_t = 0.30 * fck ** (2 / 3) if fck <= 50 else 2.12 * np.log(1 + fcm / 10)
    return {"E": 21.5e9 * (fcm / 10) ** (1 / 3), "nu": 0.2, "f_t": float(f_t) * 1e6,
            "G_F": mc2010_fracture_energy(f_c),
            "sources": {"E": "fib MC2010 eq. 5.1-21, E_ci (alpha_E = 1)",
                        "f_t": "fib MC2010 eq. 5.1-3" + ("a" if fck <= 50 else "b") + ", f_ctm",
                        "G_F": MC2010_GF_SOURCE, "nu": "fib MC2010 5.1.7.3"}}


def lab_values(E: Optional[float], nu: Optional[float], f_t: Optional[float], f_c: Optional[float],
               G_F: Optional[float]) -> tuple:
    """({"E", "nu", "f_t"}, sources): what a laboratory gave, the rest from fib
    MC2010 and f_c (mc2010_from_compressive_strength); sources names each
    value's origin, G_F's too (calibrate takes MC2010's G_F from f_c if not given)."""
    given = {"E": E, "nu": nu, "f_t": f_t}
    sources = {k: "given" for k, v in given.items() if v is not None}
    if None in given.values():
        if f_c is None:
            missing = ", ".join("--" + {"f_t": "ft"}.get(k, k) for k, v in given.items() if v is None)
            raise ValueError(f"give {missing}, or --fc for fib MC2010's")
        mc = mc2010_from_compressive_strength(f_c)
        for k, v in given.items():
            if v is None:
                given[k], sources[k] = mc[k], mc["sources"][k]
    sources["G_F"] = "given" if G_F is not None else MC2010_GF_SOURCE
    return given, sources
