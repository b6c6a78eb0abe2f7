#!/usr/bin/env bash
# Configures and builds Wisp in Release into build/ (with Ninja where it is installed). Fast when
# nothing changed.
#   scripts/build.sh             every target (the tests too): what scripts/test.sh builds; configures
#                                again, so that a tree first configured by the demo, before GoogleTest
#                                was installed, gains the tests
#   scripts/build.sh TARGET...   only those targets and what they need (scripts/demo.sh: wisp, its
#                                libraries and its shaders, not the tests)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${WISP_BUILD_DIR:-$root/build}"
jobs="$(nproc 2>/dev/null || echo 2)"
if [ ! -f "$build/CMakeCache.txt" ]; then
  generator=()
  if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
elif [ $# -eq 0 ]; then
  cmake "$build" >/dev/null
fi
targets=()
for target in "$@"; do
  targets+=(--target "$target")
done
cmake --build "$build" -j "$jobs" "${targets[@]}"
