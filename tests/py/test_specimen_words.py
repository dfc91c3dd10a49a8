"""Issue 40, item 5: a specimen speaks its own words. A beam's terminal lines,
summary.json and crack picture say deflection/D and F/(bD) (its measure's
labels), never mean strain; U_min is E[G_f] x its ligament, b (D - a0); `ldem
rerun` reruns an `ldem run` output; a bad --set names the option, not a line
of the file."""
import json
import os
import tomllib

import numpy as np
import pytest

import ldem
from conftest import ROOT
from ldem.specimen import SpecimenTest

BEAM = os.path.join(ROOT, "tests", "data", "beam_small.toml")
SHORT = ["--set", "threads=1", "--set", "final_strain=6e-4", "--set", "strain_rate=1.0", "--no-progress"]


def _labelled_beam(tmp_path) -> str:
    """beam_small.toml with a beam's axis labels (examples/beam_3pb.toml's)."""
    path = tmp_path / "beam.toml"
    path.write_text(open(BEAM).read().replace(
        "[measure]\n", '[measure]\nstress_label = "F/(bD) [MPa]"\nstrain_label = "deflection/D [-]"\n'))
    return str(path)


def _ligament_of_shape(path: str) -> float:
    """b (D - a0) from the file's shape: thickness, depth, notch depth."""
    with open(path, "rb") as f:
        shape = tomllib.load(f)["shape"]
    _, b, depth = shape["size"]
    return b * (depth - shape["notch"]["depth"])


def test_a_beam_speaks_of_its_deflection_and_its_load(cli, tmp_path):
    out = tmp_path / "out"
    r = cli("run", _labelled_beam(tmp_path), "--out", str(out), "--no-plots", *SHORT)
    assert r.returncode == 0, r.stderr
    s = json.loads((out / "summary.json").read_text())
    assert s["labels"] == {"strain": "deflection/D [-]", "stress": "F/(bD) [MPa]"}
    assert "mean strain" not in r.stdout and "stress" not in r.stdout, r.stdout
    assert f"peak F/(bD) {s['peak_stress_MPa']:.4f} MPa at deflection/D {s['strain_at_peak']:.4e}\n" in r.stdout
    u_min = s["min_fracture_energy_J"]
    assert s["stop_reason"] == "final_strain" and not s["separated"]
    assert "stopped at the final strain (deflection/D 6.0" in r.stdout
    assert f"the fracture energy at the end, {s['fracture_energy_J']:.4g} J " \
           f"({s['fracture_energy_J'] / u_min:.3f} U_min)" in r.stdout


def test_the_crack_picture_is_titled_in_the_beam_s_words(tmp_path, monkeypatch):
    from ldem import plots

    titles = []
    monkeypatch.setattr(plots, "crack_figure_from_slice", lambda *a, title="", **k: titles.append(title))
    test = SpecimenTest.from_file(_labelled_beam(tmp_path), {"threads": 1, "final_strain": 2e-5})
    result = ldem.run_cube(test, out=str(tmp_path / "out"), progress=False)
    assert titles == [f"small notched beam, seed 1\ndeflection/D {result.curve['mean_strain'][-1]:.2e}"]


@pytest.mark.parametrize("path", [BEAM, os.path.join(ROOT, "examples", "beam_3pb.toml"),
                                  os.path.join(ROOT, "examples", "eccentric_notch_beam.toml")],
                         ids=os.path.basename)
def test_a_beam_s_ligament_is_its_section_above_the_notch(path):
    """measure.ligament is b (D - a0), and the smallest section of the
    specimen's modules across its span (the notch's), so U_min = E[G_f] b (D - a0)."""
    test = SpecimenTest.from_file(path)
    b = test.build
    ligament = b.measures["ligament"]
    assert ligament == pytest.approx(_ligament_of_shape(path), rel=1e-12)
    sections = b.mask.sum(axis=(1, 2)) * b.L0 ** 2  # the mask is [x, y, z]
    assert ligament == pytest.approx(sections.min(), rel=1e-12) and sections.max() > ligament
    sim = test.simulation()
    assert sim.min_fracture_energy == pytest.approx(b.params["Gf_mean"] * _ligament_of_shape(path), rel=1e-12)


def test_u_min_of_a_beam_run_and_of_a_specimen_without_a_ligament(tmp_path):
    beam = SpecimenTest.from_file(BEAM, {"threads": 1, "final_strain": 2e-5}).run().summary
    assert beam["min_fracture_energy_J"] == pytest.approx(100.0 * 0.04 * (0.08 - 0.02), rel=1e-12)
    assert beam["min_fracture_energy_J"] < 100.0 * beam["parameters"]["description"]["measure"]["area"]  # not b D
    path = tmp_path / "none.toml"
    path.write_text(open(BEAM).read().replace("ligament = 0.0024\n", ""))
    none = SpecimenTest.from_file(str(path), {"threads": 1, "final_strain": 2e-5}).run().summary
    assert none["min_fracture_energy_J"] is None and none["U_ratio"] is None


def test_ldem_rerun_reruns_an_ldem_run_output(cli, tmp_path):
    out = tmp_path / "beam"
    r = cli("run", BEAM, "--out", str(out), "--no-plots", *SHORT, "--set", "seed=3")
    assert r.returncode == 0, r.stderr
    r = cli("rerun", str(out), "--no-progress")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "identical: the curve and every other field of the summary" in r.stdout
    again = json.loads((out / "rerun" / "summary.json").read_text())
    assert again["parameters"]["parameters"]["seed"] == 3 and "cmod_m" in (out / "rerun" / "curve.csv").read_text()


def test_a_rerun_drives_at_the_rate_its_run_had():
    """A run of a file without a rate, from before a file's own default (rule (c) at 12 periods),
    ran at the table's strain_rate: ldem rerun asks for that rate again, whether the run's
    parameters say rate_periods 0 or, older still, nothing of it (the table's default then)."""
    from ldem.cube import TABLE_DEFAULTS
    from ldem.rerun import rerun_test_of
    with open(os.path.join(ROOT, "examples", "dogbone.toml"), "rb") as f:
        d = tomllib.load(f)
    now = SpecimenTest(d).build.params
    assert TABLE_DEFAULTS["rate_periods"] == 0 and now["rate_periods"] == 12
    for params in (dict(now, rate_periods=0.0), {k: v for k, v in now.items() if k != "rate_periods"}):
        test = rerun_test_of({"parameters": {"description": d, "parameters": params}}, "summary.json")
        assert test.build.params["rate_periods"] == 0 and test.build.params["strain_rate"] == 0.02


@pytest.mark.parametrize("pair,message", [("eps_p=1e9", "--set eps_p: eps_p must be in (0, 0.01] (got 1e+09)"),
                                          ("zeta=nan", "--set zeta: zeta must be in [0, 10] (got nan)")])
def test_a_bad_set_names_the_option_not_a_line_of_the_file(cli, tmp_path, pair, message):
    r = cli("run", BEAM, "--set", pair, "--out", str(tmp_path / "o"))
    assert r.returncode == 2 and r.stderr == f"ldem run: error: {message}\n", r.stderr
    # The same value in the file is the file's, by its line.
    name, value = pair.split("=")
    group = next(p["group"] for p in ldem.cube.PARAMETERS if p["name"] == name)
    text = open(BEAM).read()
    path = tmp_path / "f.toml"
    path.write_text(text + f"[{group}]\n{name} = {value}\n")
    r = cli("run", str(path), "--out", str(tmp_path / "o"))
    line = len(text.splitlines()) + 2
    assert r.returncode == 2 and f"f.toml:{line}: {group}.{name}: {message.split(': ', 1)[1]}" in r.stderr, r.stderr


def test_the_cube_s_words_are_mean_strain_and_normal_stress():
    assert ldem.cube.labels(ldem.CubeTest()) == {"strain": "mean strain [-]", "stress": "normal stress [MPa]"}
    assert ldem.cube.label_words("F/(bD) [MPa]") == ("F/(bD)", "MPa")
    assert ldem.cube.label_words("load F") == ("load F", "")
    assert np.isclose(ldem.CubeTest(size=0.04).simulation().min_fracture_energy, 100.0 * 0.04 ** 2, rtol=1e-15)
