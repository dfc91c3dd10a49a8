"""results/ holds tables, reports and figures, not bulk (results/README.md):
the files tracked there that are not text weigh at most 10 MB in all, and
every ParaView collection (.pvd) names files that are there."""
import os
import subprocess
import xml.etree.ElementTree as ET

from conftest import ROOT

MAX_BINARY_BYTES = 10_000_000
# What a study writes as text; any other file (.png, .vtu, .npz, .pdf...) counts as binary.
TEXT = (".md", ".csv", ".json", ".jsonl", ".txt", ".pvd")


def _tracked(folder: str) -> list:
    r = subprocess.run(["git", "-C", ROOT, "ls-files", "-z", folder], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr  # the suite runs on a checkout (CI: a fresh clone)
    return [os.path.join(ROOT, f) for f in r.stdout.split("\0") if f]


def _is_binary(path: str) -> bool:
    with open(path, "rb") as f:
        return not path.endswith(TEXT) or b"\0" in f.read(8192)


def binary_bytes(paths) -> int:
    return sum(os.path.getsize(p) for p in paths if _is_binary(p))


def missing_in_pvd(path: str, tracked) -> list:
    """The files path's collection names that are not among tracked."""
    folder = os.path.dirname(path)
    names = [d.get("file") for d in ET.parse(path).getroot().iter("DataSet")]
    return [n for n in names if os.path.normpath(os.path.join(folder, n)) not in tracked]


def test_results_hold_at_most_10_mb_of_binaries():
    paths = _tracked("results")
    assert len(paths) > 100  # the tables are there: the sum below is of them
    total = binary_bytes(paths)
    big = sorted((os.path.getsize(p), os.path.relpath(p, ROOT)) for p in paths if _is_binary(p))[-5:]
    assert total <= MAX_BINARY_BYTES, f"{total / 1e6:.2f} MB of binaries in results/; the largest: {big}"


def test_every_pvd_in_results_names_tracked_files():
    paths = _tracked("results")
    tracked = {os.path.normpath(p) for p in paths}
    broken = {os.path.relpath(p, ROOT): missing_in_pvd(p, tracked) for p in paths if p.endswith(".pvd")}
    assert not {k: v for k, v in broken.items() if v}, broken


def test_the_checks_see_a_binary_and_a_dangling_pvd(tmp_path):
    (tmp_path / "curve.csv").write_text("step,x\n0,1\n")
    (tmp_path / "bars.vtu").write_text("<?xml version=\"1.0\"?>\n")  # XML, but bulk: counted
    (tmp_path / "cracks.png").write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(100))
    (tmp_path / "fake.csv").write_bytes(b"a,b\n\0\0")
    (tmp_path / "bars.pvd").write_text('<VTKFile type="Collection"><Collection>'
                                       '<DataSet timestep="0" file="bars.vtu"/>'
                                       '<DataSet timestep="1" file="bars_0001.vtu"/></Collection></VTKFile>')
    paths = [str(tmp_path / n) for n in ("curve.csv", "bars.vtu", "cracks.png", "fake.csv", "bars.pvd")]
    assert binary_bytes(paths) == 22 + 108 + 6
    assert missing_in_pvd(paths[-1], {os.path.normpath(p) for p in paths}) == ["bars_0001.vtu"]
