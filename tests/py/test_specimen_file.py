"""Specimens beyond the cube (issue 13): shapes on the lattice, groups and their
loads, measures and probes, `ldem run FILE.toml` and the example gallery."""
import glob
import json
import os
import re
import subprocess
import tomllib

import numpy as np
import pytest

import ldem
from ldem import _core
from ldem.shapes import module_mask
from ldem.specimen import SpecimenError, SpecimenTest

from conftest import ROOT, picture, subprocess_env

EXAMPLES = sorted(glob.glob(os.path.join(ROOT, "examples", "*.toml")))
FAST = {"strain_rate": 0.1, "stop_at": "load_loss", "threads": 1}


def example(name: str) -> dict:
    with open(os.path.join(ROOT, "examples", name + ".toml"), "rb") as f:
        return tomllib.load(f)


@pytest.mark.parametrize("load", ["uniform", "triangular"])
def test_the_cube_files_are_ldem_cube(load):
    """examples/cube_*.toml is the study's cube: the same curve as ldem.CubeTest
    (the same run parameters: the triangular file stops at a mean strain of 0.005)."""
    settings = dict(FAST, final_strain=0.005)
    spec = SpecimenTest.from_file(os.path.join(ROOT, "examples", f"cube_{load}.toml"), settings).run()
    cube = ldem.CubeTest(size=0.12, load=load, **settings).run()
    assert spec.summary["n_bars"] == cube.summary["n_bars"] and spec.summary["steps"] == cube.summary["steps"]
    np.testing.assert_array_equal(spec.curve["stress_MPa"], cube.curve["stress_MPa"])
    np.testing.assert_allclose(spec.curve["mean_strain"], cube.curve["mean_strain"], rtol=1e-13)
    # The prescribed DOFs come in another order: the external work is summed in another order.
    np.testing.assert_allclose(spec.curve["external_work_J"], cube.curve["external_work_J"], rtol=1e-12, atol=1e-15)
    assert spec.summary["peak_stress_MPa"] == cube.summary["peak_stress_MPa"]
    assert spec.summary["min_fracture_energy_J"] == cube.summary["min_fracture_energy_J"]  # the file's ligament
    assert spec.summary["stop_reason"] == cube.summary["stop_reason"]
    assert (spec.summary["load_loss"] or {}).get("step") == (cube.summary["load_loss"] or {}).get("step")


def _bars(lattice):
    t = lattice.bar_table()
    x = np.column_stack([lattice.x0, lattice.y0, lattice.z0])
    return {k: t[k] for k in ("n1", "n2", "EA", "Af", "share")}, x


def test_a_full_mask_file_and_a_notch_of_depth_0_are_the_box(tmp_path):
    np.save(tmp_path / "m.npy", np.ones((3, 2, 4), bool))
    box = module_mask({"kind": "box", "L0": 0.02, "size": [0.06, 0.04, 0.08]})
    notch0 = module_mask({"kind": "box", "L0": 0.02, "size": [0.06, 0.04, 0.08], "notch": {"depth": 0.0}})
    from ldem.shapes import Where
    masked = module_mask({"kind": "mask", "L0": 0.02, "size": [0.06, 0.04, 0.08], "file": "m.npy"},
                         Where("", str(tmp_path / "s.toml")))
    for other in (notch0, masked):
        assert other[:2] == box[:2] and np.array_equal(other[2], box[2]) and box[2].all()
    m = _core.Material()
    full = _bars(_core.build_cubic_lattice(3, 2, 4, 0.02, m))
    clipped = _bars(_core.build_lattice(3, 2, 4, 0.02, m, box[2].transpose(2, 1, 0).ravel().astype(np.uint8)))
    for k in full[0]:
        np.testing.assert_array_equal(full[0][k], clipped[0][k])


def test_shapes_cut_what_they_say():
    L0 = 0.01
    _, n, notched = module_mask({"kind": "box", "L0": L0, "size": [0.35, 0.05, 0.10],
                                 "notch": {"depth": 0.05, "width": 0.01}})
    assert n == (35, 5, 10) and (~notched).sum() == 5 * 5 and not notched[17, :, :5].any() and notched[17, :, 5:].all()
    _, n, cyl = module_mask({"kind": "cylinder", "L0": L0, "diameter": 0.1, "length": 0.02, "axis": "y"})
    assert n == (10, 2, 10) and np.array_equal(cyl[:, 0], cyl[:, 1])
    # The discrete disc's area is within 3 % of pi D^2 / 4.
    assert cyl[:, 0].sum() * L0 ** 2 == pytest.approx(np.pi * 0.1 ** 2 / 4, rel=0.03)
    _, n, bone = module_mask({"kind": "dogbone", "L0": L0, "size": [0.1, 0.02, 0.15], "neck": 0.06,
                              "radius": 0.0725})
    width = bone[:, 0, :].sum(axis=0) * L0
    assert width[0] == width[-1] == pytest.approx(0.1) and width.min() == pytest.approx(0.06)
    assert np.array_equal(width, width[::-1]) and width[n[2] // 2] == width.min()  # narrowest at mid-height
    # An L-shaped panel: the lower-right quadrant of a 0.1 m square cut out, exactly its 5 x 5 modules.
    _, n, ell = module_mask({"kind": "box", "L0": L0, "size": [0.1, 0.02, 0.1],
                             "cutout": {"min": [0.05, 0.0, 0.0], "max": [0.1, 0.02, 0.05]}})
    assert n == (10, 2, 10) and (~ell).sum() == 5 * 2 * 5
    assert not ell[5:, :, :5].any() and ell[:5].all() and ell[:, :, 5:].all()


@pytest.mark.parametrize("cutout, message", [
    ([0.0, 0.0], "must be a table"),
    ({"min": [0.05, 0.0, 0.0]}, "shape.cutout.max"),
    ({"min": [0.05, 0.0, 0.0], "max": [0.01, 0.02, 0.05]}, "must be above min"),
    ({"min": [0.05, 0.0, 0.0], "max": [0.1, 0.02, 0.05], "depth": 1}, "depth"),
])
def test_a_bad_cutout_is_a_clear_error(cutout, message):
    with pytest.raises(SpecimenError, match=message):
        module_mask({"kind": "box", "L0": 0.01, "size": [0.1, 0.02, 0.1], "cutout": cutout})


def test_a_line_is_two_coordinates():
    """line = {x, z}: the nodes of the beam's support line, as face z- and plane x together."""
    data = example("beam_3pb")
    as_line = dict(data["groups"]["left"], line={"x": 0.05, "z": 0.0})
    del as_line["face"], as_line["plane"]
    a = SpecimenTest.of(**data).build.groups["left"]
    b = SpecimenTest.of(**dict(data, groups=dict(data["groups"], left=as_line))).build.groups["left"]
    assert len(a) == 6 and np.array_equal(a, b)  # 6 nodes across the thickness of 5 modules
    with pytest.raises(SpecimenError, match=r"groups.left.line: must be 2 coordinate\(s\)"):
        SpecimenTest.of(**dict(data, groups=dict(data["groups"], left={"line": {"x": 0.05}, "fix": ["z"]})))


def _column(shape: dict) -> dict:
    """A column 0.12 m high on a roller base (z held, pinned at two points)
    squeezed by a platen driven down, free laterally: uniaxial compression,
    stopped below eps_p (no damage)."""
    return {
        "title": "column in compression", "shape": shape,
        "groups": {"base": {"face": "z-", "fix": ["z"]},
                   "pin": {"point": [0.06, 0.06, 0.0], "fix": ["x", "y"]},
                   "guide": {"point": [0.10, 0.06, 0.0], "fix": ["y"]},
                   "platen": {"face": "z+", "drive": {"z": -1.0}}},
        "measure": {"support": "base", "loaded": "platen", "area": 1.0, "gauge_length": 0.12},
        "run": {"final_strain": 4e-5, "threads": 1}}


def _modulus(test) -> float:
    """E_app / E: the slope of the second half of the curve (past the smooth
    start), the force over the column's own section (its present modules)."""
    result = test.run()
    assert result.curve["damaged_bars"][-1] == 0
    section = test.build.mask[:, :, 0].sum() * test.build.L0 ** 2
    e, s = result.curve["mean_strain"], result.curve["stress_MPa"] * 1e6 / section  # area 1: the force
    k = len(e) // 2
    return np.polyfit(e[k:], s[k:], 1)[0] / _core.Material().E, result


def test_a_clipped_cylinder_has_the_modulus_of_the_box():
    """A 6-module box has E_app = 0.86998 E (the static solve of test_elastic.cpp:
    the lattice's surface layer is softer); the cylinder cut from it (32 of 36
    modules a layer) the same within 1 %: clipping keeps the material's stiffness.
    Measured: box 0.87000, cylinder 0.86813 (-0.2 %)."""
    box, _ = _modulus(SpecimenTest(_column({"kind": "box", "L0": 0.02, "size": [0.12, 0.12, 0.12]})))
    cyl, result = _modulus(SpecimenTest(_column({"kind": "cylinder", "L0": 0.02, "diameter": 0.12,
                                                 "length": 0.12, "axis": "z"})))
    assert box == pytest.approx(0.8699782209635861, rel=2e-3)
    assert cyl == pytest.approx(box, rel=0.01)
    # The base is a roller: free along its plane (it widens), held across it;
    # the platen moves as one and widens too.
    sim, u = result.sim, result.sim.displacement
    base, platen = sim.group("base"), sim.group("platen")
    strain = result.curve["mean_strain"][-1]
    assert np.all(u[base, 2] == 0) and np.abs(u[base, :2]).max() > 0.05 * strain * 0.06
    assert np.all(u[platen, 2] == u[platen[0], 2]) and u[platen[0], 2] == pytest.approx(-strain * 0.12, rel=1e-12)
    assert np.abs(u[platen, :2]).max() > 0.05 * strain * 0.06


def test_the_beam_measures_a_crack_mouth_opening():
    test = SpecimenTest.from_file(os.path.join(ROOT, "examples", "beam_3pb.toml"),
                                  {"threads": 1, "final_strain": 1.5e-3})
    result = test.run()
    cmod, strain = result.curve["cmod_m"], result.curve["mean_strain"]
    peak = result.summary["strain_at_peak"]
    assert 0 < peak < 1.5e-3 and result.summary["peak_stress_MPa"] > 0
    # Positive (the notch opens), and it grows faster than the deflection once the crack runs.
    assert cmod[-1] > 0 and cmod[-1] == cmod.max()
    assert cmod[-1] / strain[-1] > 1.5 * np.interp(peak, strain, cmod) / peak  # measured 1.9x


def _file(tmp_path, text, base="cube_uniform"):
    """examples/cube_uniform.toml with its text changed."""
    src = open(os.path.join(ROOT, "examples", base + ".toml")).read()
    path = tmp_path / "bad.toml"
    path.write_text(text(src))
    return str(path)


@pytest.mark.parametrize("change, key", [
    (lambda s: "colour = 1\n" + s, "1: colour: unknown key"),
    (lambda s: s.replace('kind = "box"', 'kind = "sphere"'), "shape.kind: must be one of"),
    (lambda s: s.replace("size = [0.12, 0.12, 0.12]", "size = [0.12, 0.12, 0.13]"), "shape.size: 0.13 m is not a multiple"),
    (lambda s: s.replace("L0 = 0.02", "L0 = 0.02\nholes = 2"), "shape.holes: unknown key"),
    (lambda s: s.replace('face = "z+"', 'face = "top"'), "groups.top.face: must be one of"),
    (lambda s: s.replace('drive = {z = 1.0}', 'drive = {w = 1.0}'), "groups.top.drive: must be a table"),
    (lambda s: s.replace("[measure]", '[groups.side]\nplane = {x = 0.0}\nfix = ["z"]\n\n[measure]'),
     "groups.side: node at [0.0, 0.0, 0.0] direction z is also prescribed by group 'bottom'"),
    (lambda s: s.replace('loaded = "top"', 'loaded = "bottom"'), "measure.loaded: group 'bottom' must be driven"),
    (lambda s: s.replace('support = "bottom"', 'support = "base"'), "measure.support: must name a group"),
    (lambda s: s.replace('support = "bottom"', 'support = "all"').replace(
        "[measure]", "[groups.all]\nbox = {min = [0, 0, 0], max = [0.12, 0.12, 0.12]}\n\n[measure]"),
     "measure.loaded: groups 'all' and 'top' share nodes"),
    (lambda s: s + "\n[material]\nnu = 0.7\n", "material.nu: nu must be in"),
    (lambda s: s.replace("[loading]\n", "[loading]\nload = 'triangular'\n"), "loading.load: a cube-test parameter"),
    (lambda s: s + "\n[run]\nseed = 'one'\n", "run.seed: must be int"),
    (lambda s: s.replace("area = 0.0144", "area = -1"), "measure.area: must be positive"),
    (lambda s: s.replace("area = 0.0144", "area = 0.0144\nstress_label = 2"), "measure.stress_label: must be a text"),
    (lambda s: s.replace("[measure]", "[measure\n"), "not valid TOML"),
])
def test_a_bad_file_is_one_line_naming_the_key_and_exit_2(cli, tmp_path, change, key):
    path = _file(tmp_path, change)
    r = cli("run", path, "--out", str(tmp_path / "out"), "--no-progress")
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and key in lines[0] and lines[0].startswith(f"ldem run: error: {path}"), r.stderr
    assert not os.path.exists(tmp_path / "out" / "summary.json")


BEAM_NOTCH = "notch = {depth = 0.02, width = 0.01}"
BEAM_LOAD_BOX = "box = {min = [0.17, 0.0, 0.10], max = [0.18, 0.05, 0.10]}"


@pytest.mark.parametrize("old, new, key, message", [
    (BEAM_NOTCH, BEAM_NOTCH + "\ncutout = {min = [1.0, 1.0, 1.0], max = [2.0, 2.0, 2.0]}", "shape.cutout.min",
     "must lie inside or on the specimen's box, [0, 0.35] x [0, 0.05] x [0, 0.1] m (got [1, 1, 1])"),
    (BEAM_NOTCH, BEAM_NOTCH + "\ncutout = {min = [0.3, 0.0, 0.0], max = [0.4, 0.05, 0.05]}", "shape.cutout.max",
     "must lie inside or on the specimen's box, [0, 0.35] x [0, 0.05] x [0, 0.1] m (got [0.4, 0.05, 0.05])"),
    (BEAM_NOTCH, "notch = {depth = 0.02, width = 0.01, at = 5.0}", "shape.notch.at",
     "the slot, x from 4.995 to 5.005 m, must lie inside or on the specimen's box, x in [0, 0.35] m (got at = 5)"),
    (BEAM_NOTCH, "notch = {depth = 0.02, width = 0.02, at = 0.0}", "shape.notch.at",
     "the slot, x from -0.01 to 0.01 m, must lie inside or on the specimen's box, x in [0, 0.35] m (got at = 0)"),
    ("plane = {x = 0.05}", "plane = {x = 0.5}", "groups.left.plane",
     "must lie inside or on the specimen's box, x in [0, 0.35] m (got 0.5)"),
    ("plane = {x = 0.05}", "box = {min = [0.05, -0.05, 0.0], max = [0.05, 0.10, 0.0]}", "groups.left.box",
     "must lie inside or on the specimen's box, [0, 0.35] x [0, 0.05] x [0, 0.1] m (got [0.05, -0.05, 0])"),
    (BEAM_LOAD_BOX, "box = {min = [0.17, 0.0, 0.10], max = [0.18, 0.05, 0.15]}", "groups.load.box",  # the platen
     "must lie inside or on the specimen's box, [0, 0.35] x [0, 0.05] x [0, 0.1] m (got [0.18, 0.05, 0.15])"),
    (BEAM_LOAD_BOX, "point = [0.175, 0.025, 0.105]", "groups.load.point",
     "must lie inside or on the specimen's box, [0, 0.35] x [0, 0.05] x [0, 0.1] m (got [0.175, 0.025, 0.105])"),
    ("a = [0.17, 0.0, 0.0]", "a = [0.17, 0.0, -0.005]", "measure.probes.cmod.a",
     "must lie inside or on the specimen's box, [0, 0.35] x [0, 0.05] x [0, 0.1] m (got [0.17, 0, -0.005])"),
])
def test_geometry_beyond_the_specimen_s_box_is_refused_at_its_line(cli, tmp_path, old, new, key, message):
    """A cutout, notch, group (a platen too) or probe out of the box cut or selected nothing of what it said, or
    less (a box partly out took the nodes on the face, a point within L0 of one the nearest), and ran without a
    word: each is refused before the lattice is built, at its key and line."""
    text = open(os.path.join(ROOT, "examples", "beam_3pb.toml")).read()
    assert text.count(old) == 1
    path = tmp_path / "beam.toml"
    path.write_text(text.replace(old, new))
    r = cli("run", str(path), "--out", str(tmp_path / "out"), "--no-progress")
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
    line = int(re.match(rf"ldem run: error: {re.escape(str(path))}:(\d+): ", lines[0]).group(1))
    assert lines[0] == f"ldem run: error: {path}:{line}: {key}: {message}"
    assert new.splitlines()[-1] in path.read_text().splitlines()[line - 1]  # the line of the key named
    assert not os.path.exists(tmp_path / "out")


def test_geometry_on_the_box_s_faces_is_inside():
    """On the faces is inside: a cutout to them, a notch at an end, a platen over the whole upper face."""
    data = example("beam_3pb")
    shape = dict(data["shape"], notch={"depth": 0.02, "width": 0.02, "at": 0.34},
                 cutout={"min": [0.3, 0.0, 0.05], "max": [0.35, 0.05, 0.1]})
    groups = dict(data["groups"], load={"box": {"min": [0.0, 0.0, 0.1], "max": [0.35, 0.05, 0.1]},
                                        "drive": {"z": -1.0}})
    test = SpecimenTest.of(**dict(data, shape=shape, groups=groups))
    assert (~test.build.mask).sum() == 5 * 5 * 5 + 2 * 2 * 5  # the cutout's 5 x 5 x 5 modules, the slot's 2 x 2 (x 5)
    assert len(test.build.groups["load"]) == 36 * 6 - 5 * 6  # the upper face's nodes, less the cutout's corner


def test_keyword_arguments_build_what_the_file_builds():
    data = example("beam_3pb")
    a, b = SpecimenTest.from_file(os.path.join(ROOT, "examples", "beam_3pb.toml")), SpecimenTest.of(**data)
    for x, y in zip(a.build.prescribed, b.build.prescribed):
        np.testing.assert_array_equal(x, y)
    assert a.build.measures == b.build.measures and a.build.params == b.build.params
    assert all(np.array_equal(a.build.groups[k], b.build.groups[k]) for k in data["groups"])
    with pytest.raises(SpecimenError, match="^colour: unknown key"):
        SpecimenTest.of(colour=1, **data)


@pytest.mark.direct
def test_a_files_default_rate_strains_eps_p_in_twelve_of_its_own_periods():
    """The rate a file without one is driven at, set up (no step run):
    strain_rate = eps_p omega_d / (2 pi 12), from the drive's own frequency omega_d."""
    test = SpecimenTest(example("dogbone"), overrides={"threads": 1})
    sim = test.simulation()
    eps_p = test.build.params["eps_p"]
    assert sim.strain_rate == pytest.approx(eps_p * sim.omega_d / (2 * np.pi * 12), rel=1e-12)


def test_a_file_without_a_rate_is_driven_from_its_own_period():
    """Rule (c) is a file's default rate (specimenOwnDefaults, kSpecimenRatePeriods in
    dynamics/QuasiStatic.hpp): eps_p in 12 of the specimen's own periods. A strain_rate
    the file gives is the rate driven; --set's is over the file's."""
    d = example("dogbone")
    assert "strain_rate" not in d.get("loading", {}) and "rate_periods" not in d.get("loading", {})
    assert SpecimenTest(d).build.params["rate_periods"] == _core.specimen_own_defaults()["rate_periods"] == 12
    given = SpecimenTest(dict(d, loading={"strain_rate": 0.05})).build.params
    assert given["rate_periods"] == 0 and given["strain_rate"] == 0.05
    assert SpecimenTest(dict(d, loading={"strain_rate": 0.05, "rate_periods": 6})).build.params["rate_periods"] == 6
    over = SpecimenTest(dict(d, loading={"rate_periods": 6}), overrides={"strain_rate": 0.05}).build.params
    assert over["rate_periods"] == 0 and over["strain_rate"] == 0.05
    back = SpecimenTest(dict(d, loading={"strain_rate": 0.05}), overrides={"rate_periods": 3}).build.params
    assert back["rate_periods"] == 3  # --set's rule (c) over the file's strain_rate (it was lost)
    s = SpecimenTest(d, overrides={"final_strain": 5e-5, "threads": 1}).run().summary
    assert s["quasi_static"]["periods_to_eps_p"] == pytest.approx(12, rel=1e-12)
    assert s["quasi_static"]["strain_rate"] == pytest.approx(s["parameters"]["parameters"]["eps_p"] * s["omega_d_rad_s"] / (24 * np.pi), rel=1e-12)


def test_the_line_named_is_the_key_s_line(tmp_path):
    path = _file(tmp_path, lambda s: s.replace('face = "z+"', 'face = "top"'))
    with pytest.raises(SpecimenError) as e:
        SpecimenTest.from_file(path)
    line = int(str(e.value).split(":")[1])
    assert 'face = "top"' in open(path).read().splitlines()[line - 1]


def test_a_missing_file_is_one_line(cli, tmp_path):
    r = cli("run", str(tmp_path / "none.toml"))
    assert r.returncode == 2 and "none.toml: No such file" in r.stderr and len(r.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: os.path.basename(p))
def test_each_example_runs(cli, tmp_path, path):
    """Every gallery file runs (a short stretch of it: the suite's minutes)."""
    out = tmp_path / "out"
    r = cli("run", path, "--out", str(out), "--no-progress", "--set", "final_strain=1e-4", "--set", "threads=1")
    assert r.returncode == 0, r.stderr
    s = json.load(open(out / "summary.json"))
    assert s["status"] == "done" and s["peak_stress_MPa"] > 0 and s["energy_balance_error"] < 0.01
    assert s["parameters"]["description"]["title"] in open(path).read()
    declared = s["parameters"]["description"]["measure"].get("ligament")  # U_min = E[G_f] x ligament, or none
    gf = s["parameters"]["parameters"]["Gf_mean"]
    assert s["min_fracture_energy_J"] == (None if declared is None else pytest.approx(gf * declared, rel=1e-15))
    assert os.path.getsize(out / "cracks.png") > 0 and os.path.getsize(out / "bars.pvd") > 0


def test_the_gallery_pictures_are_the_examples_and_its_command_draws_them(tmp_path):
    """README's and docs/specimens.md's pictures docs/gallery/NAME.png are the
    pictures of examples/NAME.toml, and the command docs/specimens.md names for
    them (/usr/bin/python3 scripts/gallery.py) writes one: here on a short stretch."""
    shown = set()
    for page in ("README.md", os.path.join("docs", "specimens.md")):
        shown |= set(re.findall(r"!\[[^]]*\]\((?:docs/)?gallery/(\w+)\.png\)", open(os.path.join(ROOT, page)).read()))
    names = {os.path.splitext(os.path.basename(p))[0] for p in EXAMPLES}
    committed = {os.path.splitext(p)[0] for p in os.listdir(os.path.join(ROOT, "docs", "gallery"))}
    assert {"beam_3pb", "cube_triangular"} <= shown <= names and shown <= committed
    r = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", "gallery.py"), "--only", "cube_uniform",
                        "--runs", str(tmp_path / "runs"), "--out", str(tmp_path / "gallery"),
                        "--set", "final_strain=1e-4"], capture_output=True, text=True, timeout=300, env=subprocess_env())
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("cube_uniform: peak ") and os.listdir(tmp_path / "gallery") == ["cube_uniform.png"]
    drawn = picture(tmp_path / "gallery" / "cube_uniform.png")
    curve, cracks = (picture(tmp_path / "runs" / "cube_uniform" / n) for n in ("curve.png", "cracks.png"))
    assert drawn.shape[1] == pytest.approx(curve.shape[1] + cracks.shape[1], rel=0.02)  # side by side, at their scale


def test_a_specimen_runs_bit_for_bit_on_any_thread_count():
    """Every specimen goes through the cube's time-step loop: one thread or two,
    the same curve to the last bit (the small notched beam, past its peak)."""
    path = os.path.join(ROOT, "tests", "data", "beam_small.toml")
    one, two = (SpecimenTest.from_file(path, {"threads": t, "final_strain": 6e-4, "strain_rate": 1.0}).run()
                for t in (1, 2))
    assert one.curve["broken_bars"][-1] > 10
    for column in one.curve:
        np.testing.assert_array_equal(one.curve[column], two.curve[column], err_msg=column)


def test_an_observer_that_returns_false_stops_the_run():
    test = SpecimenTest.from_file(os.path.join(ROOT, "examples", "cube_uniform.toml"), FAST)
    seen = []
    result = test.run(observers=[seen.append, lambda row: row["mean_strain"] < 1e-4])
    assert result.summary["stop_reason"] == "stopped"
    strain = result.curve["mean_strain"]
    assert strain[-1] >= 1e-4 > strain[-2] and len(seen) == len(strain)  # every observer saw the last row


@pytest.mark.parametrize("servo", [False, True], ids=["displacement", "cmod_control"])
def test_ldem_run_restarts_bit_for_bit(cli, tmp_path, servo):
    """ldem run --checkpoint-every, stopped (SIGTERM's way: an interrupt after the
    second checkpoint), then --restart: the same curve.csv as a run that never
    stopped; under CMOD control too (the servo's state is in checkpoint.npz)."""
    path = os.path.join(ROOT, "tests", "data", "beam_small.toml")
    if servo:
        text = open(path).read().replace("[loading]\n", "[loading]\nopening_rate = 0.02\n")
        path = str(tmp_path / "servo.toml")
        open(path, "w").write(text.replace("[measure]\n", '[measure]\ncontrol = "cmod"\n'))
    common = ["--no-progress", "--no-plots", "--set", "threads=1", "--set", "final_strain=6e-4", "--set",
              "strain_rate=1.0"]
    r = cli("run", path, "--out", str(tmp_path / "whole"), *common)
    assert r.returncode == 0, r.stderr
    test = SpecimenTest.from_file(path, {"threads": 1, "final_strain": 6e-4, "strain_rate": 1.0})
    seen = []

    def interrupt(row):
        seen.append(row)
        if len(seen) == 2 * 40 + 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        ldem.run_cube(test, out=str(tmp_path / "cut"), progress=False, plots=False, checkpoint_every=40,
                      observers=[interrupt])
    r = cli("run", os.path.join(ROOT, "examples", "cube_uniform.toml"), "--out", str(tmp_path / "cut"), "--restart",
            *common)
    assert r.returncode == 2 and "other parameters" in r.stderr
    r = cli("run", path, "--out", str(tmp_path / "cut"), "--restart", *common)
    assert r.returncode == 0, r.stderr
    whole, again = ((tmp_path / d / "curve.csv").read_text() for d in ("whole", "cut"))
    assert again == whole and len(whole.splitlines()) > 2 * 40 + 3
    assert "cmod_m" in whole.splitlines()[0]
