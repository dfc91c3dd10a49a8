#!/usr/bin/env bash
# More ranks than module layers: exit 2 and one line that says so.
set -uo pipefail
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
err=$(mpirun --oversubscribe --quiet -np 4 /usr/bin/python3 -m ldem cube --size 0.06 --out "$1" 2>&1 >/dev/null)
code=$?
echo "exit $code: $err"
[ "$code" -eq 2 ] && [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] &&
  [[ "$err" == "ldem cube: error: 4 MPI ranks for 3 module layers"* ]]
