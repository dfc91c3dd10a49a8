"""`ldem study criteria`: the five specimens' runs at their rate and a quarter
of it, and the table that judges them (ldem.study.criteria)."""
import csv
import json
import os

import pytest

from conftest import ROOT
from ldem.study import criteria as study


def test_each_specimen_runs_at_its_drive_and_a_quarter_of_its_rate():
    by = {s.name: s for s in study.SPECIMENS}
    cube, quarter = by["cube_uniform"].test(ROOT, 2, 1.0, {}), by["cube_uniform"].test(ROOT, 2, 0.25, {})
    assert (cube.size, cube.seed, cube.stop_at) == (0.48, 2, "load_loss")
    assert quarter.strain_rate == pytest.approx(cube.strain_rate / 4)
    for name in ("d50_beam", "eccentric_beam", "l_panel"):
        at, q = by[name].test(ROOT, 3, 1.0, {}), by[name].test(ROOT, 3, 0.25, {})
        assert at.build.params["rate_periods"] == study.RULE_PERIODS == 12  # rule (c)
        assert q.build.params["rate_periods"] == 48 and q.seed == at.seed == 3
    assert by["eccentric_beam"].test(ROOT, 1, 1.0, {}).final_strain == 9e-4  # past its peak at 4.2e-4
    runs = study.cases(study.plan([by["l_panel"]], 1), ROOT, {}, periods=3)  # --rate-periods 3
    assert [t.build.params["rate_periods"] for t in runs] == [3, 12]


def test_a_small_cube_s_rate_effect_is_read_from_its_two_runs(tmp_path):
    """The 0.12 m uniform cube, one seed: (b) is each value's ratio minus one, not judged on one pair;
    its peak moves by less than 1 % at a quarter of the rate (the cube's paced drive)."""
    cube = study.Specimen("cube_uniform", "0.12 m cube, uniform", size=0.12)
    text = study.run_criteria(str(tmp_path), ROOT, seeds=1, specimens=[cube], log=lambda s: None)
    rows = {r["rate"]: r for r in csv.DictReader(open(tmp_path / "criteria.csv"))}
    assert set(rows) == {"rate", "quarter"}
    s = {r: json.load(open(tmp_path / "cases" / f"cube_uniform_{r}_s1" / "summary.json")) for r in rows}
    assert s["quarter"]["steps"] > 3 * s["rate"]["steps"]  # the quarter rate runs longer to its load loss
    peak = s["rate"]["peak_stress_MPa"] / s["quarter"]["peak_stress_MPa"] - 1
    energy = (s["rate"]["load_loss"]["fracture_energy_J"] / s["quarter"]["load_loss"]["fracture_energy_J"] - 1)
    assert abs(peak) < 0.01
    assert f"{100 * energy:+.2f} %, not judged" in text and f"{100 * peak:+.2f} %, not judged" in text
    assert float(rows["rate"]["energy_J"]) == pytest.approx(s["rate"]["load_loss"]["fracture_energy_J"], rel=1e-5)
    assert os.path.isfile(tmp_path / "criteria.md")


def test_the_study_refuses_to_let_set_change_what_it_sets(capsys):
    from ldem.cli import main

    assert main(["study", "criteria", "--set", "rate_periods=5", "--out", "/nonexistent/x"]) == 2
    assert "the study sets it" in capsys.readouterr().err
    assert main(["study", "criteria", "--rate-periods", "0", "--out", "/nonexistent/x"]) == 2
    assert "--rate-periods must be positive (got 0.0)" in capsys.readouterr().err
    # Run outside the checkout without --root: the files are not found, and the message says what to do.
    assert main(["study", "criteria", "--root", "/nonexistent", "--specimens", "d50_beam", "--out", "/nonexistent/x"]) == 2
    assert "no such file: run from the ldem checkout, or give its folder as --root" in capsys.readouterr().err
