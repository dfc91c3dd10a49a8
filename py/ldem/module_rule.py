"""The module a specimen needs: at least RULE_MODULES modules over the
ligament above a notch (a box's depth z less the notch's depth), or
RULE_MODULES_DEPTH over the depth of a specimen without one (a box's z, a
cylinder's diameter, a dog-bone's neck, a mask's smallest side). `ldem run`
warns when a file is coarser, naming the module that meets the rule, L0 / k
for the smallest whole k (every length of the file stays a whole number of
modules), and the bars it would cost (bar_count of the file's shape at that
module).

Both counts are measured on the Grégoire beams at a fixed concrete (`ldem
study beams convergence`, results/beams/gregoire2013/convergence/): the
fewest modules from which on each beam's peak lies within 2 % of its finest
module's. Notched: 15 over the ligament (notch D/2, finest 20) and 16 (notch
D/5, finest 32). Unnotched: 30 over the depth (finest 40), where the peak still
rose by 1.9 % from 30 to 40 after 2.8 and 3.7 % at the refinements before."""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from .shapes import module_mask

RULE_MODULES = 16  # modules over the ligament above a notch
RULE_MODULES_DEPTH = 30  # modules over the depth of a specimen without a notch
LIGAMENT = "ligament above the notch"


def rule_modules(what: str) -> int:
    """The count the rule asks over governing_length's `what`."""
    return RULE_MODULES if what == LIGAMENT else RULE_MODULES_DEPTH


def governing_length(shape: dict) -> tuple:
    """(what, length [m]) that the rule counts in modules, of a [shape] table."""
    kind = shape.get("kind")
    if kind == "cylinder":
        return "diameter", float(shape["diameter"])
    if kind == "dogbone":
        return "neck", float(shape["neck"])
    size = [float(s) for s in shape["size"]]
    if kind == "mask":
        return "smallest side", min(size)
    notch = float((shape.get("notch") or {}).get("depth", 0.0))
    return (LIGAMENT, size[2] - notch) if notch > 0 else ("depth", size[2])


def bar_count(mask: np.ndarray) -> int:
    """The bars of the lattice of the modules in mask[nx, ny, nz] (LDEM_SPEC
    section 1): 8 diagonals a module, a centre-to-centre bar per pair of
    face-adjacent modules, and each cube edge of at least one module once."""
    m = mask.astype(bool)
    p = np.pad(m, 1)
    # An edge along x at corner (i, j, k) is shared by the modules (i, j-1..j, k-1..k): padded (i+1, j..j+1, k..k+1).
    edges = (p[1:-1, :-1, :-1] | p[1:-1, 1:, :-1] | p[1:-1, :-1, 1:] | p[1:-1, 1:, 1:]).sum() \
        + (p[:-1, 1:-1, :-1] | p[1:, 1:-1, :-1] | p[:-1, 1:-1, 1:] | p[1:, 1:-1, 1:]).sum() \
        + (p[:-1, :-1, 1:-1] | p[1:, :-1, 1:-1] | p[:-1, 1:, 1:-1] | p[1:, 1:, 1:-1]).sum()
    centres = (m[1:] & m[:-1]).sum() + (m[:, 1:] & m[:, :-1]).sum() + (m[:, :, 1:] & m[:, :, :-1]).sum()
    return int(8 * m.sum() + centres + edges)


def needed(shape: dict, L0: float) -> Optional[dict]:
    """None when the shape at module L0 meets the rule; else what, length,
    modules (its count now), rule (the count asked), k, L0 (L0 / k, the
    coarsest that meets it) and bars (at that module; None: more than this
    machine holds)."""
    what, length = governing_length(shape)
    modules, rule = length / L0, rule_modules(what)
    if modules >= rule - 1e-9:
        return None
    k = math.ceil(rule / modules - 1e-9)
    try:
        bars = bar_count(module_mask(dict(shape, L0=L0 / k))[2])
    except ValueError:  # the finer lattice would not fit this machine (shapes.module_mask's estimate)
        bars = None
    return {"what": what, "length": length, "modules": modules, "rule": rule, "k": k, "L0": L0 / k, "bars": bars}


def warning(shape: dict, L0: float, bars: int) -> str:
    """The warning of a shape coarser than the rule ("" if it meets it); bars: its count now."""
    n = needed(shape, L0)
    if n is None:
        return ""
    return (f"the {n['what']} is {n['modules']:.3g} modules of L0 = {L0 * 1e3:g} mm, fewer than the module rule's "
            f"{n['rule']}: the peak may depend on the module; L0 = "
            f"{n['L0'] * 1e3:.4g} mm (L0 / {n['k']}) meets it, at "
            + (f"{n['bars']:,} bars" if n["bars"] is not None else "more bars than this machine holds")
            + f" (now {bars:,})")
