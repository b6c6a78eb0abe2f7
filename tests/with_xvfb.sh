#!/bin/sh
# tests/with_xvfb.sh COMMAND [ARGS...]: runs a command under an Xvfb of its own, on the display the
# server itself picks (-displayfd), so window tests running side by side never race for one (as
# xvfb-run -a does: two runs could take the same display, and it then exited with its own status).
# Exits with the command's status; 99 when the server does not start.
set -u
dir=$(mktemp -d) || exit 99
Xvfb -displayfd 3 -screen 0 640x480x24 -nolisten tcp 3>"$dir/display" 2>"$dir/log" &
server=$!
tries=0
while [ ! -s "$dir/display" ] && [ "$tries" -lt 200 ]; do
  sleep 0.05
  tries=$((tries + 1))
done
display=$(cat "$dir/display")
if [ -z "$display" ]; then
  echo "with_xvfb.sh: Xvfb did not start:" >&2
  cat "$dir/log" >&2
  kill "$server" 2>/dev/null
  rm -rf "$dir"
  exit 99
fi
DISPLAY=":$display" "$@"
status=$?
kill "$server" 2>/dev/null
wait "$server" 2>/dev/null
rm -rf "$dir"
exit "$status"
