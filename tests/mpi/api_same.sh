#!/usr/bin/env bash
# api_run.py on 1 and 2 ranks prints the same line (same curve and summary, bit for bit).
set -euo pipefail
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
here=$(cd "$(dirname "$0")" && pwd)
one=$(mpirun --oversubscribe --quiet -np 1 /usr/bin/python3 "$here/api_run.py")
two=$(mpirun --oversubscribe --quiet -np 2 /usr/bin/python3 "$here/api_run.py")
echo "1 rank:  $one"
echo "2 ranks: $two"
[ "$one" = "$two" ] && [[ "$one" == *"separated True"* ]]
