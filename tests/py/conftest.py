import os
import subprocess
import sys

import pytest

ROOT = os.environ.get("LDEM_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BUILD_PY = os.path.join(ROOT, "build", "python")
if BUILD_PY not in sys.path:
    sys.path.insert(0, BUILD_PY)

# A fast cube: 4^3 modules, a strain rate that is still quasi-static at this
# size (peak within 0.3 % of the rate 0.05 one), stopped when the load is lost.
FAST = dict(size=0.08, strain_rate=0.1, stop_at="load_loss")


def run_cli(*args, cwd=None):
    """Runs the `ldem` command itself (py/bin/ldem, what `ldem` on PATH is) on the build tree."""
    env = dict(os.environ, PYTHONPATH=BUILD_PY)
    return subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "py", "bin", "ldem"), *args], capture_output=True,
                          text=True, env=env, cwd=cwd, timeout=600)


@pytest.fixture
def cli():
    return run_cli
