#!/usr/bin/env bash
# Sets up, builds and runs the Wisp demo. With a display it opens the window; without one it
# renders offscreen into out/ and prints the picture's path. It builds only the wisp executable
# (its libraries and shaders), not the tests, so a fresh machine shows the picture sooner;
# scripts/test.sh builds the rest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh" wisp >/dev/null
wisp="${WISP_BUILD_DIR:-$root/build}/wisp"
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec "$wisp" view "$@"
fi
echo "demo: no display (DISPLAY is unset), so no window: rendering offscreen instead"
mkdir -p "$root/out"
"$wisp" render --out "$root/out/demo.png" --width 1280 --height 720 --frames 60 "$@" >/dev/null
echo "demo: wrote $root/out/demo.png"
