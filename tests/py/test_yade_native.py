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
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "done" and s["stop_reason"] == "final_strain"
    # The printed line is summary.json's, rounded to 5 digits.
    assert (peak, strain, particles) == (float(f"{s['peak_stress_MPa']:.4f}"), float(f"{s['strain_at_peak']:.4e}"),
                                         s["particles"])
    # YADE's own model, not ours: nothing to derive these from, so they are the values measured on this
    # tiny cube (Debian's YADE 2023.02a, one thread, packing seed 1). The run is deterministic: two runs
    # gave identical summary.json and curve.csv, bit for bit, so the tolerance only absorbs the last
    # digits. A change of YADE or of the packing moves them by percents (seeds 2 and 3 change the
    # 0.12 m peak by -11 % and -18 %, README): then re-measure, and re-calibrate if the default packing moved.
    measured = dict(peak_stress_MPa=1.9521871620150726, strain_at_peak=1.5673975950084316e-4,
                    E_initial_GPa=16.370924431401598, E_bulk_GPa=33.49245525989025, nu_bulk=0.19956876195385645,
                    work_per_face_area_J_m2=24.828083748623815, final_stress_MPa=0.4513462049186185,
                    gauge_length_m=0.053104695923813214, packing_fraction=0.5659520987800274)
    for k, v in measured.items():
        assert s[k] == pytest.approx(v, rel=1e-9), k
    assert (s["particles"], s["cohesive_contacts"], s["bottom_particles"], s["top_particles"], s["steps"]) == \
        (57, 232, 7, 7, 7893)
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
