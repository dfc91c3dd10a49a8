"""ParaView as its users use it (issue 14 item 3): scripts/paraview_crack.py
opens a run's bars.pvd and crack.pvd in ParaView itself (pvbatch, on a virtual
display: xvfb-run) and saves the crack; ParaView missing is a failure
(install.sh installs it)."""
import os
import shutil
import subprocess

import pytest

from conftest import ROOT, colour_share, picture, subprocess_env


def test_paraview_script_shows_the_crack(cli, tmp_path):
    for exe in ("pvbatch", "xvfb-run"):
        if shutil.which(exe) is None:
            pytest.fail(f"{exe} is not installed (README: install.sh installs paraview and xvfb)")
    out = tmp_path / "cube"
    r = cli("cube", "--size", "0.06", "--strain-rate", "0.5", "--threads", "1", "--no-progress",
            "--snapshots", "2e-4", "--out", str(out))
    assert r.returncode == 0, r.stderr
    # -noreset: Xvfb resets when its last client leaves, and a client that
    # connects meanwhile is refused (pvbatch aborts: "bad X server connection").
    r = subprocess.run(["xvfb-run", "-a", "-s", "-noreset -screen 0 1280x1024x24", "pvbatch",
                        os.path.join(ROOT, "scripts", "paraview_crack.py"), str(out)],
                       capture_output=True, text=True, timeout=300, env=subprocess_env(), cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert f"wrote {out / 'crack_paraview.png'}" in r.stdout
    rgb = picture(out / "crack_paraview.png")
    # The study's colours as ParaView draws them: undamaged bars cyan, the broken ones red.
    assert colour_share(rgb, (0.0, 1.0, 1.0)) > 0.002 and colour_share(rgb, (1.0, 0.0, 0.0)) > 0.002
    # The title (the run, its mean strain, the warp factor), white text in the band above the specimen.
    assert colour_share(rgb[:rgb.shape[0] // 12], (1.0, 1.0, 1.0)) > 0.005  # measured 0.02 on a 0.12 m cube
