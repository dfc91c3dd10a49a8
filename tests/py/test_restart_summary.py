"""Issue 40, item 4: a restart keeps every bit. A run interrupted after its
peak, continued from its checkpoint, interrupted again and continued to its
end writes the summary.json of a run that never stopped, field by field
(every field, nested ones too, but ldem.rerun.RESTART_SKIPS: the wall time,
the restart count, the date); and the summary of the run interrupted after a
restart reports the peak the core tracked, to the last bit (the curve rows
kept from before the checkpoint are read back from curve.csv, 10 digits)."""
import json
import os

import numpy as np
import pytest

import ldem
from conftest import ROOT
from ldem.rerun import RESTART_SKIPS, differences
from ldem.specimen import SpecimenTest


def _cube():
    return ldem.CubeTest(size=0.06, strain_rate=0.5, threads=1)


def _beam():
    return SpecimenTest.from_file(os.path.join(ROOT, "tests", "data", "beam_small.toml"),
                                  {"threads": 1, "final_strain": 6e-4, "strain_rate": 1.0})


def _interrupt_at(rows: int):
    seen = []

    def observer(row):
        seen.append(row)
        if len(seen) == rows:
            raise KeyboardInterrupt
    return observer


def _summary(folder) -> dict:
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


@pytest.mark.parametrize("make", [_cube, _beam], ids=["cube", "ldem_run_beam"])
def test_an_interrupted_and_continued_run_has_the_summary_of_one_never_stopped(tmp_path, make):
    whole = ldem.run_cube(make(), out=str(tmp_path / "whole"), progress=False, plots=False)
    peak_row = int(np.argmax(whole.curve["stress_MPa"]))
    every = peak_row + 7  # the first checkpoint past the peak: the peak's row is one read back from curve.csv
    assert len(whole.curve["step"]) > every + 20
    cut = str(tmp_path / "cut")
    with pytest.raises(KeyboardInterrupt):
        ldem.run_cube(make(), out=cut, progress=False, plots=False, checkpoint_every=every,
                      observers=[_interrupt_at(every + 3)])
    assert _summary(cut)["status"] == "interrupted"
    with pytest.raises(KeyboardInterrupt):  # continued, and interrupted again 10 rows on
        ldem.run_cube(make(), out=cut, progress=False, plots=False, restart=True, observers=[_interrupt_at(10)])
    again = _summary(cut)
    assert again["status"] == "interrupted"
    # The tracked peak, bit for bit; the curve's row (10 digits) is not it.
    w = whole.summary
    assert (again["peak_stress_MPa"], again["strain_at_peak"], again["edge_strain_at_peak"]) == \
        (w["peak_stress_MPa"], w["strain_at_peak"], w["edge_strain_at_peak"])
    rows = ldem.io.read_curve(os.path.join(cut, "curve.csv"))
    assert rows["stress_MPa"].max() == float(f"{w['peak_stress_MPa']:.10g}") != w["peak_stress_MPa"]
    ldem.run_cube(make(), out=cut, progress=False, plots=False, restart=True)
    done = _summary(cut)
    assert done["status"] == "done" and 0 < done["restarted_at_step"] < done["steps"]
    assert differences(_summary(tmp_path / "whole"), done, RESTART_SKIPS) == []
    assert done["quasi_static"]["kinetic_over_work_at_peak"] > 0  # compared, and not trivially
    assert (tmp_path / "cut" / "curve.csv").read_bytes() == (tmp_path / "whole" / "curve.csv").read_bytes()


def test_differences_goes_into_every_field():
    old = {"a": 1, "q": {"k": 6.667733186321216e-05, "flagged": False}, "l": [1.0, 2.0], "wall_s": 1.0,
           "provenance": {"date": "then", "host": "h"}}
    new = {"a": 1, "q": {"k": 6.667733185245464e-05, "flagged": 0}, "l": [1.0, 2.5], "wall_s": 2.0,
           "provenance": {"date": "now", "host": "h"}, "extra": None}
    assert differences(old, new, RESTART_SKIPS) == ["q.k", "q.flagged", "l[1]", "extra"]
    assert differences(old, old, ()) == [] and differences({"x": float("nan")}, {"x": float("nan")}) == []
