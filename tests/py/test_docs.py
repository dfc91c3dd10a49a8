"""The manual: README.md (a front door of at most 200 lines) and docs/ (one page
a topic). Every link resolves, and every command shown in a shell block is run:
here, on the build tree, or by the test named for it; a synopsis (options in
[brackets]) has each of its options in its command's --help."""
import glob
import itertools
import json
import os
import re
import shlex

import pytest

from conftest import ROOT, run_cli

PAGES = ["README.md"] + sorted(os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "docs", "*.md")))

# Commands run elsewhere, by the test named (it holds the command's own words).
RUN_BY = {
    "yade-double -n -x scripts/yade_one_bar.py": ("test_yade_bridge.py", "yade_one_bar.py"),
    "bash scripts/yade_batch.sh scripts/size_effect.table scripts/cube_tension.py": ("test_scenes.py", "yade_batch.sh"),
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


@pytest.mark.parametrize("page", PAGES)
def test_every_link_resolves(page):
    text = open(os.path.join(ROOT, page)).read()
    text = re.sub(r"`[^`]*`", "", re.sub(r"```.*?```", "", text, flags=re.S))  # code is not links
    here = os.path.dirname(os.path.join(ROOT, page))
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+://", target):
            continue
        path, _, anchor = target.partition("#")
        full = os.path.normpath(os.path.join(here, path)) if path else os.path.join(ROOT, page)
        assert os.path.exists(full), f"{page}: {target}"
        if anchor and full.endswith(".md"):
            assert anchor in anchors(os.path.relpath(full, ROOT)), f"{page}: {target}"


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
