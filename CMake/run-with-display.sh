#!/bin/sh
# Runs a command with an X display: the current one if set, otherwise a
# private virtual one (Xvfb, Mesa llvmpipe renders offscreen).
#
# Xvfb picks its own free display number (-displayfd), which is atomic;
# `xvfb-run -a` guesses a free number first, and tests started in parallel
# by ctest could pick the same one and lose their display. -noreset: an X
# server resets when its last client leaves, and VTK aborts when it opens a
# window during the reset (a test of library code may open and close many).
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
if ! command -v Xvfb >/dev/null 2>&1; then
  echo "run-with-display.sh: no DISPLAY and no Xvfb; install the 'xvfb' package" >&2
  exit 1
fi
dir=$(mktemp -d "${TMPDIR:-/tmp}/vimlop-display.XXXXXX") || exit 1
server=
cleanup() {
  [ -n "$server" ] && kill "$server" 2>/dev/null && wait "$server" 2>/dev/null
  server=
}
trap 'cleanup; rm -rf "$dir"; exit 130' INT TERM

# Starts a private Xvfb and waits until it accepts connections (a few tries:
# many servers starting at once, as parallel tests do, can race for a display).
start_server() {
  for attempt in 1 2 3 4 5; do
    rm -f "$dir/display"
    Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$dir/display" 2>"$dir/xvfb.log" &
    server=$!
    tries=0
    # Xvfb writes the display number and a newline once it accepts connections.
    until grep -q '^[0-9][0-9]*$' "$dir/display" 2>/dev/null; do
      tries=$((tries + 1))
      if [ "$tries" -gt 200 ] || ! kill -0 "$server" 2>/dev/null; then
        break
      fi
      sleep 0.05
    done
    if grep -q '^[0-9][0-9]*$' "$dir/display" 2>/dev/null && kill -0 "$server" 2>/dev/null; then
      return 0
    fi
    cleanup
  done
  echo "run-with-display.sh: Xvfb did not start:" >&2
  cat "$dir/xvfb.log" >&2
  return 1
}

start_server || { rm -rf "$dir"; exit 1; }
DISPLAY=":$(cat "$dir/display")" "$@"
status=$?
if [ "$status" -ge 128 ]; then
  # A crash may be the display's: say what the server said.
  echo "run-with-display.sh: the command ended with status $status on display :$(cat "$dir/display"); Xvfb said:" >&2
  cat "$dir/xvfb.log" >&2
  kill -0 "$server" 2>/dev/null || echo "run-with-display.sh: Xvfb is gone" >&2
fi
cleanup
rm -rf "$dir"
exit $status
