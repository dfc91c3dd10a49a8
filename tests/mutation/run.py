#!/usr/bin/python3
"""Mutation checks: does the test suite notice small wrong changes of ldem?

For each mutation of tests/mutation/mutations.toml (a file, a sed expression,
a one-line description) this script

  1. resets a scratch copy of the repository's committed tree (HEAD) to its
     pristine state (the copy is a git repository of its own: reset --hard,
     clean),
  2. applies the mutation there with `sed -i` and checks that it changed the
     expected number of lines,
  3. builds incrementally in a scratch build tree configured once (only the
     changed files recompile; the LTO link of _core and ldem_tests still takes
     a while),
  4. runs the suite, failing fast, direct checks first: the GoogleTest binary
     with --gtest_fail_fast on the suites named Direct* (fast checks of one
     quantity each against hand values), then `pytest -x -q -m direct
     tests/py`, then the rest of each the same way (PYTHONPATH /
     LDEM_BUILD_PYTHON = the scratch build's python folder, LDEM_SOURCE_DIR =
     the scratch source), so that the first failing test names the quantity
     a mutation broke, in seconds, where one exists,

and records "caught" (with the first failing test), "NOT CAUGHT" (the whole
suite passed) or "did not build", with the times. The repository's working
tree is never touched: only the scratch copy (default /tmp/ldem-mut) is.

Before the mutations, the unmutated scratch copy is built and the whole suite
is run once (the baseline): if it fails, nothing a mutation does can be
read, and the script stops. A full sweep writes its table to
tests/mutation/last_run.md.

    nice -n 19 /usr/bin/python3 tests/mutation/run.py           # everything (an hour or more)
    /usr/bin/python3 tests/mutation/run.py --list               # the mutations
    /usr/bin/python3 tests/mutation/run.py --check              # each applies and changes its file (no build)
    /usr/bin/python3 tests/mutation/run.py --only c_a_0_1358 --no-baseline
    /usr/bin/python3 tests/mutation/run.py --manifest held_out.toml   # another catalogue (a held-out probe)

--only runs the mutations named, in the order given. A mutation of Python
alone (py/ldem/) skips the GoogleTest stages: the C++ it would test is the
unmutated build's. Stopped (Ctrl-C, SIGTERM), the script ends its builds and
test runs with it (each runs in a process group of its own, killed whole).
"""
from __future__ import annotations

import argparse
import datetime
import os
import platform
import re
import signal
import subprocess
import sys
import tarfile
import io
import json
import time
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
MANIFEST = os.path.join(HERE, "mutations.toml")
LAST_RUN = os.path.join(HERE, "last_run.md")
PYTHON = "/usr/bin/python3"

# OpenMP threads that wait at a barrier sleep instead of spinning: on a busy
# machine (this sweep runs under nice beside other jobs) spinning threads slow
# a two-thread run many times over (test_cli.py saw 159 s on two threads against
# 21 s on one). Results do not depend on it, nor on the thread count.
TEST_ENV = dict(os.environ, OMP_WAIT_POLICY=os.environ.get("OMP_WAIT_POLICY", "passive"))

CAUGHT, NOT_CAUGHT, NO_BUILD, NOT_APPLIED = "caught", "NOT CAUGHT", "did not build", "did not apply"


# -- the manifest -------------------------------------------------------------------
def load_mutations(path=MANIFEST):
    with open(path, "rb") as f:
        muts = tomllib.load(f)["mutation"]
    names = set()
    for m in muts:
        for key in ("name", "file", "sed", "description"):
            if key not in m:
                sys.exit(f"{path}: a mutation has no {key}: {m}")
        if m["name"] in names:
            sys.exit(f"{path}: two mutations named {m['name']}")
        names.add(m["name"])
        m.setdefault("lines", 1)
    return muts


def select(muts, only):
    """The mutations named in `only`, in its order, each once; exits naming any unknown."""
    unknown = set(only) - {m["name"] for m in muts}
    if unknown:
        sys.exit(f"unknown mutation(s): {', '.join(sorted(unknown))} (see --list)")
    by_name = {m["name"]: m for m in muts}
    return [by_name[name] for name in dict.fromkeys(only)]


# -- helpers ------------------------------------------------------------------------
STOPS = {signal.SIGINT, signal.SIGTERM}


def sh(cmd, cwd=None, env=None, log=None, timeout=None, check=True):
    """Runs cmd; its output goes to log (a path) if given, else is returned.
    cmd runs in a process group of its own, killed whole if it times out or
    this script is stopped: a build's compilers and a test run's workers
    end with it (subprocess.run kills the child alone)."""
    out = open(log, "a") if log else subprocess.PIPE
    # A stop while the child starts is held until this script knows it (a signal inside Popen would lose the
    # child, as test_mutation_catalogue.py saw); the child itself starts with nothing blocked.
    signal.pthread_sigmask(signal.SIG_BLOCK, STOPS)
    proc = None
    try:
        try:
            proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT, text=True,
                                    start_new_session=True,
                                    preexec_fn=lambda: signal.pthread_sigmask(signal.SIG_UNBLOCK, STOPS))
        finally:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, STOPS)  # a stop held meanwhile is heard here
        stdout, _ = proc.communicate(timeout=timeout)
    except BaseException:
        if proc is not None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        raise
    finally:
        if log:
            out.close()
    r = subprocess.CompletedProcess(cmd, proc.returncode, stdout)
    if check and r.returncode != 0:
        detail = "" if log else r.stdout[-3000:]
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}){': ' + detail if detail else ''}"
                           + (f"; see {log}" if log else ""))
    return r


def git(src, *args, check=True):
    return sh(["git", "-C", src, "-c", "user.name=ldem-mut", "-c", "user.email=ldem-mut@localhost", *args],
              check=check)


def fmt_s(s):
    return f"{s:.0f} s" if s < 600 else f"{s / 60:.1f} min"


# -- the scratch copy ---------------------------------------------------------------
class Scratch:
    """A copy of the repository's HEAD in <root>/src (a git repository of its own,
    so it can be reset), built in <root>/build, logs in <root>/logs."""

    def __init__(self, root, jobs):
        self.root, self.jobs = root, jobs
        self.src, self.build, self.logs = (os.path.join(root, d) for d in ("src", "build", "logs"))

    def prepare(self):
        """Brings src to the repository's HEAD, touching only files that differ
        (so an existing build stays incremental), and commits it as the pristine state."""
        os.makedirs(self.logs, exist_ok=True)
        head = sh(["git", "-C", REPO, "rev-parse", "HEAD"]).stdout.strip()
        archive = subprocess.run(["git", "-C", REPO, "archive", "--format=tar", "HEAD"], check=True,
                                 stdout=subprocess.PIPE).stdout
        wanted = {}
        with tarfile.open(fileobj=io.BytesIO(archive)) as tar:
            for member in tar.getmembers():
                if member.isfile():
                    wanted[member.name] = (tar.extractfile(member).read(), member.mode)
                elif member.issym():
                    wanted[member.name] = (member.linkname, "link")
        fresh = not os.path.isdir(os.path.join(self.src, ".git"))
        os.makedirs(self.src, exist_ok=True)
        if fresh:
            git(self.src, "init", "-q")
        else:
            self.reset()
        for dirpath, dirnames, filenames in os.walk(self.src):
            if dirpath == self.src and ".git" in dirnames:
                dirnames.remove(".git")
            for name in filenames:
                rel = os.path.relpath(os.path.join(dirpath, name), self.src)
                if rel not in wanted:
                    os.remove(os.path.join(self.src, rel))
        changed = 0
        for rel, (data, mode) in wanted.items():
            path = os.path.join(self.src, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            if mode == "link":
                if not (os.path.islink(path) and os.readlink(path) == data):
                    if os.path.lexists(path):
                        os.remove(path)
                    os.symlink(data, path)
                    changed += 1
                continue
            if os.path.isfile(path) and not os.path.islink(path):
                with open(path, "rb") as f:
                    if f.read() == data:
                        continue
            with open(path, "wb") as f:  # a new mtime: ninja rebuilds what depends on it
                f.write(data)
            os.chmod(path, mode & 0o777)
            changed += 1
        git(self.src, "add", "-A")
        if git(self.src, "status", "--porcelain").stdout.strip():
            git(self.src, "commit", "-q", "-m", f"pristine: {head}")
        return head, changed

    def reset(self):
        git(self.src, "reset", "-q", "--hard")
        git(self.src, "clean", "-q", "-f", "-d", "-x")

    def configure(self):
        if os.path.isfile(os.path.join(self.build, "build.ninja")):
            return
        sh(["cmake", "-S", self.src, "-B", self.build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython_EXECUTABLE={PYTHON}"], log=os.path.join(self.logs, "configure.log"))

    def apply(self, m):
        """Applies mutation m; returns None, or why it did not apply."""
        path = os.path.join(self.src, m["file"])
        if not os.path.isfile(path):
            return f"no file {m['file']}"
        r = sh(["sed", "-i", "-e", m["sed"], path], check=False)
        if r.returncode != 0:
            return f"sed failed: {r.stdout.strip()}"
        diff = git(self.src, "diff", "--numstat", "--", m["file"]).stdout.split()
        changed = int(diff[0]) if diff else 0
        if changed != m["lines"]:
            return f"changed {changed} lines, expected {m['lines']}"
        return None

    def diff(self):
        return git(self.src, "diff", "-U0").stdout

    def build_all(self, log):
        """Incremental build; True if it succeeded."""
        targets = ["cmake", "--build", self.build]
        if self.jobs:
            targets += ["-j", str(self.jobs)]
        return sh(targets, log=log, check=False).returncode == 0

    # -- the suite, failing fast --------------------------------------------------------
    def gtest(self, log, timeout, skip=(), fail_fast=True, direct=False):
        """[] if every GoogleTest passed, else the failing tests (the first only when
        failing fast), or what went wrong. skip: tests not to run; direct: the
        direct suites only, else all the others."""
        cmd = [os.path.join(self.build, "tests", "ldem_tests"), "--gtest_color=no"]
        if fail_fast:
            cmd.append("--gtest_fail_fast")
        left_out = list(skip) + ([] if direct else [GTEST_DIRECT])
        cmd.append(f"--gtest_filter={GTEST_DIRECT if direct else '*'}" + ("-" + ":".join(left_out) if left_out else ""))
        try:
            r = sh(cmd, cwd=os.path.join(self.build, "tests"), env=TEST_ENV, log=log, timeout=timeout,
                   check=False)
        except subprocess.TimeoutExpired:
            return [f"{last_match(log, RUN_RE) or '?'} (timed out after {timeout} s)"]
        if r.returncode == 0:
            return []
        failed = all_matches(log, GTEST_FAILED_RE)
        return failed or [f"{last_match(log, RUN_RE) or '?'} (exit {r.returncode}: crashed)"]

    def pytest(self, log, timeout, skip=(), fail_fast=True, direct=False):
        """[] if every pytest test passed, else the failing tests (node ids under
        tests/py). direct: the tests marked direct only, else all the others."""
        py = os.path.join(self.build, "python")
        env = dict(TEST_ENV, PYTHONPATH=py, LDEM_BUILD_PYTHON=py, LDEM_SOURCE_DIR=self.src,
                   PYTHONDONTWRITEBYTECODE="1")
        # The spec lives beside the repository (../shared), not beside the scratch copy.
        spec = os.path.realpath(os.path.join(REPO, "..", "shared", "LDEM_SPEC.md"))
        if "LDEM_SPEC" not in env and os.path.isfile(spec):
            env["LDEM_SPEC"] = spec
        cmd = [PYTHON, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rfE", "-m",
               "direct" if direct else "not direct", "tests/py"]
        if fail_fast:
            cmd.insert(3, "-x")
        for test in (*skip, MANIFEST_CHECK):
            cmd += ["--deselect", "tests/py/" + test]
        try:
            r = sh(cmd, cwd=self.src, env=env, log=log, timeout=timeout, check=False)
        except subprocess.TimeoutExpired:
            return [f"timed out after {timeout} s (last: {last_match(log, PYTEST_FILE_RE) or '?'})"]
        if r.returncode in (0, PYTEST_NO_TESTS):  # none left: every one of the pass was left out
            return []
        return all_matches(log, PYTEST_FAILED_RE) or [f"exit {r.returncode} (see log)"]


# The manifest's own check, that each sed changes its file: in a copy the sed has
# mutated it fails by construction, so it would count every mutation the suite
# misses up to it as caught (four did on fad7904, tests/mutation/last_run.md).
MANIFEST_CHECK = "test_mutation_catalogue.py::test_mutation_applies"

# The direct checks: GoogleTest suites named Direct* (tests/cpp) and pytest tests
# marked direct (tests/py/conftest.py registers the marker and runs them first).
GTEST_DIRECT = "Direct*.*"
PYTEST_NO_TESTS = 5  # pytest's exit code when it selects no test
GTEST_FAILED_RE = re.compile(r"^\[  FAILED  \] (\w+\.\w+)")
RUN_RE = re.compile(r"^\[ RUN      \] (\S+)")
PYTEST_FAILED_RE = re.compile(r"^(?:FAILED|ERROR) (?:tests/py/)?(.+?)(?: - .*)?$")
PYTEST_FILE_RE = re.compile(r"^(tests/py/\S+\.py) ")


def all_matches(path, regex):
    """Every first group of regex in the file, once each, in order."""
    found = []
    with open(path, errors="replace") as f:
        for line in f:
            m = regex.match(line.rstrip("\n"))
            if m and m.group(1) not in found:
                found.append(m.group(1))
    return found


def last_match(path, regex):
    found = None
    with open(path, errors="replace") as f:
        for line in f:
            m = regex.match(line)
            if m:
                found = m.group(1)
    return found


def python_only(m) -> bool:
    """A mutation of the Python package alone: the C++ core and its tests are the unmutated build's."""
    return m["file"].startswith("py/ldem/") and m["file"].endswith(".py")


def run_suite(scratch, tag, timeout, skip=None, fail_fast=True, stages=("gtest", "pytest")):
    """Runs the direct checks (GoogleTest, then pytest), then the rest of each.
    Failing fast: (first failure or None, seconds); else (every failure as
    {"gtest": [...], "pytest": [...]}, seconds).
    skip: {"gtest": [...], "pytest": [...]}, tests left out (they fail unmutated).
    stages: the suites to run (pytest alone for a mutation of Python alone)."""
    skip = skip or {}
    t = time.monotonic()
    failures = {"gtest": [], "pytest": []}
    for direct in (True, False):
        for stage in stages:
            log = os.path.join(scratch.logs, f"{tag}.{stage}{'.direct' if direct else ''}.log")
            if os.path.exists(log):
                os.remove(log)
            failed = getattr(scratch, stage)(log, timeout, skip.get(stage, ()), fail_fast, direct)
            failures[stage] += failed
            if fail_fast and failed:
                return f"{stage}: {failed[0]}", time.monotonic() - t
    return (None if fail_fast else failures), time.monotonic() - t


# -- one mutation ---------------------------------------------------------------------
def run_one(scratch, m, timeout, skip=None):
    res = {"name": m["name"], "file": m["file"], "description": m["description"], "first_failure": "",
           "build_s": 0.0, "test_s": 0.0}
    scratch.reset()
    why = scratch.apply(m)
    if why:
        res.update(result=NOT_APPLIED, first_failure=why)
        scratch.reset()
        return res
    with open(os.path.join(scratch.logs, f"{m['name']}.diff"), "w") as f:
        f.write(scratch.diff())
    blog = os.path.join(scratch.logs, f"{m['name']}.build.log")
    if os.path.exists(blog):
        os.remove(blog)
    t = time.monotonic()
    built = scratch.build_all(blog)
    res["build_s"] = time.monotonic() - t
    if not built:
        res.update(result=NO_BUILD, first_failure=f"see {blog}")
    else:
        failed, res["test_s"] = run_suite(scratch, m["name"], timeout, skip,
                                          stages=("pytest",) if python_only(m) else ("gtest", "pytest"))
        res.update(result=CAUGHT if failed else NOT_CAUGHT, first_failure=failed or "")
    scratch.reset()  # the next build also undoes this mutation
    return res


# -- the report -----------------------------------------------------------------------
def table(results):
    rows = ["| # | mutation | file | result | first failing test | build | tests |",
            "|---|---|---|---|---|---|---|"]
    for i, r in enumerate(results, 1):
        result = f"**{r['result']}**" if r["result"] != CAUGHT else r["result"]
        failure = r["first_failure"].replace("|", "\\|")
        rows.append(f"| {i} | `{r['name']}` | `{r['file']}` | {result} | {failure} | {fmt_s(r['build_s'])} | "
                    f"{fmt_s(r['test_s'])} |")
    return "\n".join(rows)


def report(results, head, wall, baseline, skip, argv):
    counts = {k: sum(r["result"] == k for r in results) for k in (CAUGHT, NOT_CAUGHT, NO_BUILD, NOT_APPLIED)}
    lines = [
        "# Mutation checks: last run",
        "",
        f"Written by `tests/mutation/run.py` ({' '.join(argv) or 'no options'}) on "
        f"{datetime.datetime.now().strftime('%Y-%m-%d %H:%M')}, {platform.node()} "
        f"({os.cpu_count()} cores), on commit `{head[:12]}`.",
        f"Mutations: {len(results)}; caught {counts[CAUGHT]}, not caught {counts[NOT_CAUGHT]}, "
        f"did not build {counts[NO_BUILD]}, did not apply {counts[NOT_APPLIED]}. "
        f"Wall time {fmt_s(wall)}" + (f" (the unmutated suite: {baseline})." if baseline else "."),
        "",
        "Each mutation is applied alone to a scratch copy of the commit, built, and the suite run failing fast, "
        "direct checks first (GoogleTest with `--gtest_fail_fast` on the `Direct*` suites, then `pytest -x -q -m "
        "direct tests/py`, then the rest of each the same way); \"first failing test\" is the "
        "first test that failed, \"build\" and \"tests\" the times of the incremental build and of the suite "
        "up to that failure (the whole suite for a mutation not caught).",
        "",
        table(results),
        "",
    ]
    if skip:
        lines += ["Tests left out of every mutation's run (they FAIL ON THE UNMUTATED COMMIT, or --leave-out "
                  "named them; a mutation they alone would catch counts as not caught):", ""]
        lines += [f"- {stage}: `{t}`" for stage, tests in skip.items() for t in tests]
        lines += [""]
    elif baseline is None:
        lines += ["The unmutated suite was not run (--no-baseline).", ""]
    lines += [
        "Descriptions (tests/mutation/mutations.toml):",
        "",
    ]
    lines += [f"- `{r['name']}`: {r['description']}" for r in results]
    missed = [r for r in results if r["result"] != CAUGHT]
    if missed:
        lines += ["", "Not caught, did not build or did not apply:", ""]
        lines += [f"- `{r['name']}` ({r['result']}): {r['description']}" for r in missed]
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description="Mutation checks of the ldem test suite (not part of CI).")
    ap.add_argument("--list", action="store_true", help="list the mutations and exit")
    ap.add_argument("--check", action="store_true",
                    help="apply each mutation to the scratch copy and check it changes its file (no build)")
    ap.add_argument("--manifest", default=MANIFEST, metavar="FILE",
                    help="the catalogue of mutations (default tests/mutation/mutations.toml)")
    ap.add_argument("--only", action="append", metavar="NAME",
                    help="run only this mutation (repeatable; they run in the order given)")
    ap.add_argument("--no-baseline", action="store_true", help="skip the run of the unmutated suite")
    ap.add_argument("--strict-baseline", action="store_true",
                    help="stop if the unmutated suite fails (default: leave its failing tests out and say so)")
    ap.add_argument("--leave-out", action="append", default=[], metavar="TEST",
                    help="a test to leave out of every run (repeatable): a GoogleTest name (Suite.Test, "
                         "or a pattern such as Dynamics.*) or a pytest node id under tests/py "
                         "(test_golden.py): what would the rest of the suite catch without it?")
    ap.add_argument("--scratch", default="/tmp/ldem-mut", help="scratch folder (default /tmp/ldem-mut)")
    ap.add_argument("--jobs", type=int, default=2, help="build jobs (default 2)")
    ap.add_argument("--timeout", type=int, default=3600, help="seconds per test stage before it counts as failed")
    ap.add_argument("--out", help="where to write the table (default: tests/mutation/last_run.md for a full "
                                  "sweep, <scratch>/last_run.md with --only)")
    args = ap.parse_args(argv)
    argv = sys.argv[1:] if argv is None else argv

    # SIGTERM as Ctrl-C: the child running is killed with its process group (sh), the scratch copy is reset
    # by the next run.
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    if not os.path.isfile(args.manifest):
        sys.exit(f"no manifest {args.manifest}")
    muts = load_mutations(args.manifest)
    if args.list:
        w = max(len(m["name"]) for m in muts)
        for m in muts:
            print(f"{m['name']:<{w}}  {m['file']}\n{'':<{w}}  {m['description']}")
        return 0
    if args.only:
        muts = select(muts, args.only)

    scratch = Scratch(args.scratch, args.jobs)
    head, changed = scratch.prepare()
    print(f"scratch copy of {head[:12]} in {scratch.src} ({changed} files updated)", flush=True)
    if args.check:
        bad = 0
        for m in muts:
            scratch.reset()
            why = scratch.apply(m)
            bad += why is not None
            print(f"{'ok' if why is None else 'FAILS'}  {m['name']}" + (f": {why}" if why else ""))
            if why is None:
                print("    " + "\n    ".join(l for l in scratch.diff().splitlines() if l[:1] in "+-"
                                             and not l.startswith(("+++", "---"))))
        scratch.reset()
        return 1 if bad else 0

    t0 = time.monotonic()
    scratch.reset()
    scratch.configure()
    print("building the unmutated copy ...", flush=True)
    if not scratch.build_all(os.path.join(scratch.logs, "baseline.build.log")):
        sys.exit(f"the unmutated copy does not build: see {scratch.logs}/baseline.build.log")
    baseline, skip = None, {}
    cache = os.path.join(scratch.root, "baseline.json")
    if args.no_baseline and os.path.isfile(cache):
        with open(cache) as f:
            known = json.load(f)
        if known["head"] == head:  # the last baseline of this very commit
            baseline, skip = known["baseline"] + " (an earlier run, same commit)", known["skip"]
            if skip:
                print(f"  failing unmutated (an earlier baseline of this commit), left out: {skip}", flush=True)
    if not args.no_baseline:
        print("running the unmutated suite (all of it) ...", flush=True)
        failures, secs = run_suite(scratch, "baseline", args.timeout, fail_fast=False)
        skip = {k: v for k, v in failures.items() if v}
        baseline = f"{'passes' if not skip else 'fails'} in {fmt_s(secs)}"
        print(f"  baseline {baseline}", flush=True)
        if skip:
            listed = "; ".join(f"{k}: {', '.join(v)}" for k, v in skip.items())
            if args.strict_baseline:
                sys.exit(f"the unmutated suite fails ({listed}; logs in {scratch.logs}): fix that first")
            print(f"  FAILING UNMUTATED, left out of every mutation's run: {listed}", flush=True)
        with open(cache, "w") as f:
            json.dump({"head": head, "baseline": baseline, "skip": skip}, f)

    for test in args.leave_out:
        stage = "pytest" if (".py" in test or "::" in test) else "gtest"
        skip.setdefault(stage, []).append(test)
        print(f"  left out on request: {stage} {test}", flush=True)

    results = []
    for i, m in enumerate(muts, 1):
        print(f"[{i}/{len(muts)}] {m['name']}: {m['description']}", flush=True)
        r = run_one(scratch, m, args.timeout, skip)
        results.append(r)
        print(f"    {r['result']}" + (f": {r['first_failure']}" if r["first_failure"] else "") +
              f" (build {fmt_s(r['build_s'])}, tests {fmt_s(r['test_s'])})", flush=True)
    wall = time.monotonic() - t0

    text = report(results, head, wall, baseline, skip, argv)
    print()
    print(table(results))
    print(f"\nwall time {fmt_s(wall)}")
    out = args.out or (os.path.join(scratch.root, "last_run.md") if args.only else LAST_RUN)
    with open(out, "w") as f:
        f.write(text)
    print(f"written to {out}")
    # Leave the build matching the pristine source (nothing half-mutated).
    scratch.reset()
    return 0


if __name__ == "__main__":
    sys.exit(main())
