"""The scene script runs under python3, yade-double and yade-double-batch and
writes the same files as `ldem cube`; yade-batch table rows reach it, and the
batch example names the jobs that failed. Every script of scripts/ says a bad
argument in one line with exit code 2."""
import json
import os
import shutil
import subprocess

import numpy as np
import pytest

from conftest import ROOT, subprocess_env

SCRIPT = os.path.join(ROOT, "scripts", "cube_tension.py")
ENV = subprocess_env()


def summary(folder):
    return json.loads((folder / "summary.json").read_text())


def check_curve(folder, s):
    """curve.csv agrees with summary.json: its peak row at most the tracked peak and
    close to it, the fracture energy at the end, the steps."""
    c = np.genfromtxt(folder / "curve.csv", delimiter=",", names=True)
    assert s["peak_stress_MPa"] == pytest.approx(c["stress_MPa"].max(), rel=1e-9)  # the largest record
    assert c["fracture_J"][-1] == pytest.approx(s["fracture_energy_J"], rel=1e-9)
    assert c["step"][-1] == s["steps"]


def test_scene_script_under_python3(tmp_path):
    # --strain-rate 0.1: the tests' quasi-static rate at this size (5x fewer steps than the default).
    r = subprocess.run(["/usr/bin/python3", SCRIPT, "--size", "0.08", "--seed", "4", "--strain-rate", "0.1",
                        "--out", str(tmp_path)], capture_output=True, text=True, env=ENV, timeout=300)
    assert r.returncode == 0, r.stderr
    s = summary(tmp_path / "uniform_0.08m_seed4")
    assert s["status"] == "done" and s["parameters"]["seed"] == 4 and s["parameters"]["size"] == 0.08
    assert s["parameters"]["strain_rate"] == 0.1
    check_curve(tmp_path / "uniform_0.08m_seed4", s)
    assert (f"uniform_0.08m_seed4: peak {s['peak_stress_MPa']:.3f} MPa at strain {s['strain_at_peak']:.3e}, "
            f"U_num/U_min {s['U_ratio']:.2f}") in r.stdout


def _exe(name):
    exe = shutil.which(name)
    if exe is None:
        pytest.fail(f"{name} is not installed (README: install.sh installs Debian's yade and paraview)")
    return exe


def test_scene_script_under_yade_batch(tmp_path):
    """The batch example (scripts/yade_batch.sh, docs/python.md): two jobs run,
    a third with a size no multiple of L0 fails, and yade-batch's 0 whatever
    its jobs did becomes a line naming it and exit code 1."""
    _exe("yade-double-batch")
    table = tmp_path / "sweep.table"
    table.write_text("description size load seed strain_rate\n"
                     "u8_s1 0.08 'uniform' 1 0.1\nt8_s2 0.08 'triangular' 2 0.1\nodd 0.07 'uniform' 1 0.1\n")
    r = subprocess.run(["bash", os.path.join(ROOT, "scripts", "yade_batch.sh"), str(table), SCRIPT, "logs"],
                       capture_output=True, text=True, env=ENV, cwd=tmp_path, timeout=600)
    assert r.returncode == 1, r.stdout + r.stderr
    assert r.stderr.splitlines()[-1] == "yade_batch.sh: 1 of 3 jobs failed: odd (their logs: logs/<job>.log)", r.stderr
    assert "cube_tension.py: error: cube size 0.07 m is not a multiple of L0 = 0.02 m" in (tmp_path / "logs/odd.log").read_text()
    u, t = summary(tmp_path / "out/scenes/u8_s1"), summary(tmp_path / "out/scenes/t8_s2")
    assert (u["parameters"]["load"], u["parameters"]["seed"], u["threads"]) == ("uniform", 1, 1)
    assert (t["parameters"]["load"], t["parameters"]["seed"]) == ("triangular", 2)
    assert t["parameters"]["size"] == 0.08 and u["parameters"]["strain_rate"] == t["parameters"]["strain_rate"] == 0.1
    check_curve(tmp_path / "out/scenes/u8_s1", u)
    check_curve(tmp_path / "out/scenes/t8_s2", t)


def _one_line(r, under=None) -> str:
    """The script's error: rc 2, one line (under YADE, after its own lines up to "Running script ..."), no traceback."""
    lines = r.stderr.strip().splitlines()
    if under:
        lines = lines[next(i for i, line in enumerate(lines) if line.startswith("Running script")) + 1:]
    assert r.returncode == 2 and len(lines) == 1 and "Traceback" not in r.stdout + r.stderr, (r.returncode, r.stderr)
    return lines[0]


BAD_ARGUMENTS = [("cube_tension.py", ["--size", "0.07"], "cube size 0.07 m is not a multiple of L0 = 0.02 m"),
                 ("cube_tension.py", ["--size", "abc"], "argument --size: invalid float value: 'abc'"),
                 ("cube_tension.py", ["--seed", "-3"], "seed must be >= 0 (got -3)"),
                 ("gallery.py", ["--threads", "x"], "argument --threads: invalid int value: 'x'"),
                 ("yade_specimen.py", ["s.toml", "--nope"], "unrecognized arguments: --nope"),
                 ("yade_separation.py", ["--nope"], "unrecognized arguments: --nope"),
                 ("yade_crosscheck.py", ["--nope"], "unrecognized arguments: --nope"),
                 ("yade_native_cpm.py", ["--nope"], "unrecognized arguments: --nope")]


@pytest.mark.parametrize("script,args,message", BAD_ARGUMENTS, ids=[f"{s}{a}" for s, a, _ in BAD_ARGUMENTS])
def test_a_scripts_bad_argument_is_one_line_under_python3(tmp_path, script, args, message):
    r = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", script), *args], capture_output=True,
                       text=True, env=ENV, cwd=tmp_path, timeout=120)
    assert _one_line(r).endswith(f": error: {message}")


@pytest.mark.parametrize("script,args,message", BAD_ARGUMENTS[:2] + BAD_ARGUMENTS[4:5],
                         ids=[f"{s}{a}" for s, a, _ in BAD_ARGUMENTS[:2] + BAD_ARGUMENTS[4:5]])
def test_a_scripts_bad_argument_is_one_line_under_yade(tmp_path, script, args, message):
    r = subprocess.run([_exe("yade-double"), "-n", "-x", os.path.join(ROOT, "scripts", script), *args],
                       capture_output=True, text=True, env=ENV, cwd=tmp_path, timeout=120)
    assert _one_line(r, "yade").endswith(f": error: {message}")


def test_a_batch_tables_unknown_column_is_one_line(tmp_path):
    """A column the scene script has no parameter for: its job's log says so in one line, not YADE's NameError."""
    _exe("yade-double-batch")
    table = tmp_path / "sweep.table"
    table.write_text("description size final_strain\nshort 0.04 1e-4\n")
    r = subprocess.run(["bash", os.path.join(ROOT, "scripts", "yade_batch.sh"), str(table), SCRIPT, "logs"],
                       capture_output=True, text=True, env=ENV, cwd=tmp_path, timeout=300)
    assert r.returncode == 1 and "1 of 1 jobs failed: short" in r.stderr, r.stderr
    log = (tmp_path / "logs/short.log").read_text()
    assert "cube_tension.py: error: the batch table: Parameter `final_strain' has no default value assigned" in log
    assert "Traceback" not in log


@pytest.mark.parametrize("args,message", [(["RUN", "abc"], "SCALE must be a positive number (got 'abc')"),
                                          (["nowhere"], "nowhere holds no bars.pvd and crack.pvd (ldem cube and "
                                                        "ldem run write them)")])
def test_the_paraview_scripts_bad_argument_is_one_line(tmp_path, args, message):
    (tmp_path / "RUN").mkdir()
    for name in ("bars.pvd", "crack.pvd"):
        (tmp_path / "RUN" / name).write_text("")
    r = subprocess.run([_exe("pvpython"), os.path.join(ROOT, "scripts", "paraview_crack.py"), *args],
                       capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert _one_line(r) == f"paraview_crack.py: error: {message}"


def test_the_batch_example_refuses_bad_arguments_in_one_line(tmp_path):
    r = subprocess.run(["bash", os.path.join(ROOT, "scripts", "yade_batch.sh"), "no.table", SCRIPT],
                       capture_output=True, text=True, cwd=tmp_path, timeout=60)
    assert _one_line(r) == "yade_batch.sh: error: no file no.table"
    assert not (tmp_path / "out").exists()
