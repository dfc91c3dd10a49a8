"""The mutation catalogue (tests/mutation/mutations.toml) stays applicable: each
mutation's file exists and its sed expression changes it. A refactor that moves
the code a mutation targets must move the mutation too, or the sweep would
report it as caught while testing nothing."""
import os
import subprocess
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
