"""pip's view of ldem: the package is what CMake stages in a build tree
(build/python/ldem: the Python modules, the compiled ldem._core and the build's
git commit), so building a wheel is running CMake and copying that folder.

    pip install .                                  # needs cmake, ninja, g++, Eigen, Boost, pybind11
    pip install --no-build-isolation --no-index .  # offline, with Debian's setuptools and wheel
"""
import os
import shutil
import subprocess
import sys

from setuptools import Distribution, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    """The build step setuptools runs for a package with compiled parts."""

    def run(self):
        cmake_build = os.path.normpath(os.path.join(os.path.abspath(self.build_lib), "..", "cmake"))
        subprocess.check_call(["cmake", "-S", ROOT, "-B", cmake_build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                               "-DBUILD_TESTING=OFF", f"-DPython_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", cmake_build, "--target", "_core", "ldem_python", "ldem_build_info"])
        target = os.path.join(self.build_lib, "ldem")
        shutil.rmtree(target, ignore_errors=True)
        shutil.copytree(os.path.join(cmake_build, "python", "ldem"), target,
                        ignore=shutil.ignore_patterns("__pycache__"))


class BinaryDistribution(Distribution):
    def has_ext_modules(self):  # ldem._core is compiled: a platform wheel
        return True


setup(cmdclass={"build_ext": CMakeBuild}, distclass=BinaryDistribution, packages=[])
