#!/usr/bin/env bash
# Renders the README's gallery: every hair style (hair_style) on the default head from the front,
# the side, the back and above, Sintel's artist groom from the same views, and the other grooms of
# ../shared/data on their own heads and on the default head from the front and the back, each view
# `wisp render --scene VIEW --frames 30 --width W --height H` (the views are scenes that only set the
# camera), joined side by side by ffmpeg into images/gallery-NAME.png.
# Usage: scripts/gallery.sh [OUT_DIR (default images)] [WIDTH (512)] [HEIGHT (384)]
#   ONLY_STYLES=1 renders the styles and Sintel's groom only; STYLES="bob crop" only those styles.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/images}"
width="${2:-512}"
height="${3:-384}"
wisp="${WISP:-$root/build/wisp}"
data="${WISP_SHARED_DATA:-$root/../shared/data}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

view() {  # NAME YAW PITCH
  printf '{"version": 1, "keys": [{"time": 0, "camera": {"yaw": %s, "pitch": %s}}]}\n' "$2" "$3" >"$work/$1.json"
}
view front 0 5
view side 90 5
view back 180 10
view top 0 80

# strip NAME VIEWS... -- RENDER-OPTIONS...: one picture per view, joined left to right.
strip() {
  local name="$1"; shift
  local views=()
  while [ "$1" != "--" ]; do views+=("$1"); shift; done
  shift
  local inputs=()
  for v in "${views[@]}"; do
    "$wisp" render --scene "$work/$v.json" --frames 30 --width "$width" --height "$height" "$@" \
      --out "$work/$name-$v.png" >"$work/$name-$v.log"
    inputs+=(-i "$work/$name-$v.png")
  done
  ffmpeg -loglevel error -y "${inputs[@]}" -filter_complex "hstack=inputs=${#views[@]}" "$out/gallery-$name.png"
  echo "$out/gallery-$name.png"
}

# Every style at its own density (the longer ones make more fragments than lavapipe's buffer holds:
# the compute raster draws them in pieces).
for style in ${STYLES:-bob long wavy crop bangs afro}; do
  strip "style-$style" front side back top -- --set hair_style="$style"
done
if [ -d "$data" ]; then
  strip sintel front side back top -- --head "$data/sintel/sintel.obj" \
    --hair "$data/sintel/sintel_hair_11400x16.tfx" --set strands_per_guide=8
  [ "${ONLY_STYLES:-0}" = 1 ] && exit 0
  strip sintel-lite front back -- --head "$data/sintel-lite/sintel_lite.obj" --hair "$data/sintel-lite/sintel_hair_228x32.tfx"
  strip tressfx front back -- --head "$data/tressfx-text/head_max4.obj" \
    --hair "$data/tressfx-text/hair_front_16_guide.tfx" --hair "$data/tressfx-text/hair_tail_16_guide.tfx"
  strip sintel-on-default front back -- --hair "$data/sintel/sintel_hair_11400x16.tfx" --set strands_per_guide=4
  strip sintel-lite-on-default front back -- --hair "$data/sintel-lite/sintel_hair_228x32.tfx"
else
  echo "gallery: $data is absent: only the default groom" >&2
fi
