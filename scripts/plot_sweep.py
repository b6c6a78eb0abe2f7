#!/usr/bin/env python3
"""Charts for `wisp sweep`: frames per second against the first varied setting (one line per
combination of the others) and the per-pass GPU time of every point, stacked.
Usage: plot_sweep.py results.csv OUT_DIR   (writes fps.png and passes.png)"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PASSES = ["physics", "shadow", "opacity", "oit.clear", "meshes", "hair", "oit.resolve", "oit.composite", "oit.stats"]


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_sweep.py results.csv OUT_DIR")
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{sys.argv[1]}: no rows")
    columns = list(rows[0].keys())
    varied = columns[: columns.index("physics_ms_median")]
    device = rows[0]["device"]
    out = sys.argv[2]

    # FPS against the first varied setting.
    x_name, others = varied[0], varied[1:]
    groups = {}
    for r in rows:
        key = ", ".join(f"{o}={r[o]}" for o in others)
        groups.setdefault(key, []).append(r)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, group in groups.items():
        xs = [number(r[x_name]) for r in group]
        labels = [r[x_name] for r in group]
        ys = [float(r["fps"]) for r in group]
        if all(v is not None for v in xs):
            ax.plot(xs, ys, marker="o", label=key or None)
        else:
            ax.plot(range(len(ys)), ys, marker="o", label=key or None)
            ax.set_xticks(range(len(ys)), labels)
    ax.set_xlabel(x_name)
    ax.set_ylabel("frames per second (GPU time)")
    ax.set_title(f"Wisp: frames per second against {x_name}\n{device}", fontsize=10)
    ax.grid(True, alpha=0.3)
    if any(groups.keys()):
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/fps.png", dpi=120)

    # Per-pass GPU time of every point, stacked.
    fig, ax = plt.subplots(figsize=(max(6, 0.6 * len(rows) + 2), 4.5))
    labels = ["\n".join(f"{v}={r[v]}" for v in varied) for r in rows]
    bottom = [0.0] * len(rows)
    for p in PASSES:
        values = [float(r[f"{p}_ms_median"]) for r in rows]
        ax.bar(range(len(rows)), values, bottom=bottom, label=p)
        bottom = [b + v for b, v in zip(bottom, values)]
    ax.set_xticks(range(len(rows)), labels, fontsize=7)
    ax.set_ylabel("GPU ms per frame (median)")
    ax.set_title(f"Wisp: GPU time per pass\n{device}", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/passes.png", dpi=120)


if __name__ == "__main__":
    main()
