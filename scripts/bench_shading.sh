#!/usr/bin/env bash
# The rendering benchmark: per-pass GPU times (median and p95 of 300 frames after 60, physics
# stepping each frame) for the seed's workload at 1080 x 720 and 1920 x 1080 and Sintel's groom at
# 1920 x 1080 with 8 strands per guide, in both transparency modes; then the seed's workload at
# 1920 x 1080 with each shading model and without shadows; and a sweep of PCF taps.
# Usage: scripts/bench_shading.sh OUT_DIR [DATA_DIR]   (WISP=path/to/wisp to choose the binary;
# DATA_DIR holds sintel.obj and sintel_hair_11400x16.tfx, default ../shared/data/sintel)
# Writes OUT_DIR/render.jsonl (one `wisp render --profile --json` object per line, each with a
# "label") and OUT_DIR/pcf/ (results.csv, fps.png, passes.png).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:?usage: bench_shading.sh OUT_DIR [DATA_DIR]}"
data="${2:-$root/../shared/data/sintel}"
wisp="${WISP:-$root/build/wisp}"
mkdir -p "$out"
: > "$out/render.jsonl"
seed=(--guides 900 --vertices 10 --set strands_per_guide=12 --set divisions=42)
sintel=(--head "$data/sintel.obj" --hair "$data/sintel_hair_11400x16.tfx" --set strands_per_guide=8)
profile() {  # LABEL ARGS...
  local label="$1"; shift
  "$wisp" render --profile 300 --warmup 60 "$@" | sed "s/^{/{\"label\":\"$label\",/" >> "$out/render.jsonl"
  echo "bench: $label done" >&2
}
for mode in oit msaa; do
  profile "seed 1080x720 $mode" "${seed[@]}" --width 1080 --height 720 --set transparency=$mode
  profile "seed 1920x1080 $mode" "${seed[@]}" --width 1920 --height 1080 --set transparency=$mode
  profile "sintel 1920x1080 $mode" "${sintel[@]}" --width 1920 --height 1080 --set transparency=$mode
  profile "default 1920x1080 $mode" --width 1920 --height 1080 --set transparency=$mode
done
for shading in kajiya lut; do
  profile "seed 1920x1080 oit shading=$shading" "${seed[@]}" --width 1920 --height 1080 --set shading=$shading
done
profile "seed 1920x1080 oit shadows=off" "${seed[@]}" --width 1920 --height 1080 --set shadows=off
profile "seed 1920x1080 oit dom_layers=0" "${seed[@]}" --width 1920 --height 1080 --set dom_layers=0
"$wisp" sweep --out "$out/pcf" --vary pcf_samples=1,4,8,16,32,64 "${seed[@]}" --width 1080 --height 720 \
  --warmup 60 --frames 300
