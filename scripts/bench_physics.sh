#!/usr/bin/env bash
# The physics benchmark: per-dispatch GPU times of one step (median and p95 over 300 steps after
# 60 warm-up steps) for 1k, 10k, 30k and 100k grown guides x 16 and 32 vertices, grid 64³ and 128³,
# with the fixed-point grid (the default) and with float atomics.
# Usage: scripts/bench_physics.sh OUT_DIR   (WISP=path/to/wisp to choose the binary)
# Writes OUT_DIR/physics.jsonl (one `wisp simulate --profile --json` object per line).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:?usage: bench_physics.sh OUT_DIR}"
wisp="${WISP:-$root/build/wisp}"
mkdir -p "$out"
: > "$out/physics.jsonl"
for atomics in fixed float; do
  for guides in 1000 10000 30000 100000; do
    for vertices in 16 32; do
      for grid in 64 128; do
        "$wisp" simulate --profile --json --warmup 60 --steps 300 --grid-atomics "$atomics" \
          --guides "$guides" --vertices "$vertices" --grid "$grid" >> "$out/physics.jsonl"
        echo "bench: $atomics, $guides guides x $vertices vertices, grid $grid done" >&2
      done
    done
  done
done
