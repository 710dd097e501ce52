#!/bin/sh
# Usage: expect-kill.sh VIMLOP OUT_DIR MOMENTS SEED COMMAND [ARGS...]
# COMMAND writes the result folder OUT_DIR (vimlop register --out OUT_DIR
# --force, perhaps through a display launcher). It runs once to its end, to
# time it and to list a complete folder's files; then MOMENTS times more,
# each killed with SIGKILL at a moment drawn (with SEED) from its own slot of
# that time, so that the kills cover the whole run: loading, registration,
# outputs, the rename. Every second run starts without OUT_DIR, the others
# over a copy of the complete folder (the --force case).
# After each kill, OUT_DIR must be absent or complete: the complete run's
# files, all of them, and `VIMLOP serve --result` must accept it. The script
# prints one line per kill and fails at the first folder that is neither.
vimlop=$1
out_dir=$2
moments=$3
seed=$4
shift 4
log=$(mktemp)
reference=$(mktemp)
listing=$(mktemp)
old_copy="$out_dir.complete-copy"
trap 'rm -f "$log" "$reference" "$listing"; rm -rf "$old_copy"' EXIT

files_of() {
  (cd "$1" && find . -type f | LC_ALL=C sort)
}

rm -rf "$out_dir" "$out_dir.partial"
start=$(date +%s.%N)
if ! "$@" >"$log" 2>&1; then
  cat "$log"
  echo "expect-kill.sh: the run to the end failed" >&2
  exit 1
fi
seconds=$(echo "$start $(date +%s.%N)" | awk '{ printf "%.3f", $2 - $1 }')
files_of "$out_dir" >"$reference"
rm -rf "$old_copy"
cp -a "$out_dir" "$old_copy"
echo "expect-kill.sh: a whole run takes $seconds s and writes $(wc -l <"$reference") files"

complete=0
absent=0
k=1
while [ "$k" -le "$moments" ]; do
  rm -rf "$out_dir"
  if [ $((k % 2)) -eq 0 ]; then
    cp -a "$old_copy" "$out_dir"
  fi
  at=$(awk -v s="$seed" -v k="$k" -v n="$moments" -v t="$seconds" \
    'BEGIN { srand(s * 1000 + k); printf "%.3f", t * (k - 1 + rand()) / n }')
  "$@" >"$log" 2>&1 &
  pid=$!
  sleep "$at"
  # A display launcher may wrap the program: kill the program itself (the
  # launcher then stops its display server), once it has started.
  target=$pid
  tries=0
  while [ "$tries" -lt 100 ] && kill -0 "$pid" 2>/dev/null &&
    [ "$(ps -o comm= -p "$target")" != vimlop ]; do
    target=$(pgrep -P "$pid" -x vimlop || echo "$pid")
    [ "$(ps -o comm= -p "$target")" = vimlop ] || sleep 0.05
    tries=$((tries + 1))
  done
  kill -KILL "$target" 2>/dev/null
  wait "$pid" 2>/dev/null
  state=absent
  if [ -e "$out_dir" ]; then
    files_of "$out_dir" >"$listing"
    if ! cmp -s "$reference" "$listing"; then
      echo "expect-kill.sh: kill $k at $at s left '$out_dir' incomplete:" >&2
      diff "$reference" "$listing" >&2
      exit 1
    fi
    if ! "$vimlop" serve --result "$out_dir" --port 0 --duration-s 0.1 >"$log" 2>&1; then
      cat "$log"
      echo "expect-kill.sh: kill $k at $at s: serve --result refuses '$out_dir'" >&2
      exit 1
    fi
    state=complete
    complete=$((complete + 1))
  else
    absent=$((absent + 1))
  fi
  echo "expect-kill.sh: kill $k at $at s: '$out_dir' $state"
  k=$((k + 1))
done
echo "expect-kill.sh: $moments kills: $complete left a complete folder, $absent none"
