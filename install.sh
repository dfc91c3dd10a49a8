#!/usr/bin/env bash
# Installs what ldem needs from Debian (only what is missing), builds it in
# ./build and installs the `ldem` command and the `ldem` Python package for
# Debian's /usr/bin/python3 (and so for yade-double) under /usr/local.
#   bash install.sh --deps-only   only the missing Debian packages (tests/run_all.sh
#                                 uses it on a machine that has never been set up)
set -euo pipefail
cd "$(dirname "$0")"

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"

missing=$(bash tests/missing_packages.sh)
if [ -n "$missing" ]; then
  echo "install.sh: installing from Debian:$missing"
  $SUDO apt-get update -q
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q $missing
fi
[ "${1:-}" = "--deps-only" ] && exit 0

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 > build.log 2>&1 ||
  { cat build.log; exit 1; }
cmake --build build >> build.log 2>&1 || { tail -50 build.log; exit 1; }
# A package folder from an older ldem may hold modules that are gone: replace it whole.
site=$(/usr/bin/python3 -c "import sys; print(f'/usr/local/lib/python3.{sys.version_info.minor}/dist-packages/ldem')")
$SUDO rm -rf "$site"
$SUDO cmake --install build >> build.log 2>&1 || { tail -20 build.log; exit 1; }
echo "install.sh: built and installed ldem ($(command -v ldem))"
