"""Cutouts and notches of a box specimen (py/ldem/shapes.py), checked module
by module against their definition: a cutout removes exactly the modules whose
centres lie inside its box, on each axis by its own bounds, whether it stops
inside the specimen (a pocket) or runs through it (a slot); a notch removes
its slot from the lower face over the whole thickness."""
import itertools

import numpy as np
import pytest

from ldem.shapes import module_mask

L0 = 0.01
N = (6, 4, 5)  # modules along x, y, z: no two alike, so a swapped axis shows


def expected(ranges):
    """The box's mask with the modules of ranges[a] = (first, end) on every axis a removed."""
    keep = np.ones(N, bool)
    keep[tuple(slice(*r) for r in ranges)] = False
    return keep


# On each axis: a pocket (from module 1 to one short of the far face) or
# through (face to face); the other axes' bounds each its own part of the box.
CASES = [(axis, through) for axis in range(3) for through in (False, True)]


@pytest.mark.direct
@pytest.mark.parametrize("axis,through", CASES, ids=[f"{'xyz'[a]}_{'through' if t else 'partial'}" for a, t in CASES])
def test_a_cutout_removes_exactly_the_modules_inside_its_bounds(axis, through):
    ranges = [(1, 3), (1, 3), (2, 4)]
    ranges[axis] = (0, N[axis]) if through else (1, N[axis] - 1)
    # Bounds on module faces, the faces just outside the box where it runs through.
    lo = [r[0] * L0 - (1e-3 * L0 if r[0] == 0 else 0.0) for r in ranges]
    hi = [r[1] * L0 + (1e-3 * L0 if r[1] == n else 0.0) for r, n in zip(ranges, N)]
    _, n, mask = module_mask({"kind": "box", "L0": L0, "size": [k * L0 for k in N],
                              "cutout": {"min": lo, "max": hi}})
    assert n == N
    want = expected(ranges)
    wrong = np.argwhere(mask != want)
    assert not wrong.size, f"modules (i, j, k) wrongly {'kept' if mask[tuple(wrong[0])] else 'cut'}: {wrong[:5].tolist()}"


@pytest.mark.direct
@pytest.mark.parametrize("depth,width,at", [(2, 1, 3), (3, 2, 2), (4, 1, 0)])
def test_a_notch_removes_its_slot_over_the_whole_thickness(depth, width, at):
    """depth, width in modules; at: the module whose lower face is the slot's left side."""
    centre = (at + 0.5 * width) * L0
    _, n, mask = module_mask({"kind": "box", "L0": L0, "size": [k * L0 for k in N],
                              "notch": {"depth": depth * L0, "width": width * L0, "at": centre}})
    assert n == N
    want = expected([(at, at + width), (0, N[1]), (0, depth)])
    assert np.array_equal(mask, want), np.argwhere(mask != want)[:5].tolist()


def test_bounds_between_module_centres_take_the_centres_inside():
    """A cutout's bounds need not lie on module faces: a module is cut when its centre is inside."""
    for lo, hi in itertools.product([0.004, 0.006], [0.024, 0.026]):
        _, _, mask = module_mask({"kind": "box", "L0": L0, "size": [k * L0 for k in N],
                                  "cutout": {"min": [lo, lo, lo], "max": [hi, hi, hi]}})
        first, end = (0 if lo < 0.005 else 1), (3 if hi > 0.025 else 2)
        assert np.array_equal(mask, expected([(first, end)] * 3)), (lo, hi)
