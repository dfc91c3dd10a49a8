#!/usr/bin/env bash
# The whole test suite: builds this checkout in a scratch folder (build-tests/,
# or $LDEM_TEST_BUILD) and runs the GoogleTest and pytest suites through CTest.
# It installs nothing of ldem (nothing under /usr/local, the tests import the
# package from that build). Only on a machine that lacks Debian packages ldem
# needs (a fresh CI machine) does it first install those, with install.sh
# --deps-only; on a machine set up by install.sh it runs no apt and no sudo.
set -euo pipefail
cd "$(dirname "$0")/.."
missing=$(bash tests/missing_packages.sh)
if [ -n "$missing" ]; then
  echo "tests/run_all.sh: first the missing Debian packages:$missing (install.sh --deps-only)" >&2
  bash install.sh --deps-only
fi
build=${LDEM_TEST_BUILD:-build-tests}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 > /dev/null
cmake --build "$build"
# Each pytest file is a CTest test with a timeout of its own (tests/CMakeLists.txt).
ctest --test-dir "$build" --output-on-failure -j 2 --timeout 2400  # the default of the other tests (MPI)
