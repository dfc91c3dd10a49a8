"""The comparison of the blind prediction of Grégoire et al. (2013) with the
measurements (issue 28 item 1): `ldem study beams compare` on the shared
data (../shared/data/gregoire2013) and the committed prediction
(results/beams/gregoire2013), into a temporary folder."""
import csv
import os
import shutil

import numpy as np
import pytest

from conftest import ROOT, picture
from ldem.study.beams import comparison as beam_comparison

DATA = os.path.join(ROOT, "..", "shared", "data", "gregoire2013")
PREDICTION = os.path.join(ROOT, "results", "beams", "gregoire2013")


def _rows(path):
    with open(path, newline="") as f:
        return {(float(r["D_mm"]), float(r["notch_ratio"])): r for r in csv.DictReader(f)}


@pytest.fixture
def prediction(tmp_path):
    """A copy of the committed prediction (the comparison writes beside it)."""
    shutil.copy(os.path.join(PREDICTION, "predictions.csv"), tmp_path)
    shutil.copytree(os.path.join(PREDICTION, "curves"), tmp_path / "curves")
    return tmp_path


@pytest.mark.skipif(not os.path.isdir(DATA), reason=f"{DATA} absent: the measurements of Grégoire et al. "
                                                    "(2013) are not on this machine")
def test_the_comparison_on_the_shared_data(prediction, cli):
    r = cli("study", "beams", "compare", "--out", str(prediction), "--data", DATA)
    assert r.returncode == 0, r.stderr
    lines = [x for x in (prediction / "comparison.md").read_text().splitlines() if x.startswith("| D = ")]
    cells = [[c.strip() for c in x.split("|")[1:-1]] for x in lines]
    measured, predicted = _rows(os.path.join(DATA, "measured.csv")), _rows(os.path.join(PREDICTION,
                                                                                        "predictions.csv"))
    # By hand from the two tables: predicted mean peak / measured peak.
    assert len(cells) == len(measured) == 3
    for row, beam in zip(cells, sorted(measured)):
        p, m = float(predicted[beam]["peak_load_kN"]), float(measured[beam]["peak_load_kN"])
        assert row[0].startswith(f"D = {beam[0]:g} mm")
        assert row[1] == f"{p:.3f} ({float(predicted[beam]['cv']):.3f})"
        assert row[3] == f"{m:.3f}" and row[5] == f"{p / m:.3f}" and row[6] == f"{100 * (p / m - 1):+.1f} %"
        assert float(row[8]) == pytest.approx(float(measured[beam]["cmod_at_peak_mm"]))
    # The numbers: +32 %, +51 %, +30 %; the envelopes of the two measured curves.
    assert [round(float(row[6].split()[0])) for row in cells] == [32, 51, 30]
    assert [row[4] for row in cells] == ["4.280-5.212", "0.933-1.114", "-"]
    # The predicted CMOD at peak of the half-notched beam, from its curves.
    curves = np.genfromtxt(os.path.join(PREDICTION, "curves", "D50_n0.5.csv"), delimiter=",", names=True)
    at_peak = [curves[f"cmod_mm_s{s}"][np.nanargmax(curves[f"load_kN_s{s}"])] for s in range(1, 7)]
    assert cells[1][7] == f"{np.mean(at_peak):.4f} ({min(at_peak):.4f}-{max(at_peak):.4f})"
    picture(prediction / "comparison.png")
    # Nothing of the prediction changed.
    for name in ("predictions.csv", "curves/D50_n0.csv"):
        assert (prediction / name).read_bytes() == open(os.path.join(PREDICTION, name), "rb").read()


def test_missing_measurements_are_one_clear_line(prediction, cli):
    nowhere = prediction / "no_data"
    with pytest.raises(FileNotFoundError, match="no_data: no such folder"):
        beam_comparison.compare(str(prediction), str(nowhere))
    nowhere.mkdir()
    with pytest.raises(FileNotFoundError, match="measured.csv not found"):
        beam_comparison.compare(str(prediction), str(nowhere))
    r = cli("study", "beams", "compare", "--out", str(prediction), "--data", str(nowhere))
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "measured.csv not found" in r.stderr
    assert not (prediction / "comparison.md").exists()


def test_the_opening_reached_on_the_rising_branch():
    """The load at a CMOD is read before the peak, between recorded points, and
    is nan where the curve never opens that far before its peak."""
    curve = (np.array([0.0, 0.01, 0.02, 0.015, 0.05]), np.array([0.0, 1.0, 2.0, 1.0, 0.5]))
    rising = beam_comparison.rising(curve)
    assert beam_comparison.load_at_opening(rising, 0.015) == pytest.approx(1.5)
    assert np.isnan(beam_comparison.load_at_opening(rising, 0.03))
    assert beam_comparison.cmod_at_peak(curve) == 0.02
