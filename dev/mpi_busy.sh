#!/usr/bin/env bash
# How fast a small split run steps beside CPU-bound work (results/mpi/busy/):
# the MPI tests' cube (0.06 m, 1 /s, 414 bars) on 2 ranks (bound to cores,
# mpirun's default for 2, and unbound) and on 3, beside 0, 1 and 2 busy loops.
# Each run is stopped after SECONDS; it prints steps per second of wall: a run
# that finishes, its steps over its own wall; one stopped, the steps it made
# from its first record to the stop.
#   bash dev/mpi_busy.sh PYTHON_DIR [SECONDS=30] [OMPI_MCA_mpi_yield_when_idle]
# PYTHON_DIR: a build's staged package (build/python). Run it on an idle machine.
set -uo pipefail
pydir=$(cd "$1" && pwd) seconds=${2:-30} yield=${3:-}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
[ -n "$yield" ] && export OMPI_MCA_mpi_yield_when_idle=$yield
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
rate() {  # ranks, mpirun options...
  local np=$1 out="$work/run" first="" t0 now step
  shift
  rm -rf "$out"
  PYTHONPATH=$pydir timeout "$seconds" mpirun --oversubscribe --quiet -np "$np" "$@" /usr/bin/python3 -m ldem cube \
    --threads 1 --size 0.06 --load uniform --strain-rate 1.0 --out "$out" > /dev/null 2>&1 &
  local pid=$!
  # Steps over the run's own wall if it finishes; else from the first step seen to the stop (no set-up).
  while kill -0 "$pid" 2>/dev/null; do
    sleep 1
    step=$(tail -1 "$out/curve.csv" 2>/dev/null | cut -d, -f1)
    [[ "$step" =~ ^[0-9]+$ ]] || continue
    now=$(date +%s.%N)
    [ -z "$first" ] && { first=$step; t0=$now; }
    last=$step tl=$now
  done
  wait "$pid"
  if [ -e "$out/summary.json" ]; then
    /usr/bin/python3 -c "import json,sys; s=json.load(open(sys.argv[1])); print(round(s['steps'] / s['wall_s']))" \
      "$out/summary.json"
  else
    /usr/bin/python3 -c "import sys; a=[float(x) for x in sys.argv[1:]]; print(round((a[1]-a[0])/max(a[3]-a[2],1e-9)))" \
      "${first:-0}" "${last:-0}" "${t0:-0}" "${tl:-1}"
  fi
}
echo "steps per second (ldem cube --size 0.06, 1 /s; ${seconds} s at most a run)"
echo "| busy loops | 2 ranks, bound | 2 ranks, unbound | 3 ranks |"
echo "|---|---|---|---|"
for hogs in 0 1 2; do
  for _ in $(seq "$hogs"); do (while :; do :; done) & done
  echo "| $hogs | $(rate 2) | $(rate 2 --bind-to none) | $(rate 3 --bind-to none) |"
  kill $(jobs -p) 2>/dev/null
  wait 2>/dev/null
done
