"""The dynamic parts' registry (pkg/ldem/dynamics/Registry.hpp, exported as
ldem._core.dynamic_parts): each registered part's line gives its name (a
choice of tail_drive or stop_at, or one of the dampings), its parameters and
their defaults as `ldem cube --help` shows them; a drive, a damping and a stop
rule each run chosen by name on a tiny cube, and each part chosen restarts
from a checkpoint on the bits of a run that never stopped."""
import math

import numpy as np
import pytest

import ldem
from ldem import _core
from conftest import run_cli

TABLE = {p["name"]: p for p in _core.parameter_table()}
PARTS = list(_core.dynamic_parts)
CHOICE_OF = {"drive": "tail_drive", "stop": "stop_at", "damping": "dampings"}


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
    assert families["damping"] == ["mass", "bar_dashpots"]


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


def test_help_shows_the_dampings_their_choices_and_the_default_of_every_one(cube_help):
    """dampings is some of the registered dampings: --help says each with its doc, the
    set it may be and its default, every damping registered (what runs did before)."""
    row = TABLE["dampings"]
    assert row["kind"] == "names" and row["choices"] == ["mass", "bar_dashpots"]
    assert row["default"] == "mass,bar_dashpots"
    assert "--dampings DAMPINGS" in cube_help
    assert ("; some of mass, bar_dashpots, separated by commas, or none (default: mass,bar_dashpots)"
            in cube_help)


def _tiny(**kw):
    """A 0.04 m cube pulled fast past its load loss (at mean strain 2e-3, 10 times that at the peak), on
    one thread, without the dashpots' share of the time step (dt_safety 0.4: the same step with them or not)."""
    return ldem.CubeTest(size=0.04, strain_rate=0.5, final_strain=3e-3, dt_safety=0.4, threads=1, **kw)


def test_a_damping_not_named_is_not_built_nor_felt():
    """dampings mass alone runs as the bar dashpots at zeta_high 0, and bar_dashpots alone
    as the mass damping at zeta 0, bit for bit: the one not named is not there (its state
    not in a checkpoint, its parameter not read)."""
    def run(**kw):
        test = _tiny(**kw)
        sim = test.simulation()
        return sim, test.run(simulation=sim)
    for named, zeroed, present, absent in [("mass", {"zeta_high": 0.0}, "damping_mass", "damping_bar_dashpots"),
                                           ("bar_dashpots", {"zeta": 0.0}, "damping_bar_dashpots", "damping_mass")]:
        sim, alone = run(dampings=named)
        assert present in sim.part_names and absent not in sim.part_names
        _, zero = run(**zeroed)
        assert alone.summary["load_loss"], alone.summary
        for column in ldem.CURVE_COLUMNS:
            assert np.array_equal(alone.curve[column], zero.curve[column]), (named, column)
    sim, none = run(dampings="none")
    assert not [n for n in sim.part_names if n.startswith("damping_")]
    assert sim.damping_coefficient == 0 and not none.curve["damping_J"].any()


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


# Every part chosen by name (the servo is the drive of a specimen with a controlled
# probe, no choice), the mass damping's relative tail, and no damping at all.
CHOSEN = [(CHOICE_OF[p["family"]], p["name"]) for p in PARTS if p["choice"]] + \
    [("tail_damping", "relative"), ("dampings", "none")]
ROLE = {choice: family for family, choice in CHOICE_OF.items()}


@pytest.mark.parametrize("name,value", CHOSEN, ids=[f"{n}-{v}" for n, v in CHOSEN])
def test_every_part_chosen_restarts_from_a_checkpoint_on_the_same_bits(name, value):
    """A checkpoint taken at a record past the load loss (or, where the run stops at
    it or before, three quarters of the way), restored into a new specimen, goes on
    row for row as the run that never stopped."""
    test = _tiny(**{name: value})
    rows = []
    whole = test.simulation()
    s = whole.run(lambda p: rows.append((p.step, p.mean_strain, p.stress, p.fracture, p.external_work,
                                         p.damping)) or True)
    lost = [r[0] for r in rows[:-1] if s.load_loss.reached and r[0] > s.load_loss.step]
    stop = lost[0] if lost else rows[len(rows) * 3 // 4][0]
    first = test.simulation()
    first.run(lambda p: p.step < stop)
    state = first.checkpoint()
    if value == "none":
        assert not [k for k in state if k.startswith("part_damping_")]
    elif name == "tail_damping":  # the mass damping's: whether it switched, then each node's mean velocity
        assert np.asarray(state["part_damping_mass"]).size == 1 + 3 * first.lattice.n_nodes
    else:
        assert f"part_{ROLE[name]}_{value}" in state
    second = test.simulation()
    second.restore(state)
    rest = []
    t = second.run(lambda p: rest.append((p.step, p.mean_strain, p.stress, p.fracture, p.external_work,
                                          p.damping)) or True)
    assert len(rest) > 1 and rest == rows[len(rows) - len(rest):]
    assert (t.steps, t.stop_reason, t.energy_balance_error) == (s.steps, s.stop_reason, s.energy_balance_error)
