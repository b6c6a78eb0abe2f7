#!/usr/bin/env bash
# Configures (once) and builds Wisp in Release into build/. Fast when nothing changed.
#   scripts/build.sh             every target (the tests too): what scripts/test.sh builds
#   scripts/build.sh TARGET...   only those targets and what they need (scripts/demo.sh: wisp, its
#                                libraries and its shaders, not the tests)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${WISP_BUILD_DIR:-$root/build}"
jobs="$(nproc 2>/dev/null || echo 2)"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
targets=()
for target in "$@"; do
  targets+=(--target "$target")
done
cmake --build "$build" -j "$jobs" "${targets[@]}"
