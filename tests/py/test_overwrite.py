"""A finished run is never replaced without a word: `ldem cube` and `ldem run`
into a folder that holds one refuse other parameters (exit 2, one line naming
them), run nothing for the same parameters (exit 0), and replace it with
--overwrite."""
import json
import os

import pytest

from conftest import ROOT

TINY = ["--size", "0.04", "--stop-at", "past_peak", "--no-plots", "--no-progress", "--threads", "1"]


def _one_line_exit_2(r, message):
    assert r.returncode == 2, (r.stdout, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and message in lines[0], r.stderr
    assert "Traceback" not in r.stderr


def _stamps(out):
    """Every file of the folder with its modification time and bytes."""
    return {name: (os.stat(out / name).st_mtime_ns, (out / name).read_bytes()) for name in sorted(os.listdir(out))}


@pytest.fixture(scope="module")
def seed1(tmp_path_factory):
    """A finished seed-1 cube: copied by each test, so each finds the same folder."""
    from conftest import run_cli

    out = tmp_path_factory.mktemp("seed1") / "x"
    r = run_cli("cube", *TINY, "--seed", "1", "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert json.loads((out / "summary.json").read_text())["status"] == "done"
    return out


def _copy(src, dst):
    import shutil

    shutil.copytree(src, dst)
    return dst


def test_other_parameters_are_refused_naming_them(cli, tmp_path, seed1):
    out = _copy(seed1, tmp_path / "x")
    before = _stamps(out)
    r = cli("cube", *TINY, "--seed", "2", "--out", str(out))
    _one_line_exit_2(r, f"ldem cube: error: {out} holds a finished run of other parameters (seed 1, not 2): "
                        "give another --out, or --overwrite")
    assert r.stdout == ""
    assert _stamps(out) == before
    r = cli("cube", *TINY, "--seed", "2", "--zeta", "0.05", "--out", str(out))  # each difference named
    _one_line_exit_2(r, "(seed 1, not 2; zeta 0.02, not 0.05)")


def test_the_same_parameters_run_nothing(cli, tmp_path, seed1):
    out = _copy(seed1, tmp_path / "x")
    before = _stamps(out)
    r = cli("cube", *TINY, "--seed", "1", "--threads", "2", "--out", str(out))  # threads change no result
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == f"{out} is a finished run (summary.json: done) of the same parameters: nothing to run " \
                               f"(--overwrite runs it again); to take it further: ldem cube --restart {out} --extend STRAIN"
    assert r.stderr == ""
    assert _stamps(out) == before


def test_overwrite_runs_again(cli, tmp_path, seed1):
    out = _copy(seed1, tmp_path / "x")
    old = json.loads((out / "summary.json").read_text())
    r = cli("cube", *TINY, "--seed", "2", "--out", str(out), "--overwrite")
    assert r.returncode == 0, r.stderr
    new = json.loads((out / "summary.json").read_text())
    assert new["status"] == "done" and new["parameters"]["seed"] == 2 and old["parameters"]["seed"] == 1
    assert new["peak_stress_MPa"] != old["peak_stress_MPa"]
    before = _stamps(out)
    r = cli("cube", *TINY, "--seed", "2", "--out", str(out), "--overwrite")  # the same parameters: run again
    assert r.returncode == 0, r.stderr
    assert "peak normal stress" in r.stdout and "nothing to run" not in r.stdout
    assert os.stat(out / "summary.json").st_mtime_ns > before["summary.json"][0]
    assert json.loads((out / "summary.json").read_text())["peak_stress_MPa"] == new["peak_stress_MPa"]


def test_a_folder_without_a_finished_run_is_written(cli, tmp_path, seed1):
    """An interrupted or failed run's folder (summary.json not done) is run into as before."""
    out = _copy(seed1, tmp_path / "x")
    s = json.loads((out / "summary.json").read_text())
    (out / "summary.json").write_text(json.dumps({**s, "status": "interrupted"}))
    r = cli("cube", *TINY, "--seed", "2", "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert json.loads((out / "summary.json").read_text())["parameters"]["seed"] == 2


def test_overwrite_and_restart_are_not_given_together(cli, tmp_path, seed1):
    out = _copy(seed1, tmp_path / "x")
    _one_line_exit_2(cli("cube", "--restart", str(out), "--overwrite"),
                     "--overwrite runs afresh and --restart continues: give one of them")


def _small_cube_file(tmp_path):
    text = open(os.path.join(ROOT, "examples", "cube_uniform.toml")).read()
    text = (text.replace("size = [0.12, 0.12, 0.12]", "size = [0.04, 0.04, 0.04]")
            .replace("area = 0.0144 ", "area = 0.0016 ").replace("gauge_length = 0.12 ", "gauge_length = 0.04 ")
            .replace("ligament = 0.0144 ", "ligament = 0.0016 "))
    assert "0.04, 0.04, 0.04" in text
    path = tmp_path / "small.toml"
    path.write_text(text)
    return str(path)


def test_ldem_run_the_same(cli, tmp_path):
    """ldem run: --set's parameters and the file's own keys are named; the cube's folder is not a file's run."""
    path = _small_cube_file(tmp_path)
    out = tmp_path / "r"
    common = ["--set", "stop_at=past_peak", "--threads", "1", "--no-plots", "--no-progress", "--out", str(out)]
    r = cli("run", path, *common)
    assert r.returncode == 0, r.stderr
    before = _stamps(out)
    r = cli("run", path, *common)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith(f"{out} is a finished run (summary.json: done) of the same parameters: nothing to run")
    assert _stamps(out) == before
    _one_line_exit_2(cli("run", path, *common, "--set", "seed=2"),
                     f"ldem run: error: {out} holds a finished run of other parameters (seed 1, not 2): "
                     "give another --out, or --overwrite")
    with open(path) as f:
        text = f.read()
    with open(path, "w") as f:
        f.write(text.replace("[0.04, 0.04, 0.04]", "[0.04, 0.04, 0.06]"))
    _one_line_exit_2(cli("run", path, *common), 'of other parameters (shape.size[2] 0.04, not 0.06')
    with open(path, "w") as f:
        f.write(text)
    _one_line_exit_2(cli("cube", *TINY, "--out", str(out)), "of other parameters (a specimen file's, not a cube's)")
    assert _stamps(out) == before
    r = cli("run", path, *common, "--set", "seed=2", "--overwrite")
    assert r.returncode == 0, r.stderr
    assert json.loads((out / "summary.json").read_text())["parameters"]["parameters"]["seed"] == 2
