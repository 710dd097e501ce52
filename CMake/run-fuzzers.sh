#!/bin/sh
# Usage: run-fuzzers.sh BUILD_DIR SECONDS [NAME...]
# Runs every vimlop-fuzz-* in BUILD_DIR/bin (or only the NAMEs given) for
# SECONDS each (inputs up to the size max_len() gives it), starting from the
# seed corpus in Testing/Fuzzing/corpus/<name>.
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
# ASan keeps freed memory in quarantine to catch use after free; a frame of
# 8192 x 8192 pixels decoded per input fills the default quarantine past the
# 2 GiB limit below, so keep it small.
export ASAN_OPTIONS="quarantine_size_mb=64${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
# Leaks stay findings, except the libraries' own listed there.
export LSAN_OPTIONS="suppressions=$root/Testing/Fuzzing/leak-suppressions.txt${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
if [ $# -eq 0 ]; then
  set -- $(cd "$build/bin" && ls vimlop-fuzz-* | sed 's/^vimlop-fuzz-//')
fi
# The largest input libFuzzer makes (without it libFuzzer stays near the
# seeds' size, 4 KiB at first). Sized to the seeds' complete files with room
# to grow: a patient's CT, mesh or video is larger, but the structure the
# readers parse (headers, element lists, slices, frames) repeats.
max_len() {
  case $1 in
    mesh | ct | frames) echo 262144 ;;
    field) echo 131072 ;;
    video) echo 524288 ;;
    *) echo 65536 ;;
  esac
}
for name in "$@"; do
  fuzzer="$build/bin/vimlop-fuzz-$name"
  mkdir -p "$build/fuzz-corpus/$name"
  log="$build/fuzz-$name.log"
  start=$(date +%s)
  "$fuzzer" -max_total_time="$seconds" -max_len="$(max_len "$name")" -print_final_stats=1 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -timeout=10 -artifact_prefix="$build/fuzz-crashes/$name-" \
    "$build/fuzz-corpus/$name" "$root/Testing/Fuzzing/corpus/$name" >"$log" 2>&1
  rc=$?
  runs=$(grep -a -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  line="fuzz $name: ${runs:-?} executions in $(( $(date +%s) - start )) s, exit code $rc"
  echo "$line"
  echo "$(date -u +%FT%TZ) $line" >>"$build/fuzz-executions.txt"
  if [ "$rc" -ne 0 ]; then
    status=1
    tail -n 40 "$log"
  fi
done
exit $status
