#!/bin/bash
# A yade-batch sweep that says which of its jobs failed: yade-double-batch
# reports each job's exit status, then returns 0 whatever they were.
#
#   bash scripts/yade_batch.sh TABLE SCRIPT [LOGS]
#
# runs SCRIPT once per row of TABLE, one thread a job, each job's log in
# LOGS/<description>.log (default out/logs, made first: without it YADE
# 2023.02's yade-batch fails every job, then hangs), then names the jobs
# that failed and exits 1, else 0 (2: bad arguments).
set -u -o pipefail
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
    echo "yade_batch.sh: error: usage: bash scripts/yade_batch.sh TABLE SCRIPT [LOGS]" >&2
    exit 2
fi
table=$1 script=$2 logs=${3:-out/logs}
for f in "$table" "$script"; do
    [ -f "$f" ] || { echo "yade_batch.sh: error: no file $f" >&2; exit 2; }
done
mkdir -p "$logs" || exit 2
report=$(mktemp) || exit 1
trap 'rm -f "$report"' EXIT
yade-double-batch --job-threads 1 --log "$logs/@.log" "$table" "$script" 2>&1 | tee "$report"
status=$?
# yade-batch's line of a finished job: "#1 (u012_s2) FAILED  (exit status 512), duration ..., log ..."
jobs=$(grep -cE '^#[0-9]+ \(.*\) (done|FAILED) ' "$report")
failed=$(sed -n 's/^#[0-9]* (\(.*\)) FAILED .*/\1/p' "$report" | paste -sd' ' -)
if [ -n "$failed" ]; then
    echo "yade_batch.sh: $(wc -w <<< "$failed") of $jobs jobs failed: $failed (their logs: $logs/<job>.log)" >&2
    exit 1
fi
exit $status
