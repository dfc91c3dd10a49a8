#!/usr/bin/env bash
# A lattice too big for one process, run on two: under a per-process memory
# limit (ulimit -v, address space), the 64^3 cube (3.7 million bars, 0.368 GB
# by the estimate of 100 B a bar) is refused at once in one process (the
# estimate is checked against the limit) and runs in 2 MPI ranks, each holding
# its slab (33 of the 64 layers with its halo, 0.19 GB by the estimate).
#   bash dev/mpi_memory_limit.sh [LIMIT_kB=300000] [MODULES=64]
# (from a build tree: build/pkg/ldem-bench; installed: ldem-bench on PATH)
set -uo pipefail
limit=${1:-300000} modules=${2:-64}
# The build tree's ldem-bench if there is one (an installed one may be older), else the installed one.
bench="$(dirname "$0")/../build/pkg/ldem-bench"
[ -x "$bench" ] || bench=$(command -v ldem-bench)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# One malloc arena: glibc reserves 64 MB of address space for each thread's
# arena, which would count against the limit without being used.
export MALLOC_ARENA_MAX=1
ulimit -v "$limit"
echo "limit: $limit kB of address space per process, a $modules^3 cube"
echo "one process:"
"$bench" --modules "$modules" --steps 5 --threads 1 --repeats 1
echo "exit $?"
echo "two MPI ranks:"
mpirun --oversubscribe --quiet -np 2 "$bench" --modules "$modules" --steps 5 --threads 1 --repeats 1
echo "exit $?"
