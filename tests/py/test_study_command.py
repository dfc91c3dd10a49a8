"""`ldem study` (issue 38 item 3): the registered studies listed a line each,
their options from the parameter table, and the studies that were scripts
(ablation, validation; calibration: test_calibration.py) run through
`ldem study NAME` on the small settings of their module's tests."""
import ast
import json
import os
import shutil

import pytest

import ldem
from conftest import ROOT
from ldem.cli import build_parser
from ldem.study import ablation, options, validation
from ldem.study.cases import case_name
from ldem.study.registry import STUDIES

LOADS = next(p["choices"] for p in ldem._core.parameter_table() if p["name"] == "load")


def help_text(capsys, *command) -> str:
    """`ldem *command --help`, in this process, its spaces and line breaks made single spaces."""
    with pytest.raises(SystemExit) as e:
        build_parser().parse_args([*command, "--help"])
    assert e.value.code == 0
    return " ".join(capsys.readouterr().out.split())


def test_ldem_study_lists_every_registered_study_with_its_line(cli):
    r = cli("study")
    assert r.returncode == 0, r.stderr
    listed = r.stdout.splitlines()[1:]
    assert [line.split()[0] for line in listed] == list(STUDIES)
    assert all(" ".join(line.split()[1:]) == " ".join(STUDIES[line.split()[0]].line.split()) for line in listed)
    # the studies that were scripts are here, beside those that were already commands
    assert {"size-effect", "damping", "mesh", "refinement", "beams", "ablation", "validation",
            "calibration", "fracture-energy", "seed-settings", "criteria"} == set(STUDIES)


@pytest.mark.parametrize("name", [n for n in STUDIES if n not in ("refinement", "beams", "calibration",
                                                                   "validation", "fracture-energy", "seed-settings",
                                                                   "criteria")])
def test_the_load_choices_are_the_parameter_tables(capsys, name):
    """A study's --loads takes the choices of the parameter `load`, all of them
    by default (refinement: uniform only), and says which they are."""
    text = help_text(capsys, "study", name)
    assert f"--loads LOADS comma-separated loads, of: {', '.join(LOADS)} " \
        f"(default: {','.join(LOADS)})" in text, text
    assert options.parse_loads(",".join(LOADS)) == LOADS
    with pytest.raises(ValueError, match=f"unknown load 'shear' \\(expected {' or '.join(LOADS)}\\)"):
        options.parse_loads("uniform,shear")


def test_a_studys_parameter_options_are_the_tables(capsys, cli):
    """--strain-rate, --size, --seed, --zetas: the parameter's help, unit,
    domain and type from the table; the study's default where it has its own."""
    rows = {p["name"]: p for p in ldem._core.parameter_table()}
    text = help_text(capsys, "study", "damping")
    for flag, name, default in (("--strain-rate STRAIN_RATE", "strain_rate", "0.02"), ("--size SIZE", "size", "0.96"),
                                ("--seed SEED", "seed", "1")):
        p = rows[name]
        unit = f" [{p['unit']}]" if p["unit"] else ""
        assert f"{flag} {p['help']}{unit}; {p['domain']} (default: {default})" in text, (flag, text)
    z = rows["zeta"]  # --zetas: several values of the parameter zeta
    assert f"--zetas ZETAS comma-separated values of zeta, {z['help']}; each {z['domain']} (above 1: overcritical) " \
        "(default: 0.02,2)" in text, text
    assert cli("study", "damping", "--out", "x", "--seed", "1.5").returncode == 2  # an int, as the table says


def test_the_ablation_runs_as_a_study_command(tmp_path, cli):
    """The 0.04 m cube, one seed, two variants of the uniform load: the same
    cases as ldem.study.ablation builds, one JSON line per run printed and in
    ablation.jsonl, then the table (ablation.md)."""
    out = tmp_path / "ablation"
    r = cli("study", "ablation", "--out", str(out), "--size", "0.04", "--seeds", "1", "--loads", "uniform",
            "--variants", "base,rollers", "--threads", "1")
    assert r.returncode == 0, r.stderr
    runs = ablation.read_runs(str(out / "ablation.jsonl"))
    assert [(x["load"], x["variant"], x["seed"]) for x in runs] == [("uniform", "base", 1), ("uniform", "rollers", 1)]
    assert r.stdout == "".join(json.dumps(x) + "\n" for x in runs) + (out / "ablation.md").read_text()
    assert (out / "ablation.md").read_text() == ablation.ablation_table(runs)
    expected = [case_name(t.cube) for t in ablation.ablation_tests(0.04, [1], 1, [("uniform", "base"),
                                                                               ("uniform", "rollers")])]
    assert sorted(os.listdir(out / "cases")) == sorted(expected)
    assert all(x["peak_MPa"] > 0 and x["energy_error"] < 1e-2 for x in runs)


def test_the_ablation_table_of_committed_runs(cli):
    path = os.path.join(ROOT, "results", "ablation", "peak_ablation_0.48m_seeds1-3.jsonl")
    r = cli("study", "ablation", "--table", path)
    assert r.returncode == 0 and r.stdout == ablation.ablation_table(ablation.read_runs(path))
    r = cli("study", "ablation", "--size", "0.04")
    assert r.returncode == 2 and "--out DIR" in r.stderr


def test_a_blind_prediction_runs_as_a_study_command(tmp_path, cli):
    """`ldem study validation l_panel` on a repository (--root) whose
    specimen file is test_validation's coarse L-panel, with the committed
    calibration in its folder (so no prism runs): the seeds' runs with that
    material, predictions.csv from them, the row printed."""
    root = tmp_path / "repo"
    (root / "examples").mkdir(parents=True)
    text = open(os.path.join(ROOT, validation.SPECIMENS["l_panel"].file)).read()
    assert "L0 = 0.01\n" in text and "rate_periods = 12 " in text and "final_strain = 0.002 " in text
    text = text.replace("L0 = 0.01\n", "L0 = 0.025\n").replace("rate_periods = 12 ", "strain_rate = 1.0 ")
    (root / "examples" / "l_panel.toml").write_text(text.replace("final_strain = 0.002 ", "final_strain = 5e-4 "))
    out = tmp_path / "l_panel"
    out.mkdir()
    shutil.copy(os.path.join(ROOT, "results", "validation", "l_panel", "material.json"), out / "material.json")
    material = json.loads((out / "material.json").read_text())["material"]
    r = cli("study", "validation", "l_panel", "--root", str(root), "--out", str(out), "--seeds", "2")
    assert r.returncode == 0, r.stderr
    peaks = []
    for seed in (1, 2):
        s = json.loads((out / "cases" / f"s{seed}" / "summary.json").read_text())
        assert s["parameters"]["parameters"]["E"] == material["E"] and s["parameters"]["parameters"]["L0"] == 0.025
        peaks.append(s["peak_stress_MPa"] * 1e3)
    row, = ldem.study.read_csv(str(out / "predictions.csv"))
    assert float(row["peak_load_kN"]) == pytest.approx(sum(peaks) / 2, rel=1e-5) and float(row["seeds"]) == 2
    printed = ast.literal_eval(r.stdout.splitlines()[-1])
    assert printed["specimen"] == "l_panel" and printed["peak_load_kN"] == pytest.approx(sum(peaks) / 2, rel=1e-12)
