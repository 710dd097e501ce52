#!/bin/sh
# Runs a command with an X display: the current one if set, otherwise a
# private virtual one from `xvfb-run -a` (Mesa llvmpipe renders offscreen).
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "run-with-display.sh: no DISPLAY and no xvfb-run; install the 'xvfb' package" >&2
  exit 1
fi
exec xvfb-run -a -s "-screen 0 1280x1024x24" "$@"
