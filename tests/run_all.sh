#!/usr/bin/env bash
# The whole test suite: installs and builds what is missing, then runs the
# GoogleTest and pytest suites through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash install.sh
ctest --test-dir build --output-on-failure -j 2 --timeout 1500
