import os
import re
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.environ.get("LDEM_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
# A commit hash as the pages name one: 7 to 40 hex digits, a letter and a digit among them (not 1555344, not deadbeef).
COMMIT_HASH = re.compile(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}\b")


def load_file(name: str, *path: str):
    """A Python file of the repository (a script, a tool) as a module: ROOT/path..."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(name, os.path.join(ROOT, *path))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _build_python() -> str:
    """The python folder of the build under test: LDEM_BUILD_PYTHON (set by
    tests/CMakeLists.txt), else the first PYTHONPATH entry that holds ldem.
    Never a guessed folder: the installed package (/usr/local) or another build
    would be tested instead without anyone noticing."""
    path = os.environ.get("LDEM_BUILD_PYTHON")
    if not path:
        for entry in os.environ.get("PYTHONPATH", "").split(os.pathsep):
            if entry and os.path.isfile(os.path.join(entry, "ldem", "__init__.py")):
                path = entry
                break
    if not path:
        raise pytest.UsageError("tests/py: set LDEM_BUILD_PYTHON (or PYTHONPATH) to the build's python folder, "
                                "e.g. LDEM_BUILD_PYTHON=build/python; CTest sets it (tests/CMakeLists.txt)")
    path = os.path.realpath(path)
    if not os.path.isfile(os.path.join(path, "ldem", "__init__.py")):
        raise pytest.UsageError(f"tests/py: LDEM_BUILD_PYTHON={path} holds no ldem package")
    return path


BUILD_PY = _build_python()

# OpenMP threads that wait at a barrier sleep instead of spinning (read when
# ldem._core loads libgomp, so before the import; subprocesses inherit it). The
# tests share 2 cores with other work (ctest -j 2 runs the C++ tests beside them):
# a spinning thread then holds the core its partner needs, and the 0.12 m cube to
# mean strain 2.5e-4 on 2 threads took 13 s instead of 1.2. Results do not depend on it.
os.environ.setdefault("OMP_WAIT_POLICY", "passive")
if sys.path[:1] != [BUILD_PY]:
    sys.path.insert(0, BUILD_PY)

import ldem  # noqa: E402  (after the path is set)
import ldem._core  # noqa: E402


def _check_imported_from_build():
    for module in (ldem, ldem._core):
        where = os.path.realpath(module.__file__)
        if os.path.commonpath([where, BUILD_PY]) != BUILD_PY:
            raise pytest.UsageError(f"tests/py: {module.__name__} was imported from {where}, not from the build "
                                    f"under test {BUILD_PY}: another ldem comes first on sys.path")


_check_imported_from_build()


def pytest_configure(config):
    config.addinivalue_line("markers", "direct: a fast check of one quantity against hand values; runs first "
                                       "(tests/mutation/run.py gives the direct checks a pass of their own)")


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(items):
    """Direct checks first (a stable sort: each group keeps its file order), so
    that `pytest -x` stops at the check that names a bug, not at a long run
    that only notices something changed."""
    items.sort(key=lambda item: item.get_closest_marker("direct") is None)


def subprocess_env(**extra) -> dict:
    """The environment of every subprocess of the tests (python3, ldem, yade-double):
    the build under test first on PYTHONPATH, nothing else of ours."""
    return dict(os.environ, PYTHONPATH=BUILD_PY, LDEM_BUILD_PYTHON=BUILD_PY, **extra)


# A fast cube: 4^3 modules, a strain rate that is still quasi-static at this
# size (peak within 0.3 % of the rate 0.05 one), stopped when the load is lost.
FAST = dict(size=0.08, strain_rate=0.1, stop_at="load_loss")

LDEM_SCRIPT = os.path.join(ROOT, "py", "bin", "ldem")


def run_cli(*args, cwd=None, timeout=600):
    """Runs the `ldem` command itself (py/bin/ldem, what `ldem` on PATH is) on the build tree."""
    return subprocess.run(["/usr/bin/python3", LDEM_SCRIPT, *args], capture_output=True,
                          text=True, env=subprocess_env(), cwd=cwd, timeout=timeout)


@pytest.fixture
def cli():
    return run_cli


def picture(path, min_side=300):
    """A PNG written by ldem, as an RGB array: readable, of a figure's size and not blank."""
    import matplotlib.image

    img = matplotlib.image.imread(str(path))
    assert img.ndim == 3 and img.shape[2] in (3, 4), (path, img.shape)
    assert min(img.shape[:2]) >= min_side, (path, img.shape)
    rgb = img[:, :, :3]
    assert len(np.unique(rgb.reshape(-1, 3), axis=0)) > 10, f"{path}: blank picture"
    return rgb


def undamaged_on_white():
    """The RGB an undamaged bar shows on white: ldem.plots draws it faint
    (STATE_ALPHA) in its colour, so the pixel is alpha c + (1 - alpha) white."""
    import matplotlib.colors

    from ldem import plots

    alpha = plots.STATE_ALPHA[plots.UNDAMAGED]
    return tuple(alpha * np.array(matplotlib.colors.to_rgb(plots.STATE_COLOURS[plots.UNDAMAGED])) + 1 - alpha)


def colour_share(rgb, colour, tol=0.15):
    """Fraction of the pixels within tol of colour (matplotlib's name or RGB)."""
    import matplotlib.colors

    want = np.array(matplotlib.colors.to_rgb(colour))
    return float(np.mean(np.all(np.abs(rgb - want) <= tol, axis=2)))
