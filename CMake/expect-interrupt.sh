#!/bin/sh
# Usage: expect-interrupt.sh OUT_DIR WAIT_REGEX COMMAND [ARGS...]
# Starts COMMAND, sends it SIGINT once its output matches WAIT_REGEX, and
# succeeds when it then exits with code 130 and leaves neither OUT_DIR nor
# its staging folder OUT_DIR.partial (the run starts without them).
out_dir=$1
wait_re=$2
shift 2
rm -rf "$out_dir" "$out_dir.partial"
log=$(mktemp)
"$@" >"$log" 2>&1 &
pid=$!
tries=0
until grep -Eq -- "$wait_re" "$log"; do
  if ! kill -0 "$pid" 2>/dev/null; then
    cat "$log"
    echo "expect-interrupt.sh: the command ended before its output matched: $wait_re" >&2
    exit 1
  fi
  tries=$((tries + 1))
  if [ "$tries" -gt 3000 ]; then
    kill "$pid"
    echo "expect-interrupt.sh: timed out waiting for: $wait_re" >&2
    exit 1
  fi
  sleep 0.1
done
# A launcher may wrap the program (a display server): signal the program
# itself, as a terminal's Ctrl-C would, and let the launcher pass its status on.
target=$(pgrep -P "$pid" -f "bin/vimlop" || true)
kill -INT "${target:-$pid}" 2>/dev/null
wait "$pid"
rc=$?
cat "$log"
rm -f "$log"
if [ "$rc" -ne 130 ]; then
  echo "expect-interrupt.sh: expected exit code 130, got $rc" >&2
  exit 1
fi
for left in "$out_dir" "$out_dir.partial"; do
  if [ -e "$left" ]; then
    echo "expect-interrupt.sh: '$left' was left behind" >&2
    exit 1
  fi
done
