"""The dynamic parts' registry (pkg/ldem/dynamics/Registry.hpp, exported as
ldem._core.dynamic_parts): each registered part's line gives its name (a
choice of tail_drive or stop_at), its parameters and their defaults as
`ldem cube --help` shows them; a drive, a damping and a stop rule each run
chosen by name on a tiny cube."""
import math

import pytest

import ldem
from ldem import _core
from conftest import run_cli

TABLE = {p["name"]: p for p in _core.parameter_table()}
PARTS = list(_core.dynamic_parts)
CHOICE_OF = {"drive": "tail_drive", "stop": "stop_at"}


@pytest.fixture(scope="module")
def cube_help():
    r = run_cli("cube", "--help")
    assert r.returncode == 0, r.stderr
    return " ".join(r.stdout.split())  # as argparse wraps it to the terminal's width


def test_the_registry_holds_every_family_with_unique_names():
    families = {}
    for part in PARTS:
        families.setdefault(part["family"], []).append(part["name"])
    assert set(families) == {"drive", "damping", "stop"}
    for names in families.values():
        assert len(names) == len(set(names)), names
    assert "constant_velocity" in families["drive"]


@pytest.mark.parametrize("part", PARTS, ids=[f"{p['family']}-{p['name']}" for p in PARTS])
def test_each_part_line_gives_its_name_parameters_and_defaults_as_help_shows_them(part, cube_help):
    choice = CHOICE_OF.get(part["family"])
    if choice and part["choice"]:
        assert part["name"] in TABLE[choice]["choices"]
        assert f"{part['name']} ({part['doc']})" in " ".join(TABLE[choice]["help"].split())
        assert part["name"] in cube_help
    elif choice:
        assert part["name"] not in TABLE[choice]["choices"]
    for name in part["parameters"]:
        row = TABLE[name]
        assert row["group"] == ("loading" if part["family"] == "drive" else "run"), name
        option = "--" + name.replace("_", "-")
        assert option in cube_help, option
        # Its default as --help says it (the cube's own default where it has one: crack_pace, ...),
        # where it says one: never a default equal to 0 (ldem.helptext.HelpFormatter).
        default = _core.cube_own_defaults().get(name, row["default"])
        assert (f"(default: {default})" in cube_help) == (default != 0), (name, default)
        if row["unit"]:
            assert f"[{row['unit']}]" in cube_help


def test_a_drive_a_damping_and_a_stop_run_chosen_by_name_on_a_tiny_cube():
    """tail_drive constant_velocity moves the loaded face at drive_velocity; tail_damping
    relative (the relative tail of the mass damping) and stop_at past_peak are chosen by name."""
    v = 0.004  # [m/s]
    test = ldem.CubeTest(size=0.04, tail_drive="constant_velocity", drive_velocity=v, tail_damping="relative",
                         stop_at="past_peak", peak_stop_strain_ratio=3, threads=1)
    sim = test.simulation()
    assert sim.part_names[0] == "drive_constant_velocity"
    assert "stop_past_peak" in sim.part_names and "stop_load_loss" not in sim.part_names
    t = 5 * sim.ramp_time  # past the smooth start: U = v (t - t_r / 2)
    assert math.isclose(sim.drive_displacement(t), v * (t - sim.ramp_time / 2), rel_tol=1e-12)
    assert math.isclose(sim.strain_rate, v / sim.gauge_length, rel_tol=1e-15)
    result = test.run()
    s = result.summary
    assert s["stop_reason"] == "past_peak"
    assert s["quasi_static"]["strain_rate"] == pytest.approx(v / 0.04, rel=1e-12)
    # Never sped up: the mean strain at the end is v t / H past the ramp, whatever the load did.
    strain, time = result.curve["mean_strain"][-1], result.curve["time_s"][-1]
    assert strain == pytest.approx(v * (time - sim.ramp_time / 2) / 0.04, rel=1e-9)


@pytest.mark.parametrize("drive", [p["name"] for p in PARTS if p["family"] == "drive" and p["choice"]])
def test_the_report_says_what_each_drive_does_once_the_load_is_lost(drive):
    from ldem.markdown import load_loss_words
    p = {name: row["default"] for name, row in TABLE.items()} | {"tail_drive": drive, "loss_speedup": 20}
    words = load_loss_words([p])
    if drive == "constant_velocity":
        assert "speeds up" not in words and f"{p['drive_velocity']:g} m/s" in words, words
    else:
        assert "speeds up 20 times" in words, words
    assert ("adaptively" in words) == (drive == "adaptive"), words
