#!/bin/sh
# Usage: expect-error.sh REGEX COMMAND [ARGS...]
# Succeeds when COMMAND exits with a non-zero code (not a crash) and its output
# matches the extended regular expression REGEX.
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
if ! printf '%s\n' "$out" | grep -Eq -- "$re"; then
  echo "expect-error.sh: output does not match: $re" >&2
  exit 1
fi
