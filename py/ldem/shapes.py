"""Shapes on the lattice: which modules of a bounding box a specimen keeps
(a box with or without a notch, a cylinder, a dog-bone, a mask from a file),
and the checks of a description's values, each error naming its key and, for
a file, its line. Geometry only: the lattice itself is built in C++
(ldem._core.build_lattice).
"""
from __future__ import annotations

import difflib
import math
import os
import re

import numpy as np

from . import _core

AXES = {"x": 0, "y": 1, "z": 2}
_SHAPE_KEYS = {"box": {"size", "notch", "cutout"}, "cylinder": {"diameter", "length", "axis"},
               "dogbone": {"size", "neck", "radius"}, "mask": {"file", "size"}}


class SpecimenError(ValueError):
    """A bad specimen description: one line naming the key (and the file's line)."""


class Where:
    """Names a key of the description, with its line when it came from a file."""

    def __init__(self, text: str = "", path: str = ""):
        self.lines, self.path = text.splitlines(), path

    def __call__(self, key: str, message: str) -> SpecimenError:
        line = self._line(key)
        at = f"{self.path}:{line}: " if line else (f"{self.path}: " if self.path else "")
        return SpecimenError(f"{at}{key}: {message}")

    def _line(self, key: str) -> int:
        """The line of the dotted key: its last part written as `part =` or a
        `[table]`, after the line of its parent, if one can be found."""
        parts = key.split(".")
        start = 0
        for depth, part in enumerate(parts):
            pattern = re.compile(r"(^|[\s{,.\[])" + re.escape(part) + r"\s*(=|\]|\.)")
            for i in range(start, len(self.lines)):
                if pattern.search(self.lines[i].split("#")[0]):
                    start = i
                    break
            else:
                return start + 1 if depth else 0
        return start + 1


def check_keys(table: dict, allowed: set, where: Where, prefix: str) -> None:
    for k in table:
        if k not in allowed:
            near = difflib.get_close_matches(str(k), sorted(allowed), n=1)
            hint = f"did you mean '{near[0]}'? " if near else ""
            raise where(f"{prefix}{k}", f"unknown key ({hint}expected one of {', '.join(sorted(allowed))})")


def named(value, options) -> bool:
    """value is one of the names in options (a file may give any TOML value)."""
    return isinstance(value, str) and value in options


def number(value, where: Where, key: str, positive: bool = True) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise where(key, f"must be a number (got {value!r})")
    if positive and not value > 0:
        raise where(key, f"must be positive (got {value!r})")
    return float(value)


def point(value, where: Where, key: str) -> np.ndarray:
    if not (isinstance(value, list) and len(value) == 3):
        raise where(key, f"must be a point [x, y, z] in m (got {value!r})")
    return np.array([number(v, where, key, positive=False) for v in value])


# A bound may sit on the box's face to its decimals, or a hair beyond it to be sure of the face's modules
# (tests/py/test_cutouts.py runs a slot a thousandth of a module past the faces): a hundredth of a module.
ON_THE_BOX = 0.01


def inside(value, lo, hi, L0: float, where: Where, key: str, axes: str = "xyz") -> None:
    """Refuses a point (or the coordinates along `axes`) beyond the specimen's box lo..hi: a notch, cutout or
    group out there cuts or selects less than it says, or nothing, and the run would not say so."""
    x, lo, hi = (np.atleast_1d(np.asarray(v, float)) for v in (value, lo, hi))
    tol = ON_THE_BOX * L0
    if np.all(x >= lo - tol) and np.all(x <= hi + tol):
        return
    got = ", ".join(f"{v:g}" for v in x)
    raise where(key, f"must lie inside or on the specimen's box, {box_words(lo, hi, axes)} m "
                     f"(got {f'[{got}]' if len(x) > 1 else got})")


def box_words(lo, hi, axes: str = "xyz") -> str:
    """'[0, 0.35] x [0, 0.05] x [0, 0.1]', or along one axis 'x in [0, 0.35]'."""
    if len(axes) == 1:
        return f"{axes} in [{lo[0]:g}, {hi[0]:g}]"
    return " x ".join(f"[{a:g}, {b:g}]" for a, b in zip(lo, hi))


def _modules(length: float, L0: float, where: Where, key: str) -> int:
    if not length / L0 <= 1e5:  # ldem cube's bound (CubeGeometry::modules): no count below overflows
        raise where(key, f"{length:g} m is {length / L0:g} modules of L0 = {L0:g} m: far beyond any machine")
    n = round(length / L0)
    if n < 1 or abs(n * L0 - length) > 1e-9 * length:
        raise where(key, f"{length:g} m is not a multiple of the module L0 = {L0:g} m")
    return n


# -- shapes: which modules of the bounding box are present ----------------------------------------

def module_mask(shape: dict, where: Optional[Where] = None):
    """(L0, (nx, ny, nz), mask[nx, ny, nz] bool) of a [shape] table."""
    where = where or Where()
    kind = shape.get("kind")
    # A misspelt key first: `knd = "box"` is that, more than a missing kind.
    check_keys(shape, set().union(*_SHAPE_KEYS.values(), {"kind", "L0"}), where, "shape.")
    if not named(kind, _SHAPE_KEYS):
        raise where("shape.kind", f"must be one of {', '.join(_SHAPE_KEYS)} (got {kind!r})")
    check_keys(shape, _SHAPE_KEYS[kind] | {"kind", "L0"}, where, "shape.")
    L0 = number(shape.get("L0"), where, "shape.L0")
    if kind == "cylinder":
        d = number(shape.get("diameter"), where, "shape.diameter")
        length = number(shape.get("length"), where, "shape.length")
        axis = AXES.get(shape["axis"]) if named(shape.get("axis", "z"), AXES) else None
        if axis is None:
            raise where("shape.axis", f"must be x, y or z (got {shape.get('axis')!r})")
        size = [d, d, d]
        size[axis] = length
    else:
        size = shape.get("size")
        if not (isinstance(size, list) and len(size) == 3):
            raise where("shape.size", f"must be [x, y, z] in m (got {size!r})")
        size = [number(s, where, "shape.size") for s in size]
    n = tuple(_modules(s, L0, where, "shape.diameter" if kind == "cylinder" else "shape.size") for s in size)
    try:  # the lattice's memory estimate (the same as ldem cube's), before the arrays below
        _core.check_fits(*n)
    except ValueError as e:
        raise where("shape.L0", str(e)) from None
    # Module centres.
    c = [(np.arange(k) + 0.5) * L0 for k in n]
    x, y, z = np.meshgrid(*c, indexing="ij")
    if kind == "box":
        mask = np.ones(n, bool)
        if "notch" in shape:
            mask &= ~_notch(shape["notch"], x, z, size, L0, where)
        if "cutout" in shape:
            mask &= ~_cutout(shape["cutout"], x, y, z, size, L0, where)
    elif kind == "cylinder":
        r = [x, y, z]
        across = [r[a] - 0.5 * d for a in range(3) if a != axis]
        mask = across[0] ** 2 + across[1] ** 2 <= (0.5 * d) ** 2
    elif kind == "dogbone":
        mask = _dogbone(shape, x, z, size, where)
    else:
        mask = _mask_file(shape, n, where)
    if not mask.any():
        raise where("shape", "has no module")
    return L0, n, mask


def _notch(notch, x, z, size, L0, where) -> np.ndarray:
    """A slot from the lower face (z = 0) up to `depth`, `width` wide (a module
    at least), centred on `at` along x (default: mid-length)."""
    if not isinstance(notch, dict):
        raise where("shape.notch", "must be a table {depth, width, at}")
    check_keys(notch, {"depth", "width", "at"}, where, "shape.notch.")
    depth = number(notch.get("depth", 0.0), where, "shape.notch.depth", positive=False)
    width = number(notch.get("width", L0), where, "shape.notch.width")
    at = number(notch.get("at", 0.5 * size[0]), where, "shape.notch.at", positive=False)
    if depth < 0 or depth >= size[2]:
        raise where("shape.notch.depth", f"must be in [0, {size[2]:g}) m (got {depth:g})")
    if width < L0 * (1 - 1e-9):
        raise where("shape.notch.width", f"must be at least one module, {L0:g} m (got {width:g})")
    left, right = at - 0.5 * width, at + 0.5 * width
    if not (left >= -ON_THE_BOX * L0 and right <= size[0] + ON_THE_BOX * L0):
        raise where("shape.notch.at", f"the slot, x from {left:g} to {right:g} m, must lie inside or on the "
                                      f"specimen's box, {box_words([0], [size[0]], 'x')} m (got at = {at:g})")
    return (np.abs(x - at) < 0.5 * width) & (z < depth)


def _cutout(cut, x, y, z, size, L0, where) -> np.ndarray:
    """The modules whose centres are inside the box {min, max} (e.g. the
    missing quadrant of an L-shaped panel)."""
    if not isinstance(cut, dict):
        raise where("shape.cutout", "must be a table {min = [x, y, z], max = [x, y, z]}")
    check_keys(cut, {"min", "max"}, where, "shape.cutout.")
    lo, hi = point(cut.get("min"), where, "shape.cutout.min"), point(cut.get("max"), where, "shape.cutout.max")
    if (hi <= lo).any():
        raise where("shape.cutout.max", f"must be above min on every axis (min {list(lo)}, max {list(hi)})")
    for k, p in (("min", lo), ("max", hi)):
        inside(p, [0, 0, 0], size, L0, where, f"shape.cutout.{k}")
    return (x > lo[0]) & (x < hi[0]) & (y > lo[1]) & (y < hi[1]) & (z > lo[2]) & (z < hi[2])


def _dogbone(shape, x, z, size, where) -> np.ndarray:
    """Van Vliet and van Mier's dog-bone: a plate of width size[0] (x) and height
    size[2] (z) narrowed to `neck` at mid-height by two circular arcs of `radius`."""
    W, H = size[0], size[2]
    neck = number(shape.get("neck"), where, "shape.neck")
    R = number(shape.get("radius"), where, "shape.radius")
    depth = 0.5 * (W - neck)  # each arc's cut at mid-height
    if not 0 < depth < R:
        raise where("shape.neck", f"must be narrower than the width {W:g} m and cut less than the radius "
                                  f"(cut {depth:g} m, radius {R:g} m)")
    dz = z - 0.5 * H
    cut = np.maximum(0.0, depth - (R - np.sqrt(np.maximum(R * R - dz * dz, 0.0))))
    cut[np.abs(dz) >= R] = 0.0
    return (x >= cut) & (x <= W - cut)


def _mask_file(shape, n, where) -> np.ndarray:
    path = shape.get("file")
    if not isinstance(path, str):
        raise where("shape.file", "must name a .npy file of a boolean array (modules along x, y, z)")
    base = os.path.dirname(where.path) if where.path else ""
    try:
        mask = np.load(os.path.join(base, path))
    except (OSError, ValueError) as e:
        raise where("shape.file", f"cannot read {path}: {e}") from None
    if mask.shape != n:
        raise where("shape.file", f"{path} has shape {mask.shape}; size / L0 gives {n}")
    return mask.astype(bool)


class Nodes:
    """The nodes of the box of n modules of side L0, numbered as the lattice numbers
    them (corners x-fastest, then centres), their coordinates and which belong to a
    kept module (mask[i, j, k]): computed, not built, so that no process needs the
    whole lattice (under MPI each rank builds its slab, pkg/ldem/Slab.hpp)."""

    def __init__(self, n, L0, mask):
        def grid(counts, offset):  # (i, j, k) L0 of every node of a grid, x fastest
            k, j, i = np.meshgrid(*(np.arange(c) for c in reversed(counts)), indexing="ij")
            return np.column_stack([(a.ravel() + offset) * L0 for a in (i, j, k)])
        nx, ny, nz = n
        self.x = np.vstack([grid((nx + 1, ny + 1, nz + 1), 0), grid((nx, ny, nz), 0.5)])
        padded = np.pad(mask.astype(bool), 1)
        corner = np.zeros((nx + 1, ny + 1, nz + 1), dtype=bool)  # a corner of some kept module
        for d in np.ndindex(2, 2, 2):
            corner |= padded[d[0]:d[0] + nx + 1, d[1]:d[1] + ny + 1, d[2]:d[2] + nz + 1]
        self.present = np.concatenate([corner.transpose(2, 1, 0).ravel(), mask.astype(bool).transpose(2, 1, 0).ravel()])
        self.lo, self.hi = self.x.min(axis=0), self.x.max(axis=0)  # the box's
        self.tol = 1e-6 * L0
        self.L0 = L0
