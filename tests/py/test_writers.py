"""The writers' registry (ldem.io): a run writes the files of the writers it
is given, those and no others; an unknown name stops it before anything is
computed; a writer registered by name is used with no change to the runner."""
import os

import pytest

import ldem
from ldem import io
from ldem.runner import default_writers
from conftest import FAST

TINY = dict(FAST, size=0.04, final_strain=0.02, threads=1)


@pytest.mark.parametrize("writers, files", [
    (["summary"], {"summary.json"}),
    (["curve", "summary", "slice"], {"curve.csv", "summary.json", "slice.npz", "cracks.png"}),
    (["curve", "summary", "figures", "checkpoint"],
     {"curve.csv", "summary.json", "curve.png", "energies.png", "cracks.png", "checkpoint.npz"}),
])
def test_a_run_writes_the_files_of_its_writers_and_no_others(tmp_path, writers, files):
    out = tmp_path / "run"
    during = set()  # what the folder held while the run went (a checkpoint lives only then)

    def look(row):
        during.update(f for f in os.listdir(out) if not f.startswith("."))
        return True

    r = ldem.run_cube(ldem.CubeTest(**TINY), out=str(out), progress=False, writers=writers, checkpoint_every=5,
                      observers=[look])
    assert set(os.listdir(out)) == files - {"checkpoint.npz"}  # a finished run keeps no checkpoint
    assert during | set(os.listdir(out)) == files
    assert io.read_summary(str(out / "summary.json"))["peak_stress_MPa"] == r.summary["peak_stress_MPa"]
    if "curve" in writers:  # the curve's rows are the run's
        assert len(io.read_curve(str(out / "curve.csv"))["step"]) == len(r.curve["step"])


def test_the_default_writers_are_the_commands_files(tmp_path):
    """`ldem cube` and `ldem run` without --no-plots: curve, summary, pictures and ParaView files."""
    assert default_writers() == ["curve", "summary", "figures", "vtk"]
    assert default_writers(plots=False, checkpoints=True) == ["curve", "summary", "checkpoint"]
    out = tmp_path / "run"
    ldem.run_cube(ldem.CubeTest(**TINY), out=str(out), progress=False)
    assert set(os.listdir(out)) == {"curve.csv", "summary.json", "curve.png", "energies.png", "cracks.png",
                                    "bars.vtu", "crack.vtu", "bars.pvd", "crack.pvd"}


def test_an_unknown_writer_is_a_clear_error_before_any_run(tmp_path):
    out = tmp_path / "run"
    with pytest.raises(ValueError, match=r"unknown writer 'curves' \(known: curve, figures, vtk, checkpoint, "
                                         r"final_state, slice, summary\)"):
        ldem.run_cube(ldem.CubeTest(**TINY), out=str(out), writers=["curves", "summary"])
    assert not out.exists()  # nothing was computed, no folder made


def test_a_registered_writer_is_used_by_name(tmp_path):
    """A new writer is one register_writer call: the run calls it on each row
    and at the end, in its rank among the others (before the summary)."""
    class PeakTxt:
        def __init__(self, run):
            self.path, self.rows = os.path.join(run.out, "peak.txt"), 0

        def __call__(self, row):
            self.rows += 1

        def finish(self, result):
            assert not os.path.exists(os.path.join(os.path.dirname(self.path), "summary.json"))  # the summary is last
            io.write_text(self.path, f"{result.summary['peak_stress_MPa']!r} {self.rows}\n")

    io.register_writer("peak", PeakTxt, 60, "peak.txt: the peak stress [MPa] and the number of rows")
    try:
        out = tmp_path / "run"
        r = ldem.run_cube(ldem.CubeTest(**TINY), out=str(out), progress=False, writers=["summary", "peak"])
        assert set(os.listdir(out)) == {"peak.txt", "summary.json"}
        assert (out / "peak.txt").read_text() == f"{r.summary['peak_stress_MPa']!r} {len(r.curve['step'])}\n"
    finally:
        io.registry._WRITERS.pop("peak")
