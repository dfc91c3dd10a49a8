"""YADE bridge (issue 5): the one-bar law check and the 0.12 m cube cross-check,
both run by YADE itself (`yade-double -n -x`); YADE missing is a failure (install.sh installs it)."""
import os
import re
import shutil
import subprocess

import pytest

from conftest import ROOT, subprocess_env

NUM = r"([-+0-9.eE]+|nan|inf)"


@pytest.fixture
def yade():
    exe = shutil.which("yade-double")
    if exe is None:
        pytest.fail("yade-double is not installed (README: install.sh installs Debian's yade)")
    return exe


def run_yade(exe, script, *args, cwd):
    env = subprocess_env()
    return subprocess.run([exe, "-n", "-x", os.path.join(ROOT, "scripts", script), *args], capture_output=True,
                          text=True, cwd=cwd, timeout=900, env=env)


def test_one_bar_law_matches_ldem(yade, tmp_path):
    r = run_yade(yade, "yade_one_bar.py", cwd=tmp_path)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    m = re.search(rf"^one_bar max_rel_diff={NUM} tol={NUM} path_strain_max_rel_diff={NUM} dt_effect={NUM}$", r.stdout,
                  re.M)
    assert m, out
    diff, tol, path_diff, dt_effect = (float(g) for g in m.groups())
    assert diff <= tol <= 1e-12
    assert path_diff < 1e-9  # the same, with the rounding of YADE's absolute positions
    assert dt_effect == 0.0  # no rate effect in YADE's law
    assert "lost_interactions=0" in r.stdout and "early=[]" in r.stdout


def test_cube_crosscheck_ldem_vs_yade(yade, tmp_path):
    png = tmp_path / "crosscheck.png"
    r = run_yade(yade, "yade_crosscheck.py", str(png), cwd=tmp_path)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    m = re.search(rf"^peak_stress_MPa ldem={NUM} yade={NUM} rel_diff={NUM} "
                  rf"strain_at_peak ldem={NUM} yade={NUM} rel_diff={NUM}$", r.stdout, re.M)
    assert m, out
    pl, py_, rp, sl, sy, rs = (float(g) for g in m.groups())
    assert 1.0 < pl < 5.0 and 1.0 < py_ < 5.0  # MPa: a tensile strength of concrete
    assert rp <= 0.02 and rs <= 0.05
    assert abs(py_ - pl) / pl == pytest.approx(rp, rel=1e-2, abs=1e-6)
    assert png.exists() and png.stat().st_size > 0
    assert "lost_interactions=0" in r.stdout
