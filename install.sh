#!/usr/bin/env bash
# Installs what ldem needs from Debian (only what is missing), builds it in
# ./build and installs the `ldem` command and the `ldem` Python package for
# Debian's /usr/bin/python3 (and so for yade-double) under /usr/local.
set -euo pipefail
cd "$(dirname "$0")"

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"

DEPS="cmake ninja-build g++ libeigen3-dev libboost-dev libgtest-dev pybind11-dev python3-dev
      python3-numpy python3-matplotlib python3-meshio python3-tqdm python3-pytest python3-scipy
      python3-distributed yade"
missing=""
for p in $DEPS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "install.sh: installing from Debian:$missing"
  $SUDO apt-get update -q
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -q $missing
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 > build.log 2>&1 ||
  { cat build.log; exit 1; }
cmake --build build >> build.log 2>&1 || { tail -50 build.log; exit 1; }
$SUDO cmake --install build >> build.log 2>&1 || { tail -20 build.log; exit 1; }
echo "install.sh: built and installed ldem ($(command -v ldem))"
