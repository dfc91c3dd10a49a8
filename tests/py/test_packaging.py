"""Another C++ project finds ldem with CMake (find_package(ldem), ldem::ldem):
the build under test installed into a scratch prefix, the consumer project of
tests/consumer built against it, and its run compared with ldem's own."""
import os
import subprocess

import ldem
from conftest import BUILD_PY, ROOT


def test_find_package_ldem_from_a_consumer_project(tmp_path):
    build = os.path.dirname(BUILD_PY)  # the build tree whose python folder is under test
    prefix, consumer = tmp_path / "prefix", tmp_path / "consumer"
    subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], check=True, capture_output=True)
    assert (prefix / "lib" / "cmake" / "ldem" / "ldemConfig.cmake").is_file()
    assert (prefix / "include" / "ldem" / "Simulation.hpp").is_file() and (prefix / "lib" / "libldem.a").is_file()
    r = subprocess.run(["cmake", "-S", os.path.join(ROOT, "tests", "consumer"), "-B", str(consumer), "-G", "Ninja",
                        f"-DCMAKE_PREFIX_PATH={prefix}", "-DCMAKE_BUILD_TYPE=Release"], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    r = subprocess.run(["cmake", "--build", str(consumer)], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    r = subprocess.run([str(consumer / "consumer")], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    peak = ldem.CubeTest(size=0.04, strain_rate=0.5, stop_at="load_loss", threads=1).run().peak_stress_MPa
    assert r.stdout.strip() == f"peak {peak:.6f} MPa, load_lost"


def test_pip_install_builds_the_package_with_cmake(tmp_path):
    """`pip install .` (offline: Debian's setuptools, no build isolation) into a
    scratch folder: the package with its compiled core and the `ldem` command,
    giving the same run as the build under test."""
    import sys

    site = tmp_path / "site"
    r = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index",
                        "--target", str(site), ROOT], capture_output=True, text=True, timeout=1500)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    env = dict(os.environ, PYTHONPATH=str(site))
    env.pop("LDEM_BUILD_PYTHON", None)
    r = subprocess.run([str(site / "bin" / "ldem"), "--version"], capture_output=True, text=True, env=env)
    assert r.returncode == 0 and r.stdout.startswith(f"ldem {ldem.__version__}"), r.stdout + r.stderr
    code = ("import ldem; assert ldem.__file__.startswith(%r), ldem.__file__; "
            "print(repr(ldem.CubeTest(size=0.04, strain_rate=0.5, stop_at='load_loss', threads=1).run()"
            ".peak_stress_MPa))" % str(site))
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    peak = ldem.CubeTest(size=0.04, strain_rate=0.5, stop_at="load_loss", threads=1).run().peak_stress_MPa
    assert float(r.stdout) == peak
