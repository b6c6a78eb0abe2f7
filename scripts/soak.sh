#!/usr/bin/env bash
# The soak: the looping soak scene (wind gusts, a sphere sweeping through the hair, the
# head turning) simulated for 100,000 steps, then recorded for 10,000 frames at 160 x 120. Each
# reports the worst physics metrics or its memory (host RSS and Wisp's device allocations) at the
# start and the end.
# Usage: scripts/soak.sh OUT_DIR [STEPS] [FRAMES]   (WISP=path/to/wisp to choose the binary)
# Writes OUT_DIR/soak_simulate.json, OUT_DIR/soak_record.log and OUT_DIR/soak_contact_sheet.png;
# the frames go to a temporary folder, removed at the end.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:?usage: soak.sh OUT_DIR [STEPS] [FRAMES]}"
steps="${2:-100000}"
frames="${3:-10000}"
wisp="${WISP:-$root/build/wisp}"
scene="$root/scenes/soak.json"
mkdir -p "$out"
frames_dir="$(mktemp -d)"
trap 'rm -rf "$frames_dir"' EXIT
start=$(date +%s)
"$wisp" simulate --scene "$scene" --steps "$steps" --json > "$out/soak_simulate.json"
echo "soak: $steps steps in $(( $(date +%s) - start )) s" >&2
start=$(date +%s)
"$wisp" record --scene "$scene" --frames "$frames" --width 160 --height 120 --out "$frames_dir/f" 2> "$out/soak_record.log" >/dev/null
echo "soak: $frames frames in $(( $(date +%s) - start )) s" | tee -a "$out/soak_record.log" >&2
cp "$frames_dir/f/contact_sheet.png" "$out/soak_contact_sheet.png"
ls "$frames_dir/f" | grep -c '^frame_.*\.png$' | sed 's/^/soak: frames written: /' | tee -a "$out/soak_record.log" >&2
