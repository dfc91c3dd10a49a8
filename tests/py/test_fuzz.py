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
