"""The manual: README.md (a front door of at most 200 lines) and docs/ (one page
a topic), for users: no issue numbers and no commit hashes (history is
CHANGELOG.md's). Every link resolves, there and in results/, and every command
shown in a shell block is run: here, on the build tree, or by the test named
for it; a synopsis (options in [brackets]) has each of its options in its
command's --help. The registered studies, laws and parts are listed where a
user and a developer look for them."""
import glob
import itertools
import json
import os
import re
import shlex

import pytest

from conftest import COMMIT_HASH, ROOT, run_cli
from ldem import _core
from ldem.study.registry import STUDIES

PAGES = ["README.md"] + sorted(os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "docs", "*.md")))
# The results' own pages: their links resolve too (a study's report.md may name figures that are not committed).
RESULT_PAGES = sorted(os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "results", "**", "*.md"),
                                                                    recursive=True))

# Commands run elsewhere, by the test named (it holds the command's own words).
RUN_BY = {
    "yade-double -n -x scripts/yade_one_bar.py": ("test_yade_bridge.py", "yade_one_bar.py"),
    "mkdir -p out/logs && yade-double-batch --job-threads 1 --log 'out/logs/@.log' scripts/size_effect.table "
    "scripts/cube_tension.py": ("test_scenes.py", "yade-double-batch"),
    "/usr/bin/python3 scripts/gallery.py": ("test_specimen_file.py", "scripts/gallery.py"),
}
# The two commands of the front door are the machine's set-up and CI's own (.ci/run), not a test's.
SET_UP = {"bash install.sh && ldem cube", "bash tests/run_all.sh"}


def shell_commands(page):
    """The commands of a page's sh blocks (continuation lines joined, comments cut)."""
    text = open(os.path.join(ROOT, page)).read()
    for block in re.findall(r"```sh\n(.*?)```", text, re.S):
        for line in block.replace("\\\n", " ").splitlines():
            line = re.sub(r"\s+#.*$", "", line).strip()
            if line:
                yield " ".join(line.split())


COMMANDS = sorted({c for p in PAGES for c in shell_commands(p)})


def anchors(page):
    """GitHub's anchors of a page's headings, and its own <a id> anchors."""
    text = open(os.path.join(ROOT, page)).read()
    heads = re.findall(r"^#+ (.*)$", text, re.M)
    return {re.sub(r"[^\w\- ]", "", h.strip().lower()).replace(" ", "-") for h in heads} | \
        set(re.findall(r'<a id="([^"]+)"></a>', text))


def test_readme_is_a_front_door():
    lines = open(os.path.join(ROOT, "README.md")).read().splitlines()
    assert len(lines) <= 200, len(lines)
    assert lines[2:6] == ["```sh", "bash install.sh && ldem cube        # install what is missing, build, run a 0.12 m "
                          "cube in tension", "bash tests/run_all.sh               # the whole test suite (GoogleTest + "
                          "pytest, through CTest)", "```"]
    linked = set(re.findall(r"\]\((docs/[\w.-]+\.md)", "\n".join(lines)))
    assert linked == {p for p in PAGES if p.startswith("docs/")}, "README links every page of docs/"


def broken_links(page) -> list:
    """The relative links of a page whose file or anchor is not there. A study's report.md may name
    figures results/ does not keep (its 10 MB of binaries): in an archived run, or where the folder's
    README says they are not committed."""
    text = open(os.path.join(ROOT, page)).read()
    text = re.sub(r"`[^`]*`", "", re.sub(r"```.*?```", "", text, flags=re.S))  # code is not links
    here = os.path.dirname(os.path.join(ROOT, page))
    readme = os.path.join(here, "README.md")
    figures_elsewhere = os.path.basename(page) == "report.md" and (
        "/results/archive/" in here + "/" or os.path.isfile(readme) and "not committed" in open(readme).read())
    broken = []
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+://", target):
            continue
        path, _, anchor = target.partition("#")
        full = os.path.normpath(os.path.join(here, path)) if path else os.path.join(ROOT, page)
        if not os.path.exists(full):
            broken += [] if figures_elsewhere and full.endswith(".png") else [target]
        elif anchor and full.endswith(".md") and anchor not in anchors(os.path.relpath(full, ROOT)):
            broken.append(target)
    return broken


@pytest.mark.parametrize("page", PAGES + ["ARCHITECTURE.md", "CHANGELOG.md"] + RESULT_PAGES)
def test_every_link_resolves(page):
    assert broken_links(page) == [], page


ISSUE = re.compile(r"(?<![\w&])#\d+\b|\bissues?\s+#?\d+", re.I)


def diary(text: str) -> list:
    """The issue numbers and commit hashes of a user's page (a link's own #anchor is not one)."""
    text = re.sub(r"\]\([^)\s]*\)", "]", text)
    return ISSUE.findall(text) + COMMIT_HASH.findall(text)


@pytest.mark.parametrize("page", PAGES)
def test_a_users_page_has_no_issue_numbers_nor_commit_hashes(page):
    assert diary(open(os.path.join(ROOT, page)).read()) == [], f"{page}: its history goes to CHANGELOG.md"


def test_the_diary_check_sees_issues_and_hashes():
    assert diary("as #41 says; see issue 41, Issues 27 and the fix in 3dafc02 (a1b2c3d4e5f6a7b8c9d0)") == \
        ["#41", "issue 41", "Issues 27", "3dafc02", "a1b2c3d4e5f6a7b8c9d0"]
    assert diary("[the tests](model.md#6-the-cube-tests), 1555344 bars, dt 2.913e-06 s, a decade, "
                 "`--seed 3`, C#") == []


def unlisted(names, text: str, command: str = "") -> list:
    """The names that text does not give as `name` (or, with a command, as command name ...)."""
    return [n for n in names if f"`{n}`" not in text and not (command and re.search(
        rf"\b{command} {re.escape(n)}(?![\w-])", text))]


def _page(name: str) -> str:
    return open(os.path.join(ROOT, name)).read()


@pytest.mark.parametrize("page", ["README.md", "docs/studies.md"])
def test_every_registered_study_is_listed(page):
    assert unlisted(STUDIES, _page(page), command="ldem study") == [], page


@pytest.mark.parametrize("page", ["README.md", "docs/cube.md", "docs/model.md"])
def test_every_registered_law_is_listed(page):
    assert unlisted(_core.bar_laws, _page(page)) == [], page


@pytest.mark.parametrize("parameter", [p for p in _core.parameter_table() if p["choices"]], ids=lambda p: p["name"])
def test_cube_md_lists_every_choice_of_a_parameter(parameter):
    """The drives (tail_drive), stops (stop_at), dampings (tail_damping) and laws a run chooses by name,
    each in its option's row of docs/cube.md."""
    option = "--" + parameter["name"].replace("_", "-")
    rows = [line for line in _page("docs/cube.md").splitlines() if line.startswith(f"| `{option}` |")]
    assert len(rows) == 1, option
    assert unlisted(parameter["choices"], rows[0]) == [], option


def test_architecture_names_every_law_and_part():
    """A law or a part is one header (ARCHITECTURE.md, "Where a new law goes"): each is named there."""
    text = _page("ARCHITECTURE.md")
    headers = glob.glob(os.path.join(ROOT, "pkg", "ldem", "laws", "*.hpp")) + \
        glob.glob(os.path.join(ROOT, "pkg", "ldem", "dynamics", "*.hpp"))
    stems = [os.path.splitext(os.path.basename(h))[0] for h in headers]
    assert len(stems) > 10 and [s for s in stems if not re.search(rf"\b{s}\b", text)] == []


def test_the_list_checks_see_a_new_entry():
    assert unlisted(["hillerborg", "bilinear", "new_law"], "`hillerborg`, `bilinear`: the laws") == ["new_law"]
    assert unlisted(["fixed"], "a fixed drive") == ["fixed"]
    assert unlisted(["mesh", "size-effect"], "`ldem study mesh-x`, `ldem study size-effect --out d`",
                    command="ldem study") == ["mesh"]


def test_every_command_is_accounted_for():
    ldem = [c for c in COMMANDS if c.startswith("ldem ")]
    assert set(COMMANDS) == set(ldem) | set(RUN_BY) | SET_UP, set(COMMANDS) - set(ldem) - set(RUN_BY) - SET_UP
    for command, (test_file, words) in RUN_BY.items():
        assert words in command and words in open(os.path.join(ROOT, "tests", "py", test_file)).read()


@pytest.mark.parametrize("command", [c for c in COMMANDS if c.startswith("ldem ") and "[" in c])
def test_synopsis_options_are_the_commands(command):
    words = command.split()
    sub = list(itertools.takewhile(lambda w: not w.startswith(("-", "[")), words[1:]))  # with a sub-command's
    r = run_cli(*sub, "--help")
    assert r.returncode == 0, r.stderr
    for option in re.findall(r"(--[\w-]+)", command):
        assert option in r.stdout, f"{command}: {option} is not an option of ldem {' '.join(sub)}"


@pytest.mark.parametrize("command", [c for c in COMMANDS if c.startswith("ldem ") and "[" not in c])
def test_command_runs(command, tmp_path):
    """The command as shown, in a scratch folder (examples/ linked into it), no plots
    aside: it exits 0 and writes its summary."""
    os.symlink(os.path.join(ROOT, "examples"), tmp_path / "examples")
    args = shlex.split(command)[1:]
    r = run_cli(*args, cwd=tmp_path, timeout=1200)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    out = tmp_path / args[args.index("--out") + 1] if "--out" in args else None
    if args[0] in ("cube", "run") and out is not None:
        assert json.load(open(out / "summary.json"))["status"] == "done"
