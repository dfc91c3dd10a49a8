#!/usr/bin/env bash
# MPI figures for README (One lattice over many processes): ldem-bench on the
# 48^3 cube in 1 and in 2 MPI ranks of 1 thread each, interleaved RUNS times;
# prints each run and the medians: ns per bar-step, parallel efficiency
# t(1) / (2 t(2)), bytes each rank sends per step, peak memory per rank.
#   bash dev/bench_mpi.sh [RUNS=5] [MODULES=48]
set -euo pipefail
runs=${1:-5} modules=${2:-48}
# The build tree's ldem-bench if there is one (an installed one may be older), else the installed one.
bench="$(dirname "$0")/../build/pkg/ldem-bench"
[ -x "$bench" ] || bench=$(command -v ldem-bench)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=$(mktemp)
for r in $(seq "$runs"); do
  for p in 1 2; do
    mpirun --quiet -np "$p" --bind-to core "$bench" --modules "$modules" --steps 200 --threads 1 --repeats 3 |
      tee -a "$out"
  done
done
/usr/bin/python3 - "$out" <<'PY'
import json, statistics, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
med = lambda p, k: statistics.median(r[k] for r in rows if r["ranks"] == p)
t1, t2 = med(1, "ns_per_bar_step"), med(2, "ns_per_bar_step")
print(f"{rows[0]['modules']}^3, {rows[0]['bars']} bars, medians of {len(rows) // 2} runs each:")
for p in (1, 2):
    print(f"  {p} rank(s): {med(p, 'ns_per_bar_step'):.3f} ns per bar-step, "
          f"{med(p, 'bytes_sent_per_rank_step'):.0f} B sent per rank per step, "
          f"peak memory {med(p, 'peak_rss_bytes') / 1e6:.1f} MB per rank")
print(f"  speed-up {t1 / t2:.2f}, parallel efficiency {t1 / (2 * t2):.2f}")
PY
rm -f "$out"
