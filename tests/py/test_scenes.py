"""The scene script runs under python3, yade-double and yade-double-batch and
writes the same files as `ldem cube`; yade-batch table rows reach it."""
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


def test_scene_script_under_yade_batch(tmp_path):
    batch = shutil.which("yade-double-batch")
    if batch is None:
        pytest.fail("yade-double-batch is not installed (README: install.sh installs Debian's yade)")
    table = tmp_path / "sweep.table"
    table.write_text("description size load seed strain_rate\n"
                     "u8_s1 0.08 'uniform' 1 0.1\nt8_s2 0.08 'triangular' 2 0.1\n")
    r = subprocess.run([batch, "--job-threads", "1", "--log", str(tmp_path / "@.log"), str(table), SCRIPT],
                       capture_output=True, text=True, env=ENV, cwd=tmp_path, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    u, t = summary(tmp_path / "out/scenes/u8_s1"), summary(tmp_path / "out/scenes/t8_s2")
    assert (u["parameters"]["load"], u["parameters"]["seed"], u["threads"]) == ("uniform", 1, 1)
    assert (t["parameters"]["load"], t["parameters"]["seed"]) == ("triangular", 2)
    assert t["parameters"]["size"] == 0.08 and u["parameters"]["strain_rate"] == t["parameters"]["strain_rate"] == 0.1
    check_curve(tmp_path / "out/scenes/u8_s1", u)
    check_curve(tmp_path / "out/scenes/t8_s2", t)
