#!/bin/sh
# Usage: run-fuzzers.sh BUILD_DIR SECONDS
# Runs every vimlop-fuzz-* in BUILD_DIR/bin for SECONDS each, starting from the
# seed corpus in Testing/Fuzzing/corpus/<name>. New interesting inputs go to
# BUILD_DIR/fuzz-corpus/<name>; a crash leaves its input in BUILD_DIR/fuzz-crashes
# and fails the run (add the input to the seed corpus once fixed).
set -u
build=$1
seconds=$2
root=$(cd "$(dirname "$0")/.." && pwd)
status=0
mkdir -p "$build/fuzz-crashes"
for fuzzer in "$build"/bin/vimlop-fuzz-*; do
  name=${fuzzer##*/vimlop-fuzz-}
  mkdir -p "$build/fuzz-corpus/$name"
  log="$build/fuzz-$name.log"
  "$fuzzer" -max_total_time="$seconds" -print_final_stats=1 -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$build/fuzz-crashes/$name-" \
    "$build/fuzz-corpus/$name" "$root/Testing/Fuzzing/corpus/$name" >"$log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  echo "fuzz $name: ${runs:-?} executions in ${seconds} s, exit code $rc"
  if [ "$rc" -ne 0 ]; then
    status=1
    tail -n 30 "$log"
  fi
done
exit $status
