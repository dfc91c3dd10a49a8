"""What README says install.sh installs is there (a missing one fails, never
skips a test), and every subprocess runs the build under test."""
import importlib
import os
import shutil
import subprocess

import pytest

from conftest import BUILD_PY, ROOT, subprocess_env

# README, Install: the Debian packages install.sh installs, as Python modules.
MODULES = {"numpy": "python3-numpy", "scipy": "python3-scipy", "matplotlib": "python3-matplotlib",
           "meshio": "python3-meshio", "tqdm": "python3-tqdm", "distributed": "python3-distributed",
           "dask": "python3-distributed"}
COMMANDS = {"yade-double": "yade", "yade-double-batch": "yade"}

PRINT_LDEM = "import ldem, ldem._core; print(ldem.__file__); print(ldem._core.__file__)"


def _under_build(paths):
    return [p for p in paths if os.path.commonpath([os.path.realpath(p), BUILD_PY]) != BUILD_PY]


@pytest.mark.parametrize("module", sorted(MODULES))
def test_python_dependency_is_installed(module):
    try:
        importlib.import_module(module)
    except ImportError as e:
        pytest.fail(f"{module} cannot be imported ({e}); README lists Debian's {MODULES[module]} as installed "
                    f"by install.sh: run bash install.sh")


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_command_is_installed(command):
    assert shutil.which(command), (f"{command} is not on PATH; README lists Debian's {COMMANDS[command]} as "
                                   f"installed by install.sh: run bash install.sh")


def test_python_subprocess_imports_the_build_under_test(tmp_path):
    r = subprocess.run(["/usr/bin/python3", "-c", PRINT_LDEM], capture_output=True, text=True, cwd=tmp_path,
                       env=subprocess_env(), timeout=60)
    assert r.returncode == 0, r.stderr
    paths = r.stdout.split()
    assert len(paths) == 2 and not _under_build(paths), (paths, BUILD_PY)


def test_yade_subprocess_imports_the_build_under_test(tmp_path):
    script = tmp_path / "where.py"
    script.write_text(PRINT_LDEM.replace("; ", "\n") + "\n")
    r = subprocess.run([shutil.which("yade-double") or "yade-double", "-n", "-x", str(script)], capture_output=True,
                       text=True, cwd=tmp_path, env=subprocess_env(), timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    paths = [line for line in r.stdout.splitlines() if line.endswith(".py") or line.endswith(".so")]
    assert len(paths) == 2 and not _under_build(paths), (r.stdout, BUILD_PY)


def _packages():
    with open(os.path.join(ROOT, "debian-packages.txt")) as f:
        return [p for line in f if not line.startswith("#") for p in line.split()]


def test_install_page_lists_the_packages_install_sh_installs():
    with open(os.path.join(ROOT, "docs", "install.md")) as f:
        readme = " ".join(f.read().split())
    assert " ".join(_packages()) in readme.replace("`", "")


def test_the_test_command_installs_nothing():
    """tests/run_all.sh builds and tests the checkout: no apt or sudo of its own, no
    cmake --install, install.sh only for missing Debian packages (--deps-only, on
    a machine never set up); it asks dpkg what is missing (nothing is, here)."""
    with open(os.path.join(ROOT, "tests", "run_all.sh")) as f:
        code = [line for line in f if not line.lstrip().startswith("#")]
    text = "".join(code)
    for forbidden in ("apt", "sudo", "--install"):
        assert forbidden not in text, forbidden
    assert text.count("install.sh") == 2 and "bash install.sh --deps-only\n" in text  # the call and its message
    r = subprocess.run(["bash", os.path.join(ROOT, "tests", "missing_packages.sh")], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip() == "", r.stdout + r.stderr


def test_citation_and_license():
    """CITATION.cff names this version and the study ldem implements; LICENSE is there."""
    import ldem

    with open(os.path.join(ROOT, "CITATION.cff")) as f:
        cff = f.read()
    assert f"version: {ldem.__version__}\n" in cff
    assert "Size Effects and Mesh Independence in Dynamic Fracture Analysis of Brittle Materials" in cff
    with open(os.path.join(ROOT, "LICENSE")) as f:
        assert f.readline().strip() == "MIT License"
