#!/bin/sh
# Usage: run-fuzzers.sh BUILD_DIR SECONDS [NAME...]
# Runs every vimlop-fuzz-* in BUILD_DIR/bin (or only the NAMEs given) for
# SECONDS each, starting from the seed corpus in Testing/Fuzzing/corpus/<name>.
# New interesting inputs go to BUILD_DIR/fuzz-corpus/<name>; a crash, a leak,
# undefined behaviour, a timeout (10 s per input) or an allocation above
# 2 GiB leaves its input in BUILD_DIR/fuzz-crashes and fails the run (add
# the input to the seed corpus once fixed). Prints one line per fuzzer with
# its executions; they are also appended to BUILD_DIR/fuzz-executions.txt.
set -u
build=$1
seconds=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
status=0
mkdir -p "$build/fuzz-crashes"
# UBSan findings stop the input like a crash (by default UBSan only prints).
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
if [ $# -eq 0 ]; then
  set -- $(cd "$build/bin" && ls vimlop-fuzz-* | sed 's/^vimlop-fuzz-//')
fi
for name in "$@"; do
  fuzzer="$build/bin/vimlop-fuzz-$name"
  mkdir -p "$build/fuzz-corpus/$name"
  log="$build/fuzz-$name.log"
  start=$(date +%s)
  "$fuzzer" -max_total_time="$seconds" -print_final_stats=1 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -timeout=10 -artifact_prefix="$build/fuzz-crashes/$name-" \
    "$build/fuzz-corpus/$name" "$root/Testing/Fuzzing/corpus/$name" >"$log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  line="fuzz $name: ${runs:-?} executions in $(( $(date +%s) - start )) s, exit code $rc"
  echo "$line"
  echo "$(date -u +%FT%TZ) $line" >>"$build/fuzz-executions.txt"
  if [ "$rc" -ne 0 ]; then
    status=1
    tail -n 40 "$log"
  fi
done
exit $status
