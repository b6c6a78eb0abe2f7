#!/usr/bin/env bash
# scripts/build_asan.sh TARGET...: configures (once) and builds the given targets in build-asan/:
# clang, Debug at -O1, WISP_SANITIZE=address,undefined (-fno-sanitize-recover=all) and WISP_FUZZ
# (the loaders' libFuzzer targets). scripts/sanitize.sh and scripts/fuzz.sh share this build.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${WISP_ASAN_BUILD_DIR:-$root/build-asan}"
jobs="$(nproc 2>/dev/null || echo 2)"
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Debug \
    -DWISP_SANITIZE=address,undefined -DWISP_FUZZ=ON >/dev/null
fi
cmake --build "$build" -j "$jobs" --target "$@"
