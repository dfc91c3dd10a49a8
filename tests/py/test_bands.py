"""A prediction's input band and the module a specimen needs (ldem.study.bands,
ldem.study.validation.band, ldem.module_rule, ldem.study.beams.convergence):
the Latin hypercube's marginals are the stated distributions and the same
seed gives the same design; the band of a peak linear in f_t is the normal's;
the inputs and their sources; the rule's warning for a coarse notched beam and
its silence for a fine one; a band of the smallest validation specimen, coarse."""
import dataclasses
import json
import math
import os

import numpy as np
import pytest
from scipy import stats

import ldem
from conftest import ROOT, picture
from ldem import module_rule
from ldem.run_command import warn_module
from ldem.study import bands, validation
from ldem.study.beams import convergence as beam_convergence
from ldem.study.validation import band as validation_band
from ldem.study.mc2010 import mc2010_from_compressive_strength

E = bands.Scatter("E", 30e9, 0.05, "a test's")
F_T = bands.Scatter("f_t", 3.0e6, bands.cv_of_fractiles(0.7, 1.3), "MC2010's fractiles of f_ctm")
G_F = bands.Scatter("G_F", 120.0, 0.15, "a test's")
INPUTS = [E, F_T, G_F]


@pytest.mark.direct
def test_mc2010_s_fractiles_of_f_ctm_make_a_cv_of_0_182():
    assert bands.cv_of_fractiles(0.7, 1.3) == pytest.approx(0.3 / 1.6448536269514722, rel=1e-12)
    assert F_T.ppf(0.05) == pytest.approx(0.7 * F_T.mean, rel=1e-12)  # the stated fractiles, back
    assert F_T.ppf(0.95) == pytest.approx(1.3 * F_T.mean, rel=1e-12)
    with pytest.raises(ValueError, match="not symmetric"):
        bands.cv_of_fractiles(0.8, 1.3)


@pytest.mark.direct
@pytest.mark.parametrize("n", [12, 200])
def test_the_design_s_marginals_are_the_stated_distributions(n):
    """Kolmogorov-Smirnov at the 5 % level, each input against its normal; each
    stratum of probability 1/n holds one point (so the KS distance is at most
    1/n); a normal of twice the sd is refused at 200 points (the check sees
    a wrong distribution)."""
    x = bands.design(INPUTS, n, seed=3)
    assert x.shape == (n, 3)
    for k, s in enumerate(INPUTS):
        r = stats.kstest(x[:, k], s.cdf)
        assert r.pvalue > 0.05 and r.statistic <= 1 / n + 1e-12, (s.name, r)
        assert sorted(np.floor(s.cdf(x[:, k]) * n).astype(int)) == list(range(n))
        if n == 200:
            wide = dataclasses.replace(s, cv=2 * s.cv)
            assert stats.kstest(x[:, k], wide.cdf).pvalue < 0.05, s.name


@pytest.mark.direct
def test_the_same_seed_gives_the_same_design():
    a, b = bands.design(INPUTS, 12, seed=70), bands.design(INPUTS, 12, seed=70)
    assert np.array_equal(a, b)
    assert not np.allclose(a, bands.design(INPUTS, 12, seed=71))


@pytest.mark.direct
def test_the_band_of_a_peak_linear_in_f_t_is_the_normal_s():
    """peak = 2 kN + 1.5e-6 f_t [Pa] at the points (E and G_F play no part).
    With no seed spread the band is the peak at f_t's own 5 and 95 % fractiles,
    0.7 and 1.3 f_ctm, all of it f_t's; with the seeds' sd s it is the mean
    -+ 1.645 sqrt((1.5e-6 sd_f_t)^2 + s^2), each part its share."""
    x = bands.design(INPUTS, 12, seed=5)
    y = 2.0 + 1.5e-6 * x[:, 1]
    at_mean = 2.0 + 1.5e-6 * F_T.mean
    b = bands.band(INPUTS, x, y, [at_mean] * 6)
    assert b["mean"] == pytest.approx(at_mean, rel=1e-12)
    assert b["low"] == pytest.approx(2.0 + 1.5e-6 * 0.7 * F_T.mean, rel=1e-9)
    assert b["high"] == pytest.approx(2.0 + 1.5e-6 * 1.3 * F_T.mean, rel=1e-9)
    assert b["shares"]["f_t"] == pytest.approx(1.0, abs=1e-12) and b["shares"]["seeds"] == 0.0
    assert b["centre"] == pytest.approx(at_mean, rel=1e-12) and b["residual"] < 1e-9 * at_mean

    seeds = at_mean + np.array([-0.1, 0.05, 0.05, 0.1, -0.05, -0.05])
    b = bands.band(INPUTS, x, y, seeds)
    sd_in, sd_s = 1.5e-6 * F_T.sd, float(np.std(seeds, ddof=1))
    half = 1.6448536269514722 * math.hypot(sd_in, sd_s)
    assert (b["low"], b["high"]) == pytest.approx((at_mean - half, at_mean + half), rel=1e-9)
    assert b["shares"]["seeds"] == pytest.approx(sd_s ** 2 / (sd_in ** 2 + sd_s ** 2), rel=1e-9)
    assert b["shares"]["E"] < 1e-20 and b["shares"]["G_F"] < 1e-20

    y[:8] = np.nan  # points that never reached the quantity are left out: 4 are too few for 3 inputs
    assert bands.band(INPUTS, x, y, seeds) == {"points": 4}


@pytest.mark.direct
def test_each_input_says_its_distribution_and_source():
    """From f_c alone: fib MC2010's E, f_ctm and G_F with their scatter; given:
    the stated defaults; a source's own scatter over both."""
    mc = mc2010_from_compressive_strength(29e6)
    drawn = {s.name: s for s in validation_band.inputs({"f_c": 29e6})}
    for k in ("E", "f_t", "G_F"):
        assert drawn[k].mean == pytest.approx(mc[k], rel=1e-12) and drawn[k].source.startswith("fib MC2010 eq. 5.1-")
    assert drawn["f_t"].cv == pytest.approx(0.18238, abs=1e-5) and "0.7 f_ctm" in drawn["f_t"].source
    assert drawn["E"].cv == pytest.approx(0.2 / 1.6448536269514722) and "stated default" in drawn["E"].source
    assert "no fractiles" in drawn["G_F"].source
    lab = validation.SPECIMENS["l_panel"].lab
    given = validation_band.inputs(lab, {"G_F": (0.2, "a paper's")})
    assert [(s.mean, s.cv) for s in given] == [(lab["E"], 0.05), (lab["f_t"], 0.10), (lab["G_F"], 0.2)]
    assert given[0].source.startswith("given") and given[2].source == "a paper's"


def _beam(L0=0.01, notch=0.02) -> ldem.SpecimenTest:
    test = ldem.SpecimenTest.from_file(os.path.join(ROOT, "examples", "beam_3pb.toml"))
    d = json.loads(json.dumps(test.description))
    d["shape"].update(L0=L0, notch=dict(d["shape"]["notch"], depth=notch))
    return ldem.SpecimenTest(d)


@pytest.mark.direct
def test_the_bar_count_is_the_lattice_s():
    """module_rule.bar_count from the modules alone: a notched beam's and the L-panel's (a cutout) lattices."""
    panel = ldem.SpecimenTest.from_file(os.path.join(ROOT, "examples", "l_panel.toml"))
    assert module_rule.bar_count(panel.build.mask) == 265485  # results/validation/l_panel/README.md
    beam = _beam()
    assert module_rule.bar_count(beam.build.mask) == beam.simulation().total_bars == 24995


def test_the_rule_warns_of_a_coarse_notched_beam_and_not_of_a_fine_one(cli, tmp_path, capsys, monkeypatch):
    """examples/beam_3pb.toml has 8 modules over its ligament (80 mm at 10 mm):
    `ldem run` says the rule's 16 need L0 = 5 mm and its bars; at L0 = 5 mm (16
    modules) nothing is said. Without its notch the same beam is 10 modules deep,
    and the rule asks 30 over the depth: L0 / 3; at L0 = 2.5 mm (40) nothing."""
    assert (module_rule.RULE_MODULES, module_rule.RULE_MODULES_DEPTH) == (16, 30)
    fine = _beam(0.005).build
    assert module_rule.needed(_beam(0.005).description["shape"], 0.005) is None
    plain = _beam(notch=0.0).description["shape"]
    assert module_rule.needed(dict(plain, L0=0.0025), 0.0025) is None
    deep = module_rule.needed(plain, 0.01)
    assert (deep["what"], deep["modules"], deep["rule"], deep["k"]) == ("depth", 10.0, 30, 3)
    n = module_rule.needed(_beam().description["shape"], 0.01)
    assert (n["modules"], n["k"], n["L0"], n["bars"]) == (8.0, 2, 0.005, module_rule.bar_count(fine.mask))
    warn_module("run", _beam(0.005))
    assert capsys.readouterr().err == ""
    with monkeypatch.context() as m:  # a finer lattice beyond this machine is said, not an error
        m.setattr(module_rule, "module_mask", lambda shape: (_ for _ in ()).throw(ValueError("too big")))
        warn_module("run", _beam())
    assert "L0 = 5 mm (L0 / 2) meets it, at more bars than this machine holds (now 24,995)" in capsys.readouterr().err
    r = cli("run", os.path.join(ROOT, "examples", "beam_3pb.toml"), "--threads", "1", "--no-plots", "--no-progress",
            "--set", "final_strain=2e-5", "--out", str(tmp_path / "o"))
    assert r.returncode == 0, r.stderr
    assert (f"ldem run: warning: the ligament above the notch is 8 modules of L0 = 10 mm, fewer than the module "
            f"rule's 16: the peak may depend on the module; L0 = 5 mm (L0 / 2) meets it, at "
            f"{n['bars']:,} bars (now 24,995)") in r.stderr.splitlines()


def test_the_convergence_plan_counts_its_modules(tmp_path):
    """The beams of the convergence study at every module of the plan are whole
    numbers of modules (built), 10/20/30/40 modules over D = 50 mm, and the rule is
    the fewest modules at which every beam is within 2 % of its finest."""
    which = beam_convergence.plan()
    assert len(which) == 10 and len(beam_convergence.plan(["D100_n0.2"], [0.0025])) == 1
    with pytest.raises(ValueError, match="unknown beam D200"):
        beam_convergence.plan(["D200_n0"])
    material = json.load(open(os.path.join(ROOT, "results", "beams", "gregoire2013", "transfer", "on_D50_n0.5",
                                           "fit.json")))["material"]
    (tmp_path / "measured.csv").write_text("D_mm,notch_ratio,cmod_at_peak_mm\n50,0.0,0.015\n50,0.5,0.02\n100,0.2,0.03\n")
    tests = beam_convergence.cases(material, str(tmp_path), 1)
    assert {t.limit for t in tests if t.notch == 0.5} == {beam_convergence.STOP * 0.02e-3}
    depth = {(t.case_name(), t.cases_folder): round(t.D / t.v.L0) for t in tests}
    assert depth == {("D50_n0.5_s1", "L1.25mm"): 40, ("D50_n0_s1", "L1.25mm"): 40, ("D50_n0.5_s1", "L1.667mm"): 30,
                     ("D50_n0_s1", "L1.667mm"): 30, ("D50_n0.5_s1", "L2.5mm"): 20, ("D50_n0_s1", "L2.5mm"): 20, ("D100_n0.2_s1", "L2.5mm"): 40, ("D50_n0.5_s1", "L5mm"): 10,
                     ("D50_n0_s1", "L5mm"): 10, ("D100_n0.2_s1", "L5mm"): 20}
    lig = module_rule.LIGAMENT
    table = [{"beam": "D50_n0.5", "L0_mm": L, "modules": m, "vs_finest": v, "over": lig}
             for L, m, v in ((5, 5, 0.05), (2.5, 10, 0.015), (1.667, 15, 0.0))] + \
            [{"beam": "D100_n0.2", "L0_mm": L, "modules": m, "vs_finest": v, "over": lig}
             for L, m, v in ((5, 16, 0.007), (2.5, 32, 0.0))] + \
            [{"beam": "D50_n0", "L0_mm": L, "modules": m, "vs_finest": v, "over": "depth"}
             for L, m, v in ((5, 10, 0.01), (2.5, 20, -0.03), (1.667, 30, 0.0))]
    r = beam_convergence.rule(table)
    assert r["per_beam"] == {"D50_n0.5": {"modules": 10, "only_finest": False, "over": lig},
                             "D100_n0.2": {"modules": 16, "only_finest": False, "over": lig},
                             "D50_n0": {"modules": 30, "only_finest": True, "over": "depth"}}
    assert r["rules"] == {lig: 16, "depth": None}


def test_a_band_of_the_smallest_validation_specimen(tmp_path, monkeypatch, cli):
    """The L-panel at L0 = 25 mm (20 x 4 x 20 modules less a quadrant), 1 m/s
    to 0.5 mm: its prediction (two seeds), then its band of five points (the
    command line asks for 12 at least): each point calibrated to its drawn
    E and f_t, run with its own seed; the band's files, its peak's band about
    the prediction's mean with shares that add up; run again, nothing is."""
    b = validation.SPECIMENS["l_panel"]
    text = open(os.path.join(ROOT, b.file)).read()
    for old, new in (("L0 = 0.01\n", "L0 = 0.025\n"), ("rate_periods = 12 ", "strain_rate = 1.0 "),
                     ("final_strain = 0.002 ", "final_strain = 0.001 ")):
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    (tmp_path / "coarse.toml").write_text(text)
    monkeypatch.setitem(validation.SPECIMENS, "l_panel", dataclasses.replace(b, file=str(tmp_path / "coarse.toml")))
    out = str(tmp_path / "l_panel")
    validation.predict(ROOT, "l_panel", out, seeds=2)
    text = validation.predict_band(ROOT, "l_panel", out, points=5)
    band = {r["quantity"]: r for r in ldem.io.read_table(os.path.join(out, "band", "band.csv"))}
    peak = band["peak_kN"]
    row = ldem.io.read_table(os.path.join(out, "predictions.csv"))[0]
    assert float(peak["mean"]) == pytest.approx(float(row["peak_load_kN"]), rel=1e-4)
    assert float(peak["low"]) < float(peak["mean"]) < float(peak["high"]) and int(peak["points"]) == 5
    shares = [float(peak[f"share_{k}"]) for k in ("E", "f_t", "G_F")]
    assert sum(shares) == pytest.approx(float(peak["share_inputs"]), abs=1e-5)
    assert float(peak["share_inputs"]) + float(peak["share_seeds"]) == pytest.approx(1.0, abs=1e-5)
    design = ldem.io.read_table(os.path.join(out, "band", "design.csv"))
    assert [int(r["seed"]) for r in design] == [101, 102, 103, 104, 105]
    for i, r in enumerate(design, 1):
        with open(os.path.join(out, "band", "calibration", f"p{i}.json")) as f:
            m = json.load(f)["measured"]
        assert m["E"] == pytest.approx(float(r["E"]), rel=0.011) and m["f_t"] == pytest.approx(float(r["f_t"]), rel=0.03)
    assert "| peak [kN] |" in text and "Cost: 5 calibrations" in text
    picture(os.path.join(out, "band", "band.png"))
    assert validation.predict_band(ROOT, "l_panel", out, points=5, log=lambda s: None) == text
    r = cli("study", "validation", "l_panel", "--band", "--points", "11", "--out", out)
    assert r.returncode == 2 and "the band's design has at least 12 points" in r.stderr
    r = cli("study", "validation", "l_panel", "--band", "--out", str(tmp_path / "none"))
    assert r.returncode == 2 and r.stderr.strip().endswith("none: no predictions.csv: the prediction comes first "
                                                          f"(ldem study validation NAME --out {tmp_path / 'none'})")
