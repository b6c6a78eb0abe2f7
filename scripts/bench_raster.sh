#!/usr/bin/env bash
# The hair-drawing benchmark: the tessellation path (hair_raster=graphics) and the compute path
# (hair_raster=compute) side by side, whole frames with physics, shadows, deep opacity and
# transparency, per-pass GPU times (median and p95 of --frames after --warmup), for:
#   the seed's workload (900 grown guides x 10 vertices, 12 strands per guide, 42 divisions) at
#   1080 x 720 and 1920 x 1080; Sintel's groom (11,400 guides) with 1, 4, 8, 16 and 32 strands per
#   guide at 1920 x 1080 (and 8 at 256 x 144, and 8 without MSAA); a million strands (Sintel x 88
#   strands per guide, 1,003,200 strands); Sintel with 1 and 8 strands per guide close up
#   (scenes/close-up.json: the hair over about a third of the frame); Sintel with 8 at 3840 x 2160.
# Usage: scripts/bench_raster.sh OUT_DIR [DATA_DIR] [FRAMES] [WARMUP]
#   WISP=path/to/wisp picks the binary; DATA_DIR holds sintel/ (default ../shared/data);
#   ONLY=graphics|compute runs one path; QUICK=1 runs the first three workloads only.
# Writes OUT_DIR/raster.jsonl (one `wisp render --profile` object per line, with "workload" and
# "hair_raster" added) and prints a table: frame and hair ms per path and their ratio.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:?usage: bench_raster.sh OUT_DIR [DATA_DIR] [FRAMES] [WARMUP]}"
data="${2:-$root/../shared/data}"
frames="${3:-300}"
warmup="${4:-60}"
wisp="${WISP:-$root/build/wisp}"
paths="${ONLY:-graphics compute}"
mkdir -p "$out"
: > "$out/raster.jsonl"
sintel=(--head "$data/sintel/sintel.obj" --hair "$data/sintel/sintel_hair_11400x16.tfx")
seed=(--guides 900 --vertices 10 --set strands_per_guide=12 --set divisions=42)
workloads=(
  "seed-1080x720|--width 1080 --height 720 ${seed[*]}"
  "sintel-8-1920x1080|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=8"
  "sintel-8-256x144|--width 256 --height 144 ${sintel[*]} --set strands_per_guide=8"
)
if [ "${QUICK:-0}" != 1 ]; then
  workloads+=(
    "seed-1920x1080|--width 1920 --height 1080 ${seed[*]}"
    "sintel-1-1920x1080|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=1"
    "sintel-4-1920x1080|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=4"
    "sintel-16-1920x1080|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=16"
    "sintel-32-1920x1080|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=32"
    "sintel-8-1920x1080-1x|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=8 --set samples=1"
    "million-1920x1080|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=88"
    "sintel-1-close-1920x1080|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=1 --scene $root/scenes/close-up.json"
    "sintel-8-close-1920x1080|--width 1920 --height 1080 ${sintel[*]} --set strands_per_guide=8 --scene $root/scenes/close-up.json"
    "sintel-8-3840x2160|--width 3840 --height 2160 ${sintel[*]} --set strands_per_guide=8"
  )
fi
for w in "${workloads[@]}"; do
  name="${w%%|*}"
  read -r -a args <<< "${w#*|}"
  for path in $paths; do
    n="$frames"
    # The tessellation path takes up to half a second a frame on the heaviest workloads: fewer frames.
    case "$path:$name" in graphics:sintel-32*|graphics:million*) n=$(( frames < 60 ? frames : 60 )) ;; esac
    if json=$("$wisp" render --profile "$n" --warmup "$warmup" "${args[@]}" --set hair_raster="$path"); then
      echo "$json" | sed "s/^{/{\"workload\":\"$name\",\"hair_raster\":\"$path\",/" >> "$out/raster.jsonl"
    else
      echo "{\"workload\":\"$name\",\"hair_raster\":\"$path\",\"failed\":true}" >> "$out/raster.jsonl"
    fi
    echo "bench: $name $path done" >&2
  done
done
python3 - "$out/raster.jsonl" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
hair = {"graphics": ["shadow", "opacity", "oit.clear", "hair", "oit.resolve", "oit.composite", "oit.stats"],
        "compute": ["strands.clear", "shadow", "strands.light", "light.depth", "light.opacity", "light.resolve",
                    "light.copy", "strands.generate", "strands.depth", "strands.count", "strands.scan.blocks",
                    "strands.scan.totals", "strands.scan.offsets", "strands.pieces", "strands.write", "strands.resolve", "strands.reserve",
                    "hair.composite", "strands.stats"]}
by = {}
for r in rows:
    by.setdefault(r["workload"], {})[r["hair_raster"]] = r
print("%-22s %12s %12s %12s %12s %8s" % ("workload", "graphics ms", "(hair+maps)", "compute ms", "(hair+maps)", "ratio"))
for w, paths in by.items():
    cells = []
    for p in ("graphics", "compute"):
        r = paths.get(p)
        if not r or r.get("failed"):
            cells += ["-", "-"]
            continue
        ms = r["ms"]
        cells += ["%.2f" % ms["frame"]["median"], "%.2f" % sum(t["median"] for n, t in ms.items() if n.split(" ")[0] in hair[p])]
    try:
        ratio = "%.1fx" % (float(cells[0]) / float(cells[2]))
    except ValueError:
        ratio = "-"
    print("%-22s %12s %12s %12s %12s %8s" % (w, cells[0], cells[1], cells[2], cells[3], ratio))
PY
