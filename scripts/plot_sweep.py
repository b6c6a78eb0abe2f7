#!/usr/bin/env python3
"""Charts for `wisp sweep`: frames per second and the median frame time against the first varied
setting (one line per combination of the others), and the per-pass GPU time of every point,
stacked. The passes are the CSV's (every X_ms_median column but the frame's), each in a colour of
its own name, so a pass keeps its colour from one chart and one sweep to the next.
Usage: plot_sweep.py results.csv OUT_DIR   (writes fps.png, frame.png and passes.png)"""
import csv
import os
import sys
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MEDIAN = "_ms_median"


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def pass_colours(passes):
    """A colour per pass from its name (crc32 into 60 distinct colours), the next free one where two
    names meet, so one chart never shows two passes alike."""
    palette = [c for name in ("tab20", "tab20b", "tab20c") for c in plt.get_cmap(name).colors]
    taken, colours = set(), {}
    for p in passes:
        i = zlib.crc32(p.encode()) % len(palette)
        while i in taken and len(taken) < len(palette):
            i = (i + 1) % len(palette)
        taken.add(i)
        colours[p] = palette[i]
    return colours


def save(fig, path):
    """The chart written whole or not at all: under a temporary name beside it, flushed to the disk,
    then renamed over it. A full disk (or any failure to write) says so in wisp's one line, naming
    the chart, removes the temporary file and exits 3, which `wisp sweep` reads as bad
    environment."""
    temp = f"{path}.partial-{os.getpid()}.png"
    try:
        with open(temp, "wb") as f:
            fig.savefig(f, format="png", dpi=120, bbox_inches="tight")
            f.flush()
            os.fsync(f.fileno())
        os.replace(temp, path)
    except OSError as e:
        try:
            os.remove(temp)
        except OSError:
            pass
        print(f"wisp: cannot write {path}: {e.strerror or e}", file=sys.stderr)
        sys.exit(3)
    finally:
        plt.close(fig)


def outside_legend(ax, entries):
    """The legend to the right of the axes, small, in two columns past 16 entries."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=6, ncol=2 if entries > 16 else 1,
              frameon=False, borderaxespad=0.0)


def line_chart(rows, x_name, others, column, ylabel, title, path):
    """`column` against the first varied setting, one line per combination of the others."""
    groups = {}
    for r in rows:
        key = ", ".join(f"{o}={r[o]}" for o in others)
        groups.setdefault(key, []).append(r)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, group in groups.items():
        xs = [number(r[x_name]) for r in group]
        labels = [r[x_name] for r in group]
        ys = [float(r[column]) for r in group]
        if all(v is not None for v in xs):
            ax.plot(xs, ys, marker="o", label=key or None)
        else:
            ax.plot(range(len(ys)), ys, marker="o", label=key or None)
            ax.set_xticks(range(len(ys)), labels)
    ax.set_xlabel(x_name)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    if any(groups.keys()):
        outside_legend(ax, len(groups))
    save(fig, path)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_sweep.py results.csv OUT_DIR")
    with open(sys.argv[1], newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        columns = list(reader.fieldnames or [])
    if not rows:
        sys.exit(f"{sys.argv[1]}: no rows")
    timed = [c for c in columns if c.endswith(MEDIAN)]
    if "frame" + MEDIAN not in timed:
        sys.exit(f"{sys.argv[1]}: no frame{MEDIAN} column (not a results.csv of 'wisp sweep')")
    varied = columns[: columns.index(timed[0])]
    if not varied:
        sys.exit(f"{sys.argv[1]}: no varied setting before the first {MEDIAN} column")
    passes = [c[: -len(MEDIAN)] for c in timed if c != "frame" + MEDIAN]
    device = rows[0]["device"]
    out = sys.argv[2]

    x_name, others = varied[0], varied[1:]
    line_chart(rows, x_name, others, "fps", "frames per second (GPU time)",
               f"Wisp: frames per second against {x_name}\n{device}", f"{out}/fps.png")
    line_chart(rows, x_name, others, "frame" + MEDIAN, "GPU ms per frame (median)",
               f"Wisp: frame time against {x_name}\n{device}", f"{out}/frame.png")

    # Per-pass GPU time of every point, stacked, the passes in the CSV's order.
    colours = pass_colours(passes)
    labels = ["\n".join(f"{v}={r[v]}" for v in varied) for r in rows]
    widest = max(len(line) for label in labels for line in label.split("\n"))
    fig, ax = plt.subplots(figsize=(max(6, max(0.6, 0.07 * widest) * len(rows) + 2), 4.5))
    bottom = [0.0] * len(rows)
    for p in passes:
        values = [float(r[p + MEDIAN]) for r in rows]
        ax.bar(range(len(rows)), values, bottom=bottom, label=p, color=colours[p])
        bottom = [b + v for b, v in zip(bottom, values)]
    ax.set_xticks(range(len(rows)), labels, fontsize=7)
    ax.set_ylabel("GPU ms per frame (median)")
    ax.set_title(f"Wisp: GPU time per pass\n{device}", fontsize=10)
    # Top of the stack first, as the bars read.
    handles, names = ax.get_legend_handles_labels()
    ax.legend(handles[::-1], names[::-1], loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=6,
              ncol=2 if len(passes) > 16 else 1, frameon=False, borderaxespad=0.0)
    save(fig, f"{out}/passes.png")


if __name__ == "__main__":
    main()
