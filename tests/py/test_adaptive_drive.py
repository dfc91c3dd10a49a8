"""The adaptive drive after the load loss (issue 27 item 4; AdaptiveDrive in
pkg/ldem/Loading.hpp): its parameters reach the command line and summary.json
from Parameters.hpp, the 0.08 m cube separates in fewer steps than with the
fixed drive and its U_num stays within 1 %, and a checkpoint taken past the
load loss (its `tail_drive` array through the bindings, as checkpoint.npz
holds it) restarts on the bits of a run that never stopped."""
import json

import numpy as np
import pytest

import ldem
from ldem import _core

# The constant rate before the load loss (the cube's default paces it: the fixed drive does not).
ARGS = ["--size", "0.08", "--seed", "2", "--threads", "1", "--crack-pace", "1", "--no-progress", "--no-plots"]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from conftest import run_cli

    out = {}
    for drive in ("fixed", "adaptive"):
        d = tmp_path_factory.mktemp(drive)
        r = run_cli("cube", *ARGS, "--tail-drive", drive, "--out", str(d))
        assert r.returncode == 0, r.stderr
        out[drive] = json.loads((d / "summary.json").read_text())
    return out


def test_the_parameters_come_from_the_table_with_their_defaults(cli):
    table = {p["name"]: p for p in _core.parameter_table()}
    assert table["tail_drive"]["default"] == "adaptive"
    assert {"fixed", "adaptive"} <= set(table["tail_drive"]["choices"])
    for name, default in (("loss_speedup", 20.0), ("tail_max_speedup", 2000.0), ("tail_load", 0.005),
                          ("tail_drag", 0.03), ("tail_step", 1.1)):
        assert table[name]["default"] == default, name
    assert ldem.CubeTest().tail_drive == "adaptive"
    r = cli("cube", "--help")
    for flag in ("--tail-drive", "--tail-max-speedup", "--tail-load", "--tail-drag", "--tail-step"):
        assert flag in r.stdout, flag
    r = cli("cube", "--size", "0.04", "--tail-max-speedup", "10", "--out", "unused", "--no-progress")
    assert r.returncode == 2 and "tail_max_speedup (10) must be at least loss_speedup (20)" in r.stderr


def test_fewer_steps_to_the_same_u_num_than_the_fixed_drive(runs):
    fixed, adaptive = runs["fixed"], runs["adaptive"]
    assert fixed["parameters"]["tail_drive"] == "fixed" and adaptive["parameters"]["tail_drive"] == "adaptive"
    assert fixed["separated"] and adaptive["separated"]
    assert adaptive["peak_stress_MPa"] == fixed["peak_stress_MPa"]  # bit for bit: the drive changes past the load loss
    assert adaptive["load_loss"] == fixed["load_loss"]
    # Measured: 132768 steps against 209088, U_num 0.42848 J against 0.42860 J.
    assert adaptive["steps"] < 0.8 * fixed["steps"]
    assert adaptive["U_num_J"] == pytest.approx(fixed["U_num_J"], rel=0.01)
    assert adaptive["energy_balance_error"] < 1e-3


def test_a_checkpoint_past_the_load_loss_restarts_on_the_same_bits(runs):
    test = ldem.CubeTest(size=0.08, seed=2, threads=1, crack_pace=1.0)
    whole = test.simulation()
    rows = []
    s = whole.run(lambda p: rows.append((p.step, p.mean_strain, p.fracture, p.external_work)) or True)
    # Stop at the first record past the load loss at which the drive goes at more than 1.5 x 20 x strain_rate.
    stop = next(rows[k][0] for k in range(1, len(rows))
                if rows[k][0] > s.load_loss.step and
                (rows[k][1] - rows[k - 1][1]) / (rows[k][0] - rows[k - 1][0]) / whole.dt > 1.5 * 20 * 0.02)
    first = test.simulation()
    first.run(lambda p: p.step < stop)
    state = first.checkpoint()
    drive = np.asarray(state["part_drive_adaptive"])  # the ramp's start, floor and time, then the adaptive drive's
    assert drive.size == 11 and drive[3] == 1.0  # active, its state stored (no pace: crack_pace 1)
    assert drive[1] == 20.0  # the floor: the bound leaves the 0.08 m cube the fixed drive's ramp
    assert drive[6] > 20.0 and drive[7] > 20.0  # S_0, S_1: faster than the fixed drive there
    second = test.simulation()
    second.restore(state)
    rest = []
    t = second.run(lambda p: rest.append((p.step, p.mean_strain, p.fracture, p.external_work)) or True)
    assert rest == rows[len(rows) - len(rest):]
    assert (t.steps, t.separation.fracture, t.energy_balance_error) == (s.steps, s.separation.fracture,
                                                                         s.energy_balance_error)
