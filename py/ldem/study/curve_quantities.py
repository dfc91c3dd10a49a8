"""What an engineer reads off a load-opening curve beyond its peak: the load
at given multiples of the opening at the peak, and the work under the curve to
the last of them. Pure functions of (x, load) arrays: x an opening or a
deflection [mm], the load [kN], so a work is in kN mm = J.

Measured curves are noisy at their start (a CMOD that steps back) and driven
ones may start below zero (a beam zeroed under its weight): every quantity
is read along the recorded path, from x = 0 on."""
from __future__ import annotations

from typing import Dict, Sequence, Tuple

import numpy as np

Curve = Tuple[np.ndarray, np.ndarray]  # (x [mm], load [kN])
MULTIPLES = (1.5, 2.0, 4.0)  # of the opening at the peak


def rising(curve: Curve) -> Curve:
    """The curve up to its peak."""
    j = int(np.argmax(curve[1])) + 1
    return curve[0][:j], curve[1][:j]


def cmod_at_peak(curve: Curve) -> float:
    """The opening of the recorded point of largest load."""
    return float(rising(curve)[0][-1])


def load_at_opening(curve: Curve, x: float) -> float:
    """The load when the opening first reaches x, linear between the recorded
    points (nan if it never does)."""
    cmod, load = curve
    j = int(np.argmax(cmod >= x))
    return float(np.interp(x, cmod[j - 1:j + 1], load[j - 1:j + 1])) if j > 0 else float("nan")


def past_the_peak(curve: Curve) -> Curve:
    """The curve from its peak on (where 1.5, 2 and 4 times the opening at the
    peak are first reached, even if the opening stepped back before the peak)."""
    j = int(np.argmax(curve[1]))
    return curve[0][j:], curve[1][j:]


def load_past_the_peak(curve: Curve, x: float) -> float:
    """The load when the opening first reaches x after the peak (nan if it
    never does; the peak's own load if x is below the opening there)."""
    after = past_the_peak(curve)
    return float(after[1][0]) if x <= after[0][0] else load_at_opening(after, x)


def work_to(curve: Curve, x_end: float) -> float:
    """The work of the load along the recorded path from x = 0 to where x first
    reaches x_end past the peak, W = int P dx by the trapezoidal rule, the two
    ends cut at x = 0 and x_end by linear interpolation (nan if the curve never
    reaches x_end)."""
    x, load = (np.asarray(a, float) for a in curve)
    peak = int(np.argmax(load))
    ends = np.nonzero(x[peak:] >= x_end)[0]
    if len(ends) == 0:
        return float("nan")
    j = peak + int(ends[0])
    if j > 0 and x[j] > x_end:  # cut the last segment at x_end
        f = (x_end - x[j - 1]) / (x[j] - x[j - 1])
        x, load = np.append(x[:j], x_end), np.append(load[:j], load[j - 1] + f * (load[j] - load[j - 1]))
    else:
        x, load = x[:j + 1], load[:j + 1]
    i = int(np.argmax(x >= 0.0))
    if i > 0:  # start at x = 0, between the last negative point and the first one past it
        f = -x[i - 1] / (x[i] - x[i - 1])
        x, load = np.insert(x[i:], 0, 0.0), np.insert(load[i:], 0, load[i - 1] + f * (load[i] - load[i - 1]))
    return float(np.sum(0.5 * (load[1:] + load[:-1]) * np.diff(x)))


def quantities(curve: Curve, x_ref: float, multiples: Sequence[float] = MULTIPLES) -> Dict[str, float]:
    """The peak and the opening there, the load at each multiple m of x_ref
    (load_at_{m}), and the work to the last multiple (work_J). x_ref: the
    measured opening at the peak, or the curve's own where none was measured."""
    x, load = (np.asarray(a, float) for a in curve)
    out = {"peak_kN": float(load.max()), "x_at_peak": cmod_at_peak((x, load))}
    for m in multiples:
        out[f"load_at_{m:g}"] = load_past_the_peak((x, load), m * x_ref)
    out["work_J"] = work_to((x, load), multiples[-1] * x_ref)
    return out
