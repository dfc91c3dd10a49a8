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
