"""The mutation catalogue (tests/mutation/mutations.toml) stays applicable: each
mutation's file exists and its sed expression changes it. A refactor that moves
the code a mutation targets must move the mutation too, or the sweep would
report it as caught while testing nothing."""
import importlib.util
import os
import signal
import subprocess
import sys
import time
import tomllib

import pytest

from conftest import ROOT

with open(os.path.join(ROOT, "tests", "mutation", "mutations.toml"), "rb") as f:
    MUTATIONS = tomllib.load(f)["mutation"]


@pytest.mark.parametrize("m", MUTATIONS, ids=[m["name"] for m in MUTATIONS])
def test_mutation_applies(m):
    path = os.path.join(ROOT, m["file"])
    assert os.path.isfile(path), f"{m['name']}: {m['file']} is gone"
    with open(path) as f:
        original = f.read()
    r = subprocess.run(["sed", "-e", m["sed"], path], capture_output=True, text=True, check=True)
    assert r.stdout != original, f"{m['name']}: its sed changes nothing in {m['file']}"


def _test_names(kind):
    """The names of the tests there are: gtest Suite.Test of tests/cpp, pytest file.py::test of tests/py."""
    import glob
    import re

    names = set()
    if kind == "gtest":
        for path in glob.glob(os.path.join(ROOT, "tests", "cpp", "*.cpp")):
            with open(path) as f:
                names |= {f"{s}.{t}" for s, t in re.findall(r"^TEST(?:_F|_P)?\((\w+), (\w+)\)", f.read(), re.M)}
    else:
        for path in glob.glob(os.path.join(ROOT, "tests", "py", "test_*.py")):
            with open(path) as f:
                names |= {f"{os.path.basename(path)}::{t}" for t in re.findall(r"^def (test_\w+)\(", f.read(), re.M)}
    return names


NAMED = [m for m in MUTATIONS if "caught_by" in m]


@pytest.mark.parametrize("m", NAMED, ids=[m["name"] for m in NAMED])
def test_the_check_named_to_catch_a_mutation_exists(m):
    kind, _, test = m["caught_by"].partition(": ")
    assert kind in ("gtest", "pytest"), m["caught_by"]
    assert test in _test_names(kind), f"{m['name']}: no test {m['caught_by']}"


# -- the runner (tests/mutation/run.py): its options and its children ---------------------------------
RUNNER = os.path.join(ROOT, "tests", "mutation", "run.py")


def _runner():
    spec = importlib.util.spec_from_file_location("mutation_run", RUNNER)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_runner_takes_another_manifest_and_runs_only_in_the_order_given(tmp_path):
    manifest = tmp_path / "held_out.toml"
    manifest.write_text("".join(f'[[mutation]]\nname = "{n}"\nfile = "py/ldem/signals.py"\nsed = "s|a|b|"\n'
                                f'description = "the {n}"\n\n' for n in ("first", "second", "third")))
    r = subprocess.run([sys.executable, RUNNER, "--manifest", str(manifest), "--list"], capture_output=True, text=True,
                       timeout=60)
    listed = [line.split()[0] for line in r.stdout.splitlines() if line and not line.startswith(" ")]
    assert r.returncode == 0 and listed == ["first", "second", "third"], r.stdout + r.stderr
    run = _runner()
    muts = run.load_mutations(str(manifest))
    assert [m["name"] for m in run.select(muts, ["third", "first", "third"])] == ["third", "first"]
    r = subprocess.run([sys.executable, RUNNER, "--manifest", str(tmp_path / "none.toml")], capture_output=True,
                       text=True, timeout=60)
    assert r.returncode == 1 and r.stderr.strip() == f"no manifest {tmp_path / 'none.toml'}"


def test_a_mutation_of_python_alone_skips_the_cpp_suite():
    run = _runner()
    assert run.python_only({"file": "py/ldem/study/transfer.py"})
    assert not run.python_only({"file": "pkg/ldem/Simulation.cpp"}) and not run.python_only({"file": "py/src/bindings.cpp"})
    stages = []

    class Scratch:
        def __getattr__(self, stage):
            return lambda log, timeout, skip, fail_fast, direct: stages.append((stage, direct)) or []
        logs = "/nonexistent"
    run.run_suite(Scratch(), "m", 60, stages=("pytest",))
    assert stages == [("pytest", True), ("pytest", False)]


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def test_the_runner_stopped_kills_its_childrens_process_groups(tmp_path):
    """A build's compilers, a test run's workers: SIGTERM to the runner while
    a command of its runs ends that command's whole process group."""
    pidfile = tmp_path / "pid"
    code = (f"import importlib.util, signal; spec = importlib.util.spec_from_file_location('r', {RUNNER!r}); "
            "r = importlib.util.module_from_spec(spec); spec.loader.exec_module(r); "
            "signal.signal(signal.SIGTERM, signal.default_int_handler); "
            f"r.sh(['bash', '-c', 'sleep 300 & echo $! > {pidfile}; wait'])")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    t0 = time.monotonic()
    while not (pidfile.exists() and pidfile.read_text().strip()):
        assert proc.poll() is None and time.monotonic() - t0 < 60, proc.communicate()
        time.sleep(0.05)
    grandchild = int(pidfile.read_text())
    proc.send_signal(signal.SIGTERM)
    proc.communicate(timeout=30)
    t0 = time.monotonic()
    while _alive(grandchild):
        assert time.monotonic() - t0 < 10, f"process {grandchild} (sleep 300) outlived the runner"
        time.sleep(0.05)
