#!/bin/sh
# Usage: test-cohort-slurm.sh VIMLOP WORK_DIR SEQUENCE_DIR CT
# A cohort on a real one-node Slurm cluster (slurm-cluster.sh, on loopback):
#  1. eight rows (register with three methods and settings, P1 with two
#     seeds) submitted with `vimlop cohort submit --slurm` as job arrays split
#     under a MaxArraySize of 5, merged by the dependent merge job; the same
#     manifest run here with `vimlop cohort run`; the two merged tables must
#     be identical outside their volatile columns (times, hosts, threads:
#     1 per row on Slurm, 2 here);
#  2. a manifest with two broken rows (a missing CT, an unreadable video):
#     every other row runs, the broken ones are listed with their one-line
#     errors; after the fix `vimlop cohort resubmit --failed` runs those two
#     rows only.
# Exits 77 (ctest's SKIP) when Slurm's packages are missing. The daemons are
# stopped by their process ids whatever happens.
set -eu
vimlop=$1
work=$2
sequence=$3
ct=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
cluster="$work/cluster"
status=0
SLURM_CLUSTER_MAX_ARRAY_SIZE=5 "$here/slurm-cluster.sh" start "$cluster" || status=$?
if [ "$status" -ne 0 ]; then
  exit "$status"
fi
trap '"$here/slurm-cluster.sh" stop "$cluster" >/dev/null 2>&1' EXIT INT TERM
. "$cluster/env.sh"

fail() {
  echo "test-cohort-slurm.sh: $*" >&2
  for log in "$1"/slurm/logs/*.out; do
    [ -f "$log" ] && { echo "--- $log" >&2; tail -n 5 "$log" >&2; }
  done 2>/dev/null
  exit 1
}

# Waits until no job of the cohort in $1 is queued or running.
wait_for_cohort() {
  deadline=$(($(date +%s) + 240))
  while squeue --noheader --format=%i | grep -q .; do
    [ "$(date +%s)" -lt "$deadline" ] || fail "$1" "Slurm jobs still queued after 240 s"
    sleep 0.5
  done
}

row() { # id, options
  echo "$1,register,$sequence/model.vtp,$sequence/frames,$sequence/intrinsics.yaml,$sequence/tracker.csv,manual:$sequence/truth/poses.json,$sequence/truth/poses.json,--no-video --no-report $2"
}
header="id,command,mesh,frames,intrinsics,tracker,init,truth,options"
{
  echo "$header"
  row vimlop "--method vimlop"
  row imlp "--method imlp"
  row trimmed-icp "--method trimmed-icp"
  row vimlop-kappa-50 "--kappa 50"
  row vimlop-few-iterations "--max-iterations 5"
  row imlp-trim "--method imlp --trim 0.2"
  echo "p1-seed1,evaluate synthetic,$sequence/model.vtp,,,,,,\"--trials 2 --seed 1 --methods vimlop,imlp,trimmed-icp\""
  echo "p1-seed2,evaluate synthetic,$sequence/model.vtp,,,,,,\"--trials 2 --seed 2 --methods vimlop,imlp,trimmed-icp\""
} >"$work/cohort.csv"

start=$(date +%s.%N)
"$vimlop" cohort submit "$work/cohort.csv" --out "$work/slurm" --slurm --cpus-per-task 1 --array-chunk 1
wait_for_cohort "$work/slurm"
slurm_s=$(echo "$start $(date +%s.%N)" | awk '{ printf "%.1f", $2 - $1 }')
test -f "$work/slurm/table.csv" || fail "$work/slurm" "the merge job wrote no table"
arrays=$(grep -c '"job_id"' "$work/slurm/slurm/submission-1.json")
[ "$arrays" -eq 2 ] || fail "$work/slurm" "8 tasks under MaxArraySize 5 make $arrays arrays, not 2"

start=$(date +%s.%N)
"$vimlop" cohort run "$work/cohort.csv" --out "$work/local" --jobs 1 --threads-per-job 2
local_s=$(echo "$start $(date +%s.%N)" | awk '{ printf "%.1f", $2 - $1 }')
"$vimlop" cohort merge "$work/local"
python3 "$here/compare-cohort-tables.py" "$work/slurm" "$work/local"
echo "test-cohort-slurm.sh: 8 rows: $slurm_s s through Slurm (submission to merged table), $local_s s with cohort run"

# 2. Broken rows, then their fix and a resubmission of the failed ones only.
printf 'not a video' >"$work/broken.avi"
{
  echo "$header,video"
  echo "$(row good ""),"
  echo "no-ct,register,,$sequence/frames,$sequence/intrinsics.yaml,$sequence/tracker.csv,manual:$sequence/truth/poses.json,,--no-video --no-report --ct $work/ct-missing.inv3,"
  echo "bad-video,register,$sequence/model.vtp,,$sequence/intrinsics.yaml,$sequence/tracker.csv,manual:$sequence/truth/poses.json,,--no-video --no-report,$work/broken.avi"
} >"$work/broken.csv"
"$vimlop" cohort submit "$work/broken.csv" --out "$work/broken" --slurm --cpus-per-task 1
wait_for_cohort "$work/broken"
"$vimlop" cohort status "$work/broken" | tee "$work/broken-status.txt"
grep -q "^cohort '.*': 3 rows: 1 complete, 2 failed$" "$work/broken-status.txt" ||
  fail "$work/broken" "expected 1 complete and 2 failed rows"
grep -q "^cohort: failed no-ct (attempt 1 on .*, Slurm [0-9]*_[0-9]*): '$work/ct-missing.inv3': no such file or folder$" \
  "$work/broken-status.txt" || fail "$work/broken" "the missing CT is not said in one line"
grep -q "^cohort: failed bad-video (attempt 1 on .*): .*broken.avi" "$work/broken-status.txt" ||
  fail "$work/broken" "the unreadable video is not said in one line"
grep -q '"state": "failed"' "$work/broken/table.json" || fail "$work/broken" "the merged table lists no failure"

cp "$ct" "$work/ct-missing.inv3"
ffmpeg -loglevel error -y -framerate 30 -i "$sequence/frames/frame%03d.png" -c:v mjpeg -q:v 2 "$work/broken.avi"
"$vimlop" cohort resubmit "$work/broken" --failed | tee "$work/resubmit.txt"
grep -q "^cohort: submission 2: 2 rows in " "$work/resubmit.txt" || fail "$work/broken" "the resubmission is not of the two failed rows"
wait_for_cohort "$work/broken"
"$vimlop" cohort status "$work/broken" | tee "$work/fixed-status.txt"
grep -q "^cohort '.*': 3 rows: 3 complete$" "$work/fixed-status.txt" || fail "$work/broken" "the fixed rows did not complete"
good_attempts=$(grep -c '"state": ' "$work/broken/status/good.json")
[ "$good_attempts" -eq 1 ] || fail "$work/broken" "the good row ran $good_attempts times"
echo "test-cohort-slurm.sh: the broken rows failed alone, and ran alone after their fix"
