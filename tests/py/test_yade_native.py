"""scripts/yade_native_cpm.py (YADE's native Cpm concrete model on the cube test)
on a tiny cube, run by YADE itself; YADE missing is a failure (install.sh installs it)."""
import json
import os
import re
import shutil
import subprocess

import numpy as np
import pytest

from conftest import ROOT, subprocess_env

NUM = r"([-+0-9.eE]+|nan|inf)"


def test_native_cpm_tiny_cube(tmp_path):
    exe = shutil.which("yade-double")
    if exe is None:
        pytest.fail("yade-double is not installed (README: install.sh installs Debian's yade)")
    out = tmp_path / "cpm"
    env = subprocess_env()
    r = subprocess.run([exe, "-j", "1", "-n", "-x", os.path.join(ROOT, "scripts", "yade_native_cpm.py"),
                        "--size", "0.06", "--spheres-in-cell", "300", "--final-strain", "4e-4", "--out", str(out)],
                       capture_output=True, text=True, cwd=tmp_path, timeout=300, env=env)
    text = r.stdout + r.stderr
    assert r.returncode == 0, text
    m = re.search(rf"^size=0.06 peak_stress_MPa={NUM} strain_at_peak={NUM} particles=(\d+) wall_s={NUM}", r.stdout,
                  re.M)
    assert m, text
    peak, strain, particles = float(m.group(1)), float(m.group(2)), int(m.group(3))
    assert 0.5 < peak < 6.0  # MPa: a tensile strength of concrete
    assert 2e-5 < strain < 4e-4
    assert 20 < particles < 200
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "done" and s["peak_stress_MPa"] == pytest.approx(peak, rel=1e-3)
    assert 30 < s["E_bulk_GPa"] < 40  # calibrated to 35 GPa on the default packing; a smaller cell differs a little
    header = (out / "curve.csv").read_text().splitlines()[0]
    assert header.startswith("mean_strain,stress_MPa")
    # The peak and its strain are the curve's largest row (9 digits in the file).
    c = np.genfromtxt(out / "curve.csv", delimiter=",", names=True)
    assert len(c) > 100 and c["mean_strain"][0] >= 0 and np.all(np.diff(c["step"]) > 0)
    k = int(np.argmax(c["stress_MPa"]))
    assert c["stress_MPa"][k] == pytest.approx(s["peak_stress_MPa"], rel=1e-8)
    assert c["mean_strain"][k] == pytest.approx(s["strain_at_peak"], rel=1e-8)


def test_native_cpm_bad_argument(tmp_path):
    exe = shutil.which("yade-double")
    if exe is None:
        pytest.fail("yade-double is not installed (README: install.sh installs Debian's yade)")
    env = subprocess_env()
    r = subprocess.run([exe, "-n", "-x", os.path.join(ROOT, "scripts", "yade_native_cpm.py"), "--radius", "-1"],
                       capture_output=True, text=True, cwd=tmp_path, timeout=120, env=env)
    assert r.returncode == 2, r.stdout + r.stderr
