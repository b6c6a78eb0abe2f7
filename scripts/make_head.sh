#!/usr/bin/env bash
# Rebuilds the project's default head, models/head.obj and models/head.json, with the generator in
# tools/make_head.cpp (a signed distance field of blended ellipsoids meshed by surface nets).
# Pass --preview DIR to also write front, side and three-quarter PNG previews.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" >/dev/null
"${WISP_BUILD_DIR:-$root/build}/wisp_make_head" --out-dir "$root/models" "$@"
