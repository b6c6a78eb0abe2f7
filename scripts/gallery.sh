#!/usr/bin/env bash
# Renders the README's gallery: the default groom on the default head from the front, the side,
# the back and above, and every groom of ../shared/data on its own head and on the default head,
# from the front and the back, each view `wisp render --scene VIEW --frames 30 --width W --height H`
# (the views are scenes that only set the camera), joined side by side by ffmpeg into images/.
# Usage: scripts/gallery.sh [OUT_DIR (default images)] [WIDTH (240)] [HEIGHT (180)]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/images}"
width="${2:-240}"
height="${3:-180}"
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

strip default front side back top --
if [ -d "$data" ]; then
  strip sintel front back -- --head "$data/sintel/sintel.obj" --hair "$data/sintel/sintel_hair_11400x16.tfx" \
    --set strands_per_guide=4
  strip sintel-lite front back -- --head "$data/sintel-lite/sintel_lite.obj" --hair "$data/sintel-lite/sintel_hair_228x32.tfx"
  strip tressfx front back -- --head "$data/tressfx-text/head_max4.obj" \
    --hair "$data/tressfx-text/hair_front_16_guide.tfx" --hair "$data/tressfx-text/hair_tail_16_guide.tfx"
  strip sintel-on-default front back -- --hair "$data/sintel/sintel_hair_11400x16.tfx" --set strands_per_guide=4
  strip sintel-lite-on-default front back -- --hair "$data/sintel-lite/sintel_hair_228x32.tfx"
else
  echo "gallery: $data is absent: only the default groom" >&2
fi
