#!/bin/sh
# Usage: test-cohort-killed.sh VIMLOP WORK_DIR SEQUENCE_DIR
# `vimlop cohort run` killed with SIGKILL in the middle of a cohort, then run
# again: the second run must finish the rest without redoing a row the first
# one completed, and the row the first run was on must not go on working
# without it (its command ends with its runner).
set -eu
vimlop=$1
work=$2
sequence=$3
rm -rf "$work"
mkdir -p "$work"
manifest="$work/cohort.csv"
{
  echo "id,command,mesh,frames,intrinsics,tracker,init,truth,options"
  for method in vimlop imlp trimmed-icp vimlop imlp; do
    n=$((${n:-0} + 1))
    echo "row-$n,register,$sequence/model.vtp,$sequence/frames,$sequence/intrinsics.yaml,$sequence/tracker.csv,manual:$sequence/truth/poses.json,$sequence/truth/poses.json,--method $method --no-video --no-report"
  done
} >"$manifest"

"$vimlop" cohort run "$manifest" --out "$work/out" --jobs 1 >"$work/first.log" 2>&1 &
runner=$!
# Kill it once two rows are complete, while it works on the third.
tries=0
until [ "$(grep -c ': complete in' "$work/first.log" 2>/dev/null || true)" -ge 2 ]; do
  tries=$((tries + 1))
  if [ "$tries" -gt 1200 ] || ! kill -0 "$runner" 2>/dev/null; then
    cat "$work/first.log"
    echo "test-cohort-killed.sh: the first run did not complete two rows" >&2
    exit 1
  fi
  sleep 0.1
done
kill -KILL "$runner"
wait "$runner" 2>/dev/null || true
done_before=$(grep -c ': complete in' "$work/first.log")
echo "test-cohort-killed.sh: killed the runner after $done_before complete rows"

# The row it was on ends with it: no lock stays held, no command keeps running.
sleep 1
if pgrep -f -- "--out $work/out/jobs/" >/dev/null; then
  pgrep -af -- "--out $work/out/jobs/" >&2
  echo "test-cohort-killed.sh: a row's command outlived its killed runner" >&2
  exit 1
fi
"$vimlop" cohort status "$work/out"

"$vimlop" cohort run "$manifest" --out "$work/out" --jobs 2 >"$work/second.log" 2>&1
cat "$work/second.log"
summary=$(grep '^cohort: 5 rows: ' "$work/second.log")
case "$summary" in
  "cohort: 5 rows: $done_before complete before, $((5 - done_before)) ran now ($((5 - done_before)) complete,"*) ;;
  *)
    echo "test-cohort-killed.sh: unexpected summary: $summary" >&2
    exit 1
    ;;
esac
# The rows complete before the kill ran once, in the first run only.
for row in $(grep ': complete in' "$work/first.log" | sed 's/^cohort: \[[0-9/]*\] \([^:]*\):.*/\1/'); do
  attempts=$(grep -c '"state": ' "$work/out/status/$row.json")
  if [ "$attempts" -ne 1 ]; then
    echo "test-cohort-killed.sh: $row, complete before the kill, has $attempts attempts" >&2
    exit 1
  fi
done
for n in 1 2 3 4 5; do
  test -f "$work/out/jobs/row-$n/result.json"
done
echo "test-cohort-killed.sh: the second run finished the other $((5 - done_before)) rows; none was done twice"
