#!/usr/bin/env bash
# Sets up, builds and runs every Wisp test (GoogleTest through ctest). GPU tests run on the
# machine's Vulkan device (Mesa's lavapipe where there is no GPU) with validation on.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
cd "${WISP_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
