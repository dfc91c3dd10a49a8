#!/usr/bin/env bash
# The whole test suite: builds this checkout in a scratch folder (build-tests/,
# or $LDEM_TEST_BUILD) and runs the GoogleTest and pytest suites through CTest.
# Installs nothing (no apt, no sudo, nothing under /usr/local): the Debian
# packages come from install.sh, and a missing one stops here with its name.
set -euo pipefail
cd "$(dirname "$0")/.."
missing=$(bash tests/missing_packages.sh)
if [ -n "$missing" ]; then
  echo "tests/run_all.sh: missing Debian packages:$missing (run install.sh first: it installs them)" >&2
  exit 2
fi
build=${LDEM_TEST_BUILD:-build-tests}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 > /dev/null
cmake --build "$build"
ctest --test-dir "$build" --output-on-failure -j 2 --timeout 1500
