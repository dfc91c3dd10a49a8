"""results/ holds tables, reports and figures, not bulk (results/README.md):
the files tracked there that are not text weigh at most 10 MB in all, and
every ParaView collection (.pvd) names files that are there. It holds one
current result per registered study, whose README names the command, the
commits on main and the wall time; every earlier run is in results/archive/,
listed in results/HISTORY.md, and README.md and docs/ cite none of them."""
import glob
import os
import re
import subprocess
import xml.etree.ElementTree as ET

import pytest

from conftest import COMMIT_HASH, ROOT
from ldem.study.registry import STUDIES

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


# One current result per study (results/README.md): results/NAME/ for each
# registered study that has one, its README opening with the command, the
# commit(s) and the wall time; the side results; the archive of earlier runs.
SIDE = {"dynamics", "mpi", "yade-native"}  # no study's output (results/README.md, "Side results")
VARIANTS = {"size-effect": {"seed-settings"}}  # the one named variant a study's folder may hold
ARCHIVE = os.path.join(ROOT, "results", "archive")


def provenance(readme: str) -> dict:
    """The lines `- command:`, `- commit:` and `- wall time:` of a README, by key (each a list)."""
    found = {}
    for key, value in re.findall(r"^- (command|commit|wall time): (.+)$", open(readme).read(), re.M):
        found.setdefault(key, []).append(value)
    return found


def commits(line: str) -> list:
    return COMMIT_HASH.findall(line)


def study_folders() -> list:
    top = sorted(n for n in os.listdir(os.path.join(ROOT, "results"))
                 if os.path.isdir(os.path.join(ROOT, "results", n)))
    return [n for n in top if n not in SIDE | {"archive"}]


def test_every_folder_of_results_is_a_study_a_side_result_or_the_archive():
    assert set(study_folders()) <= set(STUDIES), set(study_folders()) - set(STUDIES)
    assert os.path.isdir(ARCHIVE) and os.path.isfile(os.path.join(ROOT, "results", "HISTORY.md"))


@pytest.mark.parametrize("name", study_folders())
def test_a_current_result_says_where_it_comes_from(name):
    readme = os.path.join(ROOT, "results", name, "README.md")
    p = provenance(readme)
    assert set(p) == {"command", "commit", "wall time"}, f"{readme}: {sorted(p)}"
    assert all(re.match(rf"`ldem study {name}\b", c) for c in p["command"]), p["command"]
    assert all(commits(c) for c in p["commit"]), p["commit"]


def test_only_a_study_folder_and_its_named_variant_hold_a_current_run():
    """Each study has exactly one current folder: no README elsewhere (but the archive) opens as one does."""
    declared = []
    for folder, dirs, files in os.walk(os.path.join(ROOT, "results")):
        dirs[:] = [d for d in dirs if os.path.join(folder, d) != ARCHIVE]
        if "README.md" in files and "command" in provenance(os.path.join(folder, "README.md")):
            declared.append(os.path.relpath(folder, os.path.join(ROOT, "results")).split(os.sep))
    allowed = [[n] for n in study_folders()] + [[n, v] for n, vs in VARIANTS.items() for v in vs]
    assert [d for d in declared if d not in allowed] == []


def _on_main(commit: str) -> bool:
    return subprocess.run(["git", "-C", ROOT, "merge-base", "--is-ancestor", commit, "HEAD"],
                          capture_output=True).returncode == 0


@pytest.mark.parametrize("name", study_folders())
def test_the_commits_a_current_result_names_are_on_main(name):
    git = subprocess.run(["git", "-C", ROOT, "rev-parse", "--is-shallow-repository"], capture_output=True, text=True)
    if git.returncode != 0 or git.stdout.strip() != "false":
        pytest.skip("this checkout has no git history (not a clone, or a shallow one): the commits cannot be looked up")
    named = [c for line in provenance(os.path.join(ROOT, "results", name, "README.md"))["commit"] for c in commits(line)]
    assert named and [c for c in named if not _on_main(c)] == []


def test_history_lists_every_archived_run():
    history = open(os.path.join(ROOT, "results", "HISTORY.md")).read()
    runs = {os.path.join("archive", study, run).replace(os.sep, "/")
            for study in os.listdir(ARCHIVE) for run in os.listdir(os.path.join(ARCHIVE, study))}
    linked = set(re.findall(r"\]\((archive/[^)/]+/[^)/]+)", history))
    assert runs == linked, (sorted(runs - linked), sorted(linked - runs))


def test_the_front_pages_cite_current_results_only():
    for page in ["README.md"] + sorted(glob.glob(os.path.join(ROOT, "docs", "*.md"))):
        text = open(os.path.join(ROOT, page)).read()
        assert "results/archive" not in text, f"{page} cites an archived run; cite the current one (or HISTORY.md)"


def test_the_layout_checks_see_a_missing_block_and_a_stray_commit(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("# x\n\n- command: `ldem study damping --out d`\n- commit: 3dafc02, b\n- wall time: 1 s\n")
    assert provenance(str(readme)) == {"command": ["`ldem study damping --out d`"], "commit": ["3dafc02, b"],
                                       "wall time": ["1 s"]}
    assert commits("3dafc02 (the build), 1555344 bars, 2.913e-06 s, deadbeef") == ["3dafc02"]
    readme.write_text("# x\n\nRun by `ldem study damping` at 3dafc02 in 1 s.\n")
    assert provenance(str(readme)) == {}
