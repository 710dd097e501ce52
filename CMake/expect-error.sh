#!/bin/sh
# Usage: expect-error.sh REGEX COMMAND [ARGS...]
# Succeeds when COMMAND exits with a non-zero code (not a crash) and its output
# matches the extended regular expression REGEX (on one of its lines, or
# across them: the lines joined by spaces).
re=$1
shift
out=$("$@" 2>&1)
rc=$?
printf '%s\n' "$out"
if [ "$rc" -eq 0 ]; then
  echo "expect-error.sh: expected a non-zero exit code" >&2
  exit 1
fi
if [ "$rc" -ge 128 ]; then
  echo "expect-error.sh: the command crashed (exit code $rc)" >&2
  exit 1
fi
# On one line, or across lines (".*" between them) with the lines joined by spaces.
joined=$(printf '%s' "$out" | tr '\n' ' ')
if ! printf '%s\n' "$out" | grep -Eq -- "$re" && ! printf '%s\n' "$joined" | grep -Eq -- "$re"; then
  echo "expect-error.sh: output does not match: $re" >&2
  exit 1
fi
