"""Studies of any test object: a series of tiny beams (ldem.SpecimenTest) runs,
resumes and is named as the cubes' do; the beam study's own cases (Beam:
a SpecimenTest stopped past its peak) keep the folders of the committed
results; the ablation's table reads the committed runs."""
import copy
import json
import os

import pytest

import ldem
from conftest import ROOT
from ldem import study
from ldem.study import ablation
from ldem.study.beams import cases as beams


def tiny_beam(seed: int, notch: float = 0.5) -> ldem.SpecimenTest:
    """A 20 mm deep beam of the series, driven fast: a few seconds a run."""
    d = copy.deepcopy(beams.beam(0.02, notch, 1e-4, seed).description)
    d["loading"]["strain_rate"] = 2.0
    d["run"]["final_strain"] = 2e-3
    return ldem.SpecimenTest(d)


def test_a_study_of_specimens_runs_resumes_and_never_recomputes(tmp_path):
    out = str(tmp_path / "st")
    tests = [tiny_beam(1), tiny_beam(2)]
    first = study.run_cases(tests, out, jobs=2, log=lambda s: None)  # in two worker processes
    assert [s["status"] for s in first] == ["done", "done"]
    assert first[0]["peak_stress_MPa"] != first[1]["peak_stress_MPa"]  # two random fields
    names = [study.case_name(t) for t in tests]
    assert names[0].startswith("s1_") and names[1].startswith("s2_") and names[0][3:] != names[1][3:]
    dirs = [study.case_dir(out, t) for t in tests]
    for d in dirs:
        assert set(os.listdir(d)) == {"curve.csv", "summary.json", "slice.npz", "cracks.png"}
    stamp = [os.path.getmtime(os.path.join(d, "summary.json")) for d in dirs]
    # Threads do not change the result: the same case.
    again_tests = [tiny_beam(1), tiny_beam(2)]
    again_tests[0].description["run"]["threads"] = 2
    ran = []
    again = study.run_cases([ldem.SpecimenTest(again_tests[0].description), tests[1]], out, log=ran.append)
    assert ran == [f"2 of 2 cases already finished in {out}/cases"]
    assert again == first and [os.path.getmtime(os.path.join(d, "summary.json")) for d in dirs] == stamp
    # A case whose last file is missing runs again, the same run.
    os.remove(os.path.join(dirs[1], "slice.npz"))
    ran = []
    again = study.run_cases(tests, out, log=ran.append)
    assert ran[:2] == [f"1 of 2 cases already finished in {out}/cases",
                       f"  {names[1]}: no loadable slice.npz: running it again"]
    assert again[1]["peak_stress_MPa"] == first[1]["peak_stress_MPa"]
    # A parameter declared after a case ran counts at its default (the run it made): the case is finished.
    path = os.path.join(dirs[0], "summary.json")
    summary = json.load(open(path))
    del summary["parameters"]["parameters"]["drive_velocity"]
    json.dump(summary, open(path, "w"))
    assert study.cases.unfinished_reason(dirs[0], tests[0]) is None
    summary["parameters"]["parameters"]["E"] *= 1.01  # a parameter of another value is another run
    json.dump(summary, open(path, "w"))
    assert study.cases.unfinished_reason(dirs[0], tests[0]) == "other parameters"


def test_a_study_says_each_peak_in_its_specimen_s_unit(tmp_path):
    """The line a finished case logs gives the peak in the unit of the specimen's stress_label
    (the L-panel's study said "peak 0.0071 MPa" of a load of 7.1 kN, in MN)."""
    d = tiny_beam(1).description
    d["measure"]["stress_label"] = "F/(bD) [N/mm2]"
    ran = []
    [s] = study.run_cases([ldem.SpecimenTest(d)], str(tmp_path / "u"), log=ran.append)
    assert f": peak {s['peak_stress_MPa']:.5g} N/mm2 at {s['strain_at_peak']:.4e}, " in ran[-1], ran


def test_another_specimen_is_another_case():
    assert study.case_name(tiny_beam(1)) != study.case_name(tiny_beam(1, notch=0.2))
    assert study.case_name(tiny_beam(1)) == study.case_name(tiny_beam(1))


def test_the_beam_study_keeps_the_committed_folders():
    b = beams.Beam(0.1, 0.2, 1e-4, 3)
    assert study.case_dir("out", b) == os.path.join("out", "cases", "D100_n0.2_s3")
    assert study.case_dir("out", beams.Beam(0.05, 0.0, 1e-4, 1, gf_cv=0.0)) == \
        os.path.join("out", "cases_cv0", "D50_n0_s1")
    assert b.writers == ["curve", "summary"] and beams.Beam(0.1, 0.2, 1e-4, 1).writers[2:] == ["figures", "vtk"]
    series = beams.series_tests(1e-4, 2)
    assert len(series) == 18 and [t.seed for t in series] == [1] * 9 + [2] * 9  # seed by seed


def test_past_the_peak_stops_a_beam_and_counts_the_rows_before_a_restart():
    rows = [{"stress_MPa": s, "stress_top_MPa": s, "mean_strain": e} for s, e in ((1.0, 1.0), (2.0, 2.0), (1.5, 3.0))]
    stop = beams.PastThePeak(rows)
    assert (stop.peak, stop.at) == (2.0, 2.0)
    assert stop({"stress_MPa": 1.1, "stress_top_MPa": 1.1, "mean_strain": 4.5}) is True   # past twice the peak's deflection, above half
    assert stop({"stress_MPa": 0.9, "stress_top_MPa": 0.9, "mean_strain": 4.5}) is False  # below half the peak: stop
    further = beams.PastThePeak(rows, beyond=4.0)  # the L-panel's: to 4 times the peak's displacement
    assert further({"stress_MPa": 0.9, "stress_top_MPa": 0.9, "mean_strain": 7.9}) is True
    assert further({"stress_MPa": 0.9, "stress_top_MPa": 0.9, "mean_strain": 8.1}) is False


def test_past_the_peak_waits_for_the_supports_to_carry_the_push():
    """The L-panel's first rows: the push is a wave that has not reached the
    supports (their reaction 0, then -1e-41, then a flicker of 1e-9 that falls
    back at twice its deflection): not a peak passed while the supports carry
    less than half the push."""
    stop = beams.PastThePeak()
    wave = [(0.0, 0.0, 0.0), (0.0, 1e-8, 1e-11), (-1e-41, 8e-8, 9e-11), (1e-9, 2e-7, 2e-10), (1e-12, 3e-7, 3e-10),
            (1e-12, 4e-7, 5e-10)]
    assert all(stop({"stress_MPa": s, "stress_top_MPa": t, "mean_strain": e}) for s, t, e in wave)
    assert stop({"stress_MPa": 1.0, "stress_top_MPa": 1.0, "mean_strain": 1.0})
    assert stop({"stress_MPa": 0.4, "stress_top_MPa": 0.4, "mean_strain": 2.5}) is False


def test_the_ablation_table_reads_the_committed_runs():
    path = os.path.join(ROOT, "results", "ablation", "peak_ablation_0.48m_seeds1-3.jsonl")
    runs = ablation.read_runs(path)
    table = ablation.ablation_table(runs).splitlines()
    base = [r for r in runs if r["load"] == "uniform" and r["variant"] == "base"]
    mean = sum(r["peak_MPa"] for r in base) / len(base)
    assert table[2].startswith(f"| uniform | base | {len(base)} | {mean:.4f} | +0.0 % |")
    assert len(table) == 2 + len({(r["load"], r["variant"]) for r in runs})


def test_an_ablation_case_is_its_cube_s_case():
    t, = ablation.ablation_tests(0.04, [2], 1, [("uniform", "rollers")])
    assert study.case_name(t) == study.case_name(t.cube) == \
        "uniform_0.04m_s2_bottom_lateralfree_stop_atload_loss_final_strain0.0003"


def test_the_ablation_study_writes_its_runs_and_table(tmp_path):
    tests = [ablation.AblationCube(v, size=0.04, load="uniform", seed=1, threads=1, strain_rate=0.1,
                                   stop_at="load_loss", **ablation.VARIANTS[v]) for v in ("base", "rollers")]
    runs = ablation.run_ablation(tests, str(tmp_path), log=lambda s: None)
    assert [r["variant"] for r in runs] == ["base", "rollers"]
    assert ablation.read_runs(str(tmp_path / "ablation.jsonl")) == runs
    assert (tmp_path / "ablation.md").read_text() == ablation.ablation_table(runs)
    # The rollers free the lower face's lateral motion: a stronger cube, as in the committed runs.
    assert runs[1]["peak_MPa"] > runs[0]["peak_MPa"]
    assert 0 < runs[0]["damaged_at_peak"] and 0 < runs[0]["hurt_mean_height"] < 1

