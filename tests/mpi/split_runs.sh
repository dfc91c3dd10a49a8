#!/usr/bin/env bash
# Runs one specimen (`ldem cube ...` or `ldem run FILE ...`) under mpirun on
# each number of ranks given, then checks the results are the same bit for bit
# (same_run.py), and that ParaView opens the largest split's bars.pvtu.
#   split_runs.sh OUT "1 2 3" cube|run [FILE] [options...]
# The environment gives the package under test (PYTHONPATH, CTest sets it).
set -euo pipefail
out=$1 ranks=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
# mpirun refuses root unless told. Nothing else is set: ranks made to yield the
# core while they wait (mpi_yield_when_idle=1) step hundreds of times slower
# beside other work (results/mpi/busy/); with more ranks than cores OpenMPI
# yields by itself.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
rm -rf "$out"
dirs=()
for p in $ranks; do
  mpirun --oversubscribe --quiet -np "$p" /usr/bin/python3 -m ldem "$@" --out "$out/np$p" \
    > "$out.np$p.log" 2>&1 || { cat "$out.np$p.log"; exit 1; }
  grep -E "^(peak|separated|NOT)" "$out.np$p.log" | sed "s/^/np $p: /"
  dirs+=("$out/np$p")
done
/usr/bin/python3 "$here/same_run.py" "${dirs[@]}"
# ParaView opens the parallel file of the largest split, with every bar.
last=${dirs[${#dirs[@]}-1]}
if [ -e "$last/bars.pvtu" ]; then
  xvfb-run -a -s "-noreset -screen 0 640x480x24" pvbatch "$here/pvtu_cells.py" "$last"
fi
