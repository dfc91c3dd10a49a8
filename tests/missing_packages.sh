#!/usr/bin/env bash
# Prints the packages of debian-packages.txt that are not installed (nothing if
# all are). Reads dpkg's database only: needs no root and installs nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
missing=""
for p in $(grep -v '^#' debian-packages.txt); do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
echo $missing
