"""The command line: bad input is one line and exit code 2; a run writes every file."""
import csv
import json

import numpy as np
import pytest

from conftest import FAST, ROOT, colour_share, picture, undamaged_on_white
from ldem.study.registry import STUDIES

BAD_INPUT = [
    (["--size", "-0.12"], "size must be > 0 (got -0.12 m)"),
    (["--size", "0.13"], "not a multiple of L0"),
    (["--nu", "0.5"], "nu must be in (0, 0.5)"),
    (["--nu", "0.7"], "nu must be in (0, 0.5)"),
    (["--nu", "0"], "nu must be in (0, 0.5) (got 0)"),  # no diagonals: a mechanism
    (["--E", "1e300"], "E must be in (0, 1e+14] (got 1e+300 Pa)"),
    (["--size", "1e300"], "far beyond any machine"),
    (["--size", "8"], "modules (896481200 bars) needs about 89.6 GB; this machine has"),  # 400^3: checked first
    (["--threads", "99999999999"], "threads is out of range"),
    (["--Gf-cv", "-0.1"], "Gf_cv must be in [0, 10] (got -0.1)"),
    (["--load", "shear"], "invalid choice"),
    (["--tail-drive", "bogus"], "invalid choice: 'bogus'"),
    (["--dampings", "viscous"], "unknown dampings 'viscous' (expected some of mass, bar_dashpots, separated by "
                                "commas, or none)"),
    (["--dampings", "mass,mass"], "dampings 'mass,mass' names mass twice"),
    (["--dampings", "bar_dashpots", "--tail-damping", "relative"],
     "tail_damping relative re-centres the mass damping, which dampings does not name"),
    (["--Gf-draw", "cell"], "invalid choice"),
    (["--E", "abc"], "invalid float value"),
    (["--L0", "0"], "L0 must be > 0 (got 0 m)"),
    (["--dt", "1"], "stability limit"),
    (["--strain-rate", "-1"], "strain_rate must be > 0 (got -1 1/s)"),
    (["--dt-safety", "1.5"], "dt_safety must be in (0, 1] (got 1.5)"),
    (["--seed", "-3"], "seed must be >= 0 (got -3)"),
]


@pytest.mark.parametrize("args,message", BAD_INPUT)
def test_bad_input_is_one_line_and_exit_2(cli, tmp_path, args, message):
    r = cli("cube", "--out", str(tmp_path / "o"), "--no-progress", *args)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert message in lines[0]
    assert "Traceback" not in r.stderr


def test_unwritable_output_folder(cli, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    r = cli("cube", "--out", str(blocker / "sub"), "--no-progress")
    assert r.returncode == 2
    assert "cannot write to output folder" in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_help_documents_units_and_defaults(cli):
    r = cli("cube", "--help")
    assert r.returncode == 0
    text = " ".join(r.stdout.split())  # as argparse wraps it to the terminal's width
    for word in ("--size", "[m]", "--Gf-cv", "--corr-length", "--eps-p", "--c-a", "--zeta", "--strain-rate",
                 "[1/s]", "--final-strain", "--top-lateral", "--threads", "(default: 0.12)",
                 "(default: 35000000000.0)"):
        assert word in text, word
    assert "(default: 0.12) (default: 0.12)" not in text  # once


def test_cube_run_writes_all_outputs(cli, tmp_path):
    out = tmp_path / "cube"
    # One thread: two on a busy 2-core machine (or beside the C++ tests under ctest -j 2)
    # spin at every step's barrier and took 159 s instead of 5 (threads: test_golden.py).
    r = cli("cube", "--out", str(out), "--no-progress", "--size", str(FAST["size"]),
            "--strain-rate", str(FAST["strain_rate"]), "--seed", "2", "--threads", "1")
    assert r.returncode == 0, r.stderr
    for name in ("curve.png", "energies.png"):
        picture(out / name)
    # The crack picture: the central slice of a separated cube has broken (red),
    # damaged (orange) and undamaged (faint dark cyan) bars.
    cracks = picture(out / "cracks.png")
    for colour in ("red", "orange", undamaged_on_white()):
        assert colour_share(cracks, colour) > 1e-4, colour

    with open(out / "curve.csv") as f:
        header = next(csv.reader(f))
    assert ",".join(header) == ("step,time_s,mean_strain,stress_MPa,stress_top_MPa,external_work_J,kinetic_J,"
                                "elastic_J,fracture_J,damping_J,damaged_bars,broken_bars")  # as README lists it
    curve = np.genfromtxt(out / "curve.csv", delimiter=",", names=True)

    s = json.loads((out / "summary.json").read_text())
    # What it prints is what summary.json says.
    assert f"peak normal stress {s['peak_stress_MPa']:.4f} MPa at mean strain {s['strain_at_peak']:.4e}" in r.stdout
    assert f"U_num {s['U_num_J']:.4g} J, U_num/U_min {s['U_ratio']:.3f}" in r.stdout
    assert f"{s['steps']} steps of {s['dt_s']:.3e} s" in r.stdout
    for key in ("peak_stress_MPa", "strain_at_peak", "fracture_energy_J", "min_fracture_energy_J",
                "energy_balance_error", "clamped_bars", "n_nodes", "n_bars", "steps", "dt_s", "wall_s"):
        assert key in s, key
    assert s["parameters"]["seed"] == 2 and s["parameters"]["size"] == FAST["size"]
    # The peak is tracked at every step: at least the curve's maximum, and close
    # to it (rows are eps_p/50 of strain apart). U_min = E[G_f] x face area.
    assert s["peak_stress_MPa"] == pytest.approx(curve["stress_MPa"].max(), rel=1e-9)  # the largest record
    # A full run goes to separation; U_num is the energy then, never below the cheapest cut.
    assert s["stop_reason"] == "separated" and s["separated"]
    assert s["U_num_J"] == s["separation"]["fracture_energy_J"] == pytest.approx(curve["fracture_J"][-1], rel=1e-9)
    assert s["load_loss"]["mean_strain"] < s["separation"]["mean_strain"]
    assert s["load_loss"]["fracture_energy_J"] < s["U_num_J"]
    assert s["U_num_J"] >= s["U_mincut_J"] > 0.3 * s["min_fracture_energy_J"]
    assert s["min_fracture_energy_J"] == pytest.approx(100.0 * 0.08 ** 2)
    assert s["n_nodes"] == 5 ** 3 + 4 ** 3
    assert s["energy_balance_error"] < 0.01 and s["energy_error"] is False

    import meshio
    mesh = meshio.read(out / "bars.vtu")
    assert len(mesh.cells[0].data) == s["n_bars"]
    states = mesh.cell_data["damage_state"][0]
    assert set(np.unique(states)) <= {0, 1, 2}
    # The end state is the last row's: the same counts of broken and damaged bars.
    assert (states == 2).sum() == curve["broken_bars"][-1] > 0
    assert (states == 1).sum() == curve["damaged_bars"][-1]


def test_energy_error_is_flagged_and_exits_1(cli, tmp_path):
    """A run above the energy tolerance says so in summary.json and exits 1 (here a
    tolerance no run can meet, so the flag itself is what is tested)."""
    out = tmp_path / "e"
    r = cli("cube", "--out", str(out), "--no-progress", "--no-plots", "--size", str(FAST["size"]),
            "--strain-rate", str(FAST["strain_rate"]), "--stop-at", "load_loss", "--energy-tolerance", "1e-12")
    assert r.returncode == 1, r.stderr
    assert "energy balance error" in r.stderr and "not trustworthy" in r.stderr
    s = json.loads((out / "summary.json").read_text())
    assert s["energy_error"] is True and s["energy_balance_error"] > 1e-12 and s["status"] == "done"


def test_version_and_provenance(cli, tmp_path):
    """`ldem --version`; every summary.json says which ldem ran it, where and when."""
    import subprocess

    import ldem

    r = cli("--version")
    assert r.returncode == 0 and r.stdout.startswith(f"ldem {ldem.__version__}"), r.stdout + r.stderr
    s = ldem.CubeTest(size=0.04, strain_rate=0.5, stop_at="load_loss").run().summary
    p = s["provenance"]
    assert p["ldem_version"] == ldem.__version__ and p["host"] and p["date"].endswith("+00:00")
    head = subprocess.run(["git", "-C", ROOT, "rev-parse", "HEAD"], capture_output=True, text=True)
    if head.returncode == 0:  # a checkout: the build wrote its commit
        assert p["git_commit"].split("-")[0] == head.stdout.strip(), p
        assert f"(git {p['git_commit']})" in r.stdout


def test_rerun_reproduces_a_folder_and_says_when_it_does_not(cli, tmp_path):
    out = tmp_path / "run"
    r = cli("cube", "--size", "0.04", "--strain-rate", "0.5", "--out", str(out), "--no-progress", "--no-plots")
    assert r.returncode == 0, r.stderr
    r = cli("rerun", str(out), "--no-progress")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "identical: the curve and every other field of the summary" in r.stdout
    assert "not compared: wall_s (the wall time: how fast, not what); provenance (" in r.stdout
    assert (out / "rerun" / "curve.csv").read_bytes() == (out / "curve.csv").read_bytes()
    # A result that the same parameters do not give (here: an edited peak) is reported, exit 1.
    s = json.loads((out / "summary.json").read_text())
    s["peak_stress_MPa"] *= 1.01
    s["quasi_static"]["kinetic_over_work_at_peak"] *= 1 + 1e-10  # a nested field is compared too
    (out / "summary.json").write_text(json.dumps(s))
    r = cli("rerun", str(out), "--no-progress", "--out", str(tmp_path / "again"))
    assert r.returncode == 1 and "differs: peak_stress_MPa" in r.stdout, r.stdout
    assert "differs: quasi_static.kinetic_over_work_at_peak" in r.stdout and "2 difference(s)" in r.stdout
    r = cli("rerun", str(tmp_path / "nowhere"))
    assert r.returncode == 2 and "cannot read" in r.stderr and len(r.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("fmt,magic", [("pdf", b"%PDF"), ("svg", b"<?xml")])
def test_vector_figures(cli, tmp_path, fmt, magic):
    """--figure-format pdf|svg: the three pictures as vector files, in the one ldem style."""
    out = tmp_path / fmt
    r = cli("cube", "--size", "0.04", "--strain-rate", "0.5", "--stop-at", "load_loss", "--out", str(out),
            "--no-progress", "--figure-format", fmt)
    assert r.returncode == 0, r.stderr
    for name in ("curve", "energies", "cracks"):
        data = (out / f"{name}.{fmt}").read_bytes()
        assert data.startswith(magic) and len(data) > 5000, name
        assert not (out / f"{name}.png").exists()
    svg_or_pdf = (out / f"curve.{fmt}").read_bytes()
    if fmt == "svg":  # units on the axes (svg.fonttype none keeps the text as text)
        assert b"mean strain [-]" in svg_or_pdf and b"normal stress [MPa]" in svg_or_pdf


def test_more_threads_than_cores_are_clamped_with_a_warning(cli, tmp_path):
    import os

    out = tmp_path / "t"
    r = cli("cube", "--size", "0.04", "--strain-rate", "0.2", "--stop-at", "load_loss", "--threads", "1000",
            "--out", str(out), "--no-progress", "--no-plots")
    cores = os.cpu_count()
    assert r.returncode == 0, r.stderr
    assert r.stderr.strip() == f"ldem cube: warning: --threads 1000 is more than the {cores} cores: using {cores}"
    assert json.loads((out / "summary.json").read_text())["threads"] == cores


def test_bench_too_big_for_the_machine_is_one_line(cli):
    r = cli("bench", "--modules", "400", "--steps", "1", "--repeats", "1")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "this machine has" in r.stderr, r.stderr



@pytest.mark.parametrize("command", [["cube"], *(["study", name] for name in STUDIES), ["bench"], ["rerun"]])
def test_help_gives_each_default_once_and_only_a_real_one(cli, command):
    r = cli(*command, "--help")
    assert r.returncode == 0
    text = " ".join(r.stdout.split())
    for empty in ("(default: None)", "(default: False)", "(default: )", "(default: [])"):
        assert empty not in text, (command, empty)
    for option in ("--zeta", "--seed", "--strain-rate") if command == ["cube"] else ():
        help_of = text.split(f" {option} ")[1].split(" --")[0]
        assert help_of.count("(default:") == 1, (option, help_of)


def test_core_api_has_docstrings_keywords_and_reprs():
    """The C++ classes from Python: documented, built with keyword arguments, printable."""
    from ldem import _core

    m = _core.Material(E=3e10, nu=0.2, Gf_draw="module")
    assert (m.E, m.nu, m.Gf_draw, m.rho) == (3e10, 0.2, "module", 2400.0)
    assert repr(m).startswith("Material(E=30000000000.0, nu=0.2, rho=2400.0,") and "Gf_draw='module'" in repr(m)
    assert repr(_core.RunParams(seed=3)).startswith("RunParams(seed=3, gravity=0.0, dampings='mass,bar_dashpots', zeta=0.02,")
    with pytest.raises(ValueError, match="unknown parameter 'Young'"):
        _core.Material(Young=1.0)
    assert "Poisson's ratio; in (0, 0.5)" in _core.Material.nu.__doc__
    sim = _core.Simulation(_core.CubeTestParams())
    assert repr(sim) == f"Simulation(6 x 6 x 6 modules, 3150 bars, dt = {sim.dt:g} s, step 0)"
    assert repr(sim.lattice) == "Lattice(6 x 6 x 6 modules of L0 = 0.02 m, 559 nodes, 3150 bars)"
    for cls in (_core.Simulation, _core.Lattice, _core.CurvePoint, _core.RunSummary, _core.Material,
                _core.LoadingParams, _core.RunParams, _core.CubeTestParams):
        assert cls.__doc__ and len(cls.__doc__) > 20, cls


def test_restart_continues_bit_for_bit(cli, tmp_path):
    """--checkpoint-every writes checkpoint.npz; a run stopped after it (here by
    an observer that interrupts it, as Ctrl-C would) and continued with
    --restart ends exactly as a run that never stopped: the same curve.csv,
    byte for byte, and the same summary numbers."""
    import numpy as np

    import ldem
    from ldem.rerun import RESTART_SKIPS, differences

    args = ["--size", "0.06", "--strain-rate", "0.5", "--threads", "1", "--no-progress", "--no-plots"]
    r = cli("cube", *args, "--out", str(tmp_path / "whole"))
    assert r.returncode == 0, r.stderr
    test = ldem.CubeTest(size=0.06, strain_rate=0.5, threads=1)
    seen = []

    def stop_after_second_checkpoint(row):
        seen.append(row["step"])
        if len(seen) == 2 * 700 + 5:
            raise KeyboardInterrupt

    sim = test.simulation()
    with pytest.raises(KeyboardInterrupt):
        ldem.run_cube(test, out=str(tmp_path / "cut"), progress=False, plots=False, simulation=sim,
                      checkpoint_every=700, observers=[stop_after_second_checkpoint])
    cut = json.loads((tmp_path / "cut" / "summary.json").read_text())
    assert cut["status"] == "interrupted"
    state = np.load(tmp_path / "cut" / "checkpoint.npz")
    assert int(state["counters"][0]) > 0 and "parameters" in state.files
    r = cli("cube", "--restart", str(tmp_path / "cut"), "--no-progress", "--no-plots")
    assert r.returncode == 0, r.stderr
    assert not (tmp_path / "cut" / "checkpoint.npz").exists()  # finished: nothing a restart would run again
    whole, again = (json.loads((tmp_path / d / "summary.json").read_text()) for d in ("whole", "cut"))
    # At 25 times the study's rate the drag bound holds this cube's tail near the initial rate and it
    # reaches the final strain unseparated (with tail_drag 0.1 it separated): either end restarts alike.
    assert again["status"] == "done" and again["stop_reason"] == whole["stop_reason"]
    assert differences(whole, again, RESTART_SKIPS) == []
    assert (tmp_path / "cut" / "curve.csv").read_bytes() == (tmp_path / "whole" / "curve.csv").read_bytes()
