"""The drive's pace before the load loss (issue 41 item 3; pkg/ldem/dynamics/CrackPace.hpp):
its parameters come from the table; at crack_pace 1 the adaptive drive is the
fixed drive bit for bit until the load loss; and on the 0.48 m uniform cube,
where a constant rate feeds the running crack, the paced drive's fracture
energy at the load loss moves by less than 2 % when the rate is quartered
(criterion (b) of results/criteria/README.md), the unpaced one's by more than 4 %;
and on the coarse notched beam, whose own motion under the drive is near 1e-3
of the work, the pace (which counts the kinetic energy less that motion)
leaves the peak where the unpaced drive puts it. The pace is the cube's default (cube.CUBE_DEFAULTS)."""
import json
import os

import pytest

from ldem import _core

ARGS = ["--load", "uniform", "--seed", "1", "--stop-at", "load_loss", "--loss-stop-strain-ratio", "0",
        "--threads", "1", "--no-progress", "--no-plots"]


def run(tmp_path_factory, *more):
    from conftest import run_cli

    d = tmp_path_factory.mktemp("pace")
    r = run_cli("cube", *ARGS, *more, "--out", str(d))
    assert r.returncode == 0, r.stderr
    return json.loads((d / "summary.json").read_text())


def test_the_parameters_come_from_the_table(cli):
    table = {p["name"]: p for p in _core.parameter_table()}
    assert table["crack_pace"]["default"] == 1.0 and table["crack_kinetic"]["default"] == 1e-3  # off by default
    r = cli("cube", "--help")
    assert "--crack-pace" in r.stdout and "--crack-kinetic" in r.stdout


def test_at_pace_one_the_adaptive_drive_is_the_fixed_drive_until_the_load_loss(tmp_path_factory):
    fixed = run(tmp_path_factory, "--size", "0.08", "--tail-drive", "fixed")
    unpaced = run(tmp_path_factory, "--size", "0.08", "--crack-pace", "1")
    paced = run(tmp_path_factory, "--size", "0.08", "--crack-pace", "0.0625")
    assert unpaced["peak_stress_MPa"] == fixed["peak_stress_MPa"]
    assert unpaced["load_loss"] == fixed["load_loss"]
    assert paced["load_loss"] != fixed["load_loss"]  # the pace acts on this cube


def test_the_tail_damping_leaves_the_paced_drive_alone_until_the_load_loss(tmp_path_factory):
    """tail_damping relative acts from the load loss on: before it, the paced drive
    (its brake's bound included) is the absolute damping's, bit for bit. The brake
    once read the relative tail's bound, 1 + D_f tau times gentler, and the 0.24 m
    cube lost its load at a mean strain of 4.4631e-4 instead of 4.4629e-4."""
    pace = ["--size", "0.24", "--crack-pace", "0.0625", "--crack-secant", "0.9"]
    absolute = run(tmp_path_factory, *pace, "--tail-damping", "absolute")
    relative = run(tmp_path_factory, *pace, "--tail-damping", "relative")
    assert relative["peak_stress_MPa"] == absolute["peak_stress_MPa"]
    assert relative["load_loss"] == absolute["load_loss"]


# The step these measurements were made at, the lagged dashpots' 0.656 of 2/omega_max: at the default 0.9 the
# constant rate leaves a balance error of 2.13e-3 and 2.10e-3 at this load loss (seed 1; the paced default: 1.8e-3; the
# criteria study, results/criteria/, measures the pace at the default step on three seeds).
LAGGED_STEP = ["--dashpot-velocity", "lagged", "--zeta-high", "0.2", "--dt-safety", "0.8"]


@pytest.fixture(scope="module")
def cube048(tmp_path_factory):
    """The 0.48 m uniform cube at its default drive (paced: cube.CUBE_DEFAULTS) and at the constant rate, each at
    0.02 /s and a quarter of it."""
    return {(pace, q): run(tmp_path_factory, "--size", "0.48", "--strain-rate", str(0.02 / q), *LAGGED_STEP,
                           *(["--crack-pace", pace] if pace == "1" else []))
            for pace in ("default", "1") for q in (1, 4)}


def test_the_paced_drive_gives_the_quarter_rates_fracture_energy(cube048):
    def change(pace, key):
        a, b = cube048[(pace, 1)], cube048[(pace, 4)]
        if key == "U":
            return a["load_loss"]["fracture_energy_J"] / b["load_loss"]["fracture_energy_J"] - 1
        return a["peak_stress_MPa"] / b["peak_stress_MPa"] - 1
    # Measured: at the default +0.81 % (21.344 J against 21.174 J), at the constant rate +6.5 % (23.21 J
    # against 21.80 J); the peaks -0.08 % and +0.51 %. (The pace on K_own alone, crack_kinetic 1e-3: +1.53 %.)
    assert abs(change("default", "U")) < 0.02
    assert change("1", "U") > 0.04
    assert abs(change("default", "peak")) < 0.01
    for s in cube048.values():
        assert s["energy_balance_error"] < 2e-3


def test_the_pace_leaves_a_notched_beams_peak_alone(tmp_path_factory):
    """examples/beam_3pb.toml (L0 10 mm, rule (c)): the beam following its platen has K/W near 1e-3, so a pace on K
    braked and released in turn and raised the peak by 11 %; on K_own it leaves it alone. A brake within a period
    of the bending mode set that mode ringing (+1.2 % at 0.05 D/s): the pace changes no faster than the smooth
    start."""
    from conftest import ROOT, run_cli

    def beam(*more):
        d = tmp_path_factory.mktemp("beam")
        r = run_cli("run", os.path.join(ROOT, "examples", "beam_3pb.toml"), "--threads", "1", "--no-plots",
                    "--no-progress", "--set", "final_strain=0.001", *more, "--out", str(d))
        assert r.returncode == 0, r.stderr
        return json.loads((d / "summary.json").read_text())

    unpaced = beam()
    paced = beam("--set", "tail_drive=adaptive", "--set", "crack_pace=0.0625")
    assert paced["steps"] != unpaced["steps"]  # the pace acted
    assert abs(paced["peak_stress_MPa"] / unpaced["peak_stress_MPa"] - 1) < 0.005



def test_the_secant_slows_the_drive_from_the_bend_of_the_curve(tmp_path_factory):
    """crack_secant: the pace also slows while the curve's secant is below that fraction of the elastic one and
    the stress within the band. On the 0.08 m cube: at the rate's speed while the curve is straight, at
    crack_pace of it at the peak (where K_own alone leaves it near full speed), and more steps to the load loss."""
    import numpy as np
    from conftest import run_cli

    def curve(*more):
        d = tmp_path_factory.mktemp("secant")
        r = run_cli("cube", *ARGS, "--size", "0.08", "--crack-pace", "0.0625", *more, "--out", str(d))
        assert r.returncode == 0, r.stderr
        c = np.genfromtxt(d / "curve.csv", delimiter=",", names=True)
        return c, json.loads((d / "summary.json").read_text())

    def speed(c, row):  # mean strain per step over the record interval ending at row
        return (c["mean_strain"][row] - c["mean_strain"][row - 1]) / (c["step"][row] - c["step"][row - 1])

    (a, sa), (b, sb) = curve("--crack-secant", "0"), curve("--crack-secant", "0.9")
    assert sb["load_loss"]["step"] > sa["load_loss"]["step"]
    straight = np.searchsorted(a["mean_strain"], 0.25 * sa["strain_at_peak"])  # a quarter of the peak strain: straight
    assert speed(b, straight) == pytest.approx(speed(a, straight), rel=1e-9)
    peak_a, peak_b = np.argmax(a["stress_MPa"]), np.argmax(b["stress_MPa"])
    assert speed(a, peak_a) > 0.5 * speed(a, straight)  # K_own alone: near full speed at the peak
    assert speed(b, peak_b) < 0.1 * speed(a, straight)  # the secant: at crack_pace (0.0625)
    assert sb["energy_balance_error"] < 2e-3
