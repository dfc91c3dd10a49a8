"""Fuzz the command line: random and malformed flags and values (a fixed seed,
a fixed number of examples) through `ldem cube`'s own entry point. Whatever
comes in, the answer is exit 0 (a run, with a done summary), 1 (a run flagged
or failed, its summary saying so) or 2 (one line naming the problem): never a
traceback, a hang or a summary claiming success for a failed run."""
import json
import random

import pytest

from ldem import cli

FLAGS = ["--size", "--L0", "--E", "--nu", "--rho", "--Gf-mean", "--Gf-cv", "--corr-length", "--Gf-draw", "--eps-p",
         "--c-a", "--load", "--strain-rate", "--ramp-time", "--top-lateral", "--bottom-lateral", "--loss-speedup",
         "--seed", "--zeta", "--stop-at", "--dt", "--dt-safety", "--stop-fraction", "--split-window",
         "--energy-tolerance", "--record-every", "--threads", "--figure-format", "--snapshots", "--bogus"]
VALUES = ["0", "-1", "1e300", "-1e-300", "nan", "inf", "0.5", "0.04", "0.06", "0.02", "abc", "", "1,2", "3",
          "module", "free", "triangular", "1e-9", "99999999999", "0.25", "2e-4", "svg", "--", "1e5"]


def _case(rng):
    args = ["--size", "0.04", "--strain-rate", "0.5", "--stop-at", "load_loss", "--final-strain", "3e-4"]
    for _ in range(rng.randint(1, 4)):
        flag = rng.choice(FLAGS)
        args += [flag] if rng.random() < 0.1 else [flag, rng.choice(VALUES)]
    return args


@pytest.mark.parametrize("k", range(60))
def test_random_flags_never_traceback(k, tmp_path, capsys):
    rng = random.Random(1000 + k)
    args = ["cube", *_case(rng), "--out", str(tmp_path / "o"), "--no-progress", "--no-plots"]
    try:
        code = cli.main(args)
    except SystemExit as e:  # argparse: malformed flags
        code = e.code
    out, err = capsys.readouterr()
    assert "Traceback" not in err and "Traceback" not in out, (args, err)
    assert code in (0, 1, 2), (args, code, err)
    if code == 2:
        assert len(err.strip().splitlines()) == 1, (args, err)
    summary = tmp_path / "o" / "summary.json"
    if summary.exists():
        s = json.loads(summary.read_text())
        flagged = code == 1 and s.get("energy_error") is True  # done, but its energy balance is off: exit 1
        assert (s["status"] == "done") == (code == 0 or flagged), (args, code, s["status"], err)


# A small specimen file (a 2 x 2 x 2 cube pulled fast) and the ways to break it.
SPECIMEN = """title = "fuzz"
[shape]
kind = "box"
L0 = 0.02
size = [0.04, 0.04, 0.04]
[groups.bottom]
face = "z-"
fix = ["x", "y", "z"]
[groups.top]
face = "z+"
drive = {z = 1.0}
fix = ["x", "y"]
[measure]
support = "bottom"
loaded = "top"
area = 0.0016
gauge_length = 0.04
probes = {tip = {b = [0.04, 0.04, 0.04], direction = "z"}}
[loading]
strain_rate = 0.5
[run]
stop_at = "load_loss"
final_strain = 3e-4
"""
TOML_VALUES = ["0", "-1", "1e300", "nan", "inf", '"x"', '"z-"', '"cylinder"', "[]", "[1, 2, 3]", "{}", "{z = 1.0}",
               "true", '"dogbone"', "0.02", '["x", "q"]', "[0.0, 0.0, 0.0]", '"bottom"', "{a = [0, 0, 0]}", '"']
TOML_KEYS = ["kind", "L0", "size", "notch", "face", "plane", "box", "point", "union", "fix", "drive", "linear",
             "support", "loaded", "area", "gauge_length", "probes", "seed", "zeta", "nu", "strain_rate", "bogus",
             "diameter", "axis", "neck", "radius", "file", "title"]


def _mutate(rng) -> str:
    lines = SPECIMEN.splitlines()
    for _ in range(rng.randint(1, 3)):
        if not lines:
            break
        i = rng.randrange(len(lines))
        op = rng.randrange(5)
        if op == 0:  # a value replaced
            if "=" in lines[i]:
                lines[i] = lines[i].split("=")[0] + "= " + rng.choice(TOML_VALUES)
        elif op == 1:  # a line dropped
            del lines[i]
        elif op == 2:  # a key added
            lines.insert(i + 1, f"{rng.choice(TOML_KEYS)} = {rng.choice(TOML_VALUES)}")
        elif op == 3:  # a line doubled (a key twice, a table twice)
            lines.insert(i, lines[i])
        else:  # the file cut
            lines = lines[:i]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("k", range(60))
def test_random_specimen_files_never_traceback(k, tmp_path, capsys):
    rng = random.Random(5000 + k)
    path = tmp_path / "s.toml"
    path.write_text(_mutate(rng))
    args = ["run", str(path), "--out", str(tmp_path / "o"), "--no-progress", "--no-plots", "--set", "threads=1"]
    try:
        code = cli.main(args)
    except SystemExit as e:
        code = e.code
    out, err = capsys.readouterr()
    text = path.read_text()
    assert "Traceback" not in err and "Traceback" not in out, (text, err)
    assert code in (0, 1, 2), (text, code, err)
    if code == 2:
        assert len(err.strip().splitlines()) == 1 and str(path) in err, (text, err)
    summary = tmp_path / "o" / "summary.json"
    if summary.exists():
        s = json.loads(summary.read_text())
        assert (s["status"] == "done") == (code == 0 or (code == 1 and s.get("energy_error") is True)), (text, s)
