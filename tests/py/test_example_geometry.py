"""Each committed specimen file (examples/*.toml) against the dimensions its
header states: the box (or cylinder), the supports, the platen, the notch and
the cutout, read back from what the file builds (ldem.specimen: the module
mask and the node groups), in m. A new file states its dimensions here too."""
import glob
import os

import numpy as np
import pytest

from conftest import ROOT
from ldem.shapes import Nodes
from ldem.specimen import SpecimenTest

LINE, FACE = "line", "face"


def beam(length, thickness, depth, supports, load_x, load_width, notch):
    """A beam in three-point bending: supports (lines across the thickness on
    the lower face) at x in `supports`, a platen load_width wide centred on
    load_x on the upper face, notch (depth, width, centre x) from the lower face."""
    return dict(size=(length, thickness, depth), notch=notch,
                groups={"left": dict(x=(supports[0],) * 2, z=(0.0, 0.0)),
                        "right": dict(x=(supports[1],) * 2, z=(0.0, 0.0)),
                        "load": dict(x=(load_x - load_width / 2, load_x + load_width / 2), z=(depth, depth))})


def faces(size):
    """Lower and upper faces whole."""
    return dict(size=size, groups={"bottom": dict(x=(0.0, size[0]), z=(0.0, 0.0)),
                                   "top": dict(x=(0.0, size[0]), z=(size[2], size[2]))})


STATED = {
    # depth D = 0.10 m, span 2.5 D = 0.25 m, length 0.35 m, thickness 0.05 m,
    # notch D/5 at mid-span; supports 0.125 m either side of mid-span; a platen one module (0.01 m) wide.
    "beam_3pb.toml": beam(0.35, 0.05, 0.10, (0.175 - 0.125, 0.175 + 0.125), 0.175, 0.01, (0.02, 0.01, 0.175)),
    "beam_3pb_cmod.toml": beam(0.35, 0.05, 0.10, (0.175 - 0.125, 0.175 + 0.125), 0.175, 0.01, (0.02, 0.01, 0.175)),
    # depth 80 mm, thickness 50 mm, length 250 mm, span 200 mm (supports 25 mm
    # from each end), load at mid-span on a platen 10 mm wide; notch 20 mm deep,
    # two modules (10 mm) wide, centred 50 mm from mid-span (x = 75 mm).
    "eccentric_notch_beam.toml": beam(0.25, 0.05, 0.08, (0.025, 0.225), 0.125, 0.01, (0.02, 0.01, 0.075)),
    # 500 x 500 mm, 100 mm thick, without its lower-right 250 x 250 mm quadrant;
    # the vertical leg's lower edge held; a platen 20 mm wide under the arm
    # (z = 250 mm) centred on x = 470 mm.
    "l_panel.toml": dict(size=(0.5, 0.1, 0.5), cutout=((0.25, 0.5), (0.0, 0.1), (0.0, 0.25)),
                         groups={"base": dict(x=(0.0, 0.25), z=(0.0, 0.0)),
                                 "load": dict(x=(0.46, 0.48), z=(0.25, 0.25))}),
    # Malvar and Warren (1988) at L0 = 10.2 mm: 102 x 102 mm, 81 modules long (826.2 mm), supports
    # 77 modules (785.4 mm) apart centred on mid-span (x = 413.1 mm), a platen and a notch 51 mm deep
    # one module (10.2 mm) wide there.
    "malvar_warren_beam.toml": beam(0.8262, 0.102, 0.102, (0.0204, 0.8058), 0.4131, 0.0102, (0.051, 0.0102, 0.4131)),
    # a cylinder D = 0.1 m, 0.02 m long along y, between strips 0.01 m wide along its length.
    "brazilian.toml": dict(size=(0.1, 0.02, 0.1), groups={"bottom": dict(x=(0.045, 0.055), z=(0.0, 0.0)),
                                                          "top": dict(x=(0.045, 0.055), z=(0.1, 0.1))}),
    "cube_uniform.toml": faces((0.12, 0.12, 0.12)),
    "cube_triangular.toml": faces((0.12, 0.12, 0.12)),
    "compression.toml": faces((0.10, 0.10, 0.10)),
    # D = 0.1 m: height 1.5 D, 0.02 m thick, glued between platens (its faces).
    "dogbone.toml": faces((0.10, 0.02, 0.15)),
}

FILES = sorted(glob.glob(os.path.join(ROOT, "examples", "*.toml")))


def test_every_specimen_file_states_its_dimensions_here():
    assert sorted(os.path.basename(f) for f in FILES) == sorted(STATED)


def removed_extent(build):
    """(lo, hi) on each axis of the modules the shape removes from its box (a notch, a cutout)."""
    ijk = np.argwhere(~build.mask)
    return [(ijk[:, a].min() * build.L0, (ijk[:, a].max() + 1) * build.L0) for a in range(3)]


@pytest.mark.direct
@pytest.mark.parametrize("path", FILES, ids=[os.path.basename(f) for f in FILES])
def test_the_specimen_is_what_its_header_says(path):
    stated = STATED[os.path.basename(path)]
    build = SpecimenTest.from_file(path).build
    size = np.array(build.n) * build.L0
    np.testing.assert_allclose(size, stated["size"], atol=1e-12, err_msg="the box")
    if "notch" in stated:
        depth, width, centre = stated["notch"]
        (x0, x1), (y0, y1), (z0, z1) = removed_extent(build)
        assert (z0, z1) == pytest.approx((0.0, depth)), "notch depth"
        assert (x1 - x0, (x0 + x1) / 2) == pytest.approx((width, centre)), "notch width and place"
        assert (y0, y1) == pytest.approx((0.0, size[1])), "the notch runs through the thickness"
    if "cutout" in stated:
        assert removed_extent(build) == [pytest.approx(r) for r in stated["cutout"]], "cutout"
        assert (~build.mask).sum() == np.prod([round((hi - lo) / build.L0) for lo, hi in stated["cutout"]])
    x = Nodes(build.n, build.L0, build.mask).x
    for name, where in stated["groups"].items():
        at = x[build.groups[name]]
        for axis, key in ((0, "x"), (2, "z")):
            span = (at[:, axis].min(), at[:, axis].max())
            assert span == pytest.approx(where[key], abs=1e-9), f"group {name}: {key} from {span[0]} to {span[1]}"
        assert (at[:, 1].min(), at[:, 1].max()) == pytest.approx((0.0, size[1])), f"group {name} across the thickness"
