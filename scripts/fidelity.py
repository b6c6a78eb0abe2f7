#!/usr/bin/env python3
"""The fidelity table's assembly, for scripts/fidelity.sh (which renders and measures; this only
reads what it wrote). Standard library only, but for `sheet` (Pillow, used where ffmpeg is absent).

  fidelity.py table --manifest work/manifest.tsv --out OUT_DIR ...
      reads each comparison (`wisp compare --json`, beside its picture) and each reference's log,
      writes OUT_DIR/fidelity.json and OUT_DIR/fidelity.md, and, in the work folder, the sheets'
      rows (sheet-GROOM-best.tsv, sheet-GROOM-all.tsv) and the list of pictures to pack (pack.txt).
  fidelity.py sheet --rows ROWS.tsv --width W --out SHEET.png
      each line of ROWS a row of pictures, each scaled to W pixels wide, rows stacked."""
import argparse
import json
import os
import re
import sys
from itertools import groupby

METRICS = ("rmse", "rel_mse", "ssim")
TERMS = {
    "key": "the key light alone (fill, rim and ambient off)",
    "rest": "without the key light (fill, rim and ambient)",
}


def fail(message):
    print(f"fidelity: {message}", file=sys.stderr)
    sys.exit(1)


def read_manifest(path):
    with open(path, encoding="utf-8") as f:
        lines = [line.rstrip("\n").split("\t") for line in f if line.strip()]
    header, rows = lines[0], lines[1:]
    return [dict(zip(header, row)) for row in rows]


def reference_facts(png):
    """The reference's log: its tracing time, samples per second and the noise it estimated."""
    facts = {"picture": os.path.basename(png)}
    log = png[: -len(".png")] + ".log"
    try:
        text = open(log, encoding="utf-8", errors="replace").read()
    except OSError:
        return facts
    m = re.search(r"reference: .* in ([0-9.]+) s \(([0-9.e+]+) samples/s", text)
    if m:
        facts["trace_seconds"] = float(m.group(1))
        facts["samples_per_second"] = float(m.group(2))
    m = re.search(r"noise: ([0-9.]+) of 255 levels RMS", text)
    if m:
        facts["noise_levels"] = float(m.group(1))
    return facts


class PixelStats:
    """The hair's error taken apart, where numpy and Pillow are importable (else None): over the
    pixels `wisp compare` calls hair (the test differs from the frame without hair in any channel),
    on linear RGB as compare's RMSE is: the mean square error, its part that is one offset per
    channel over the whole hair (a brightness or colour shift: bias), the references' own noise
    there (half the mean square difference of the two references, whose samples differ), the
    hair's mean luminance in the test and in the reference, and the share of the whole frame's
    squared error that lies in the hair."""

    def __init__(self):
        import numpy
        from PIL import Image

        self.np, self.image, self.cache = numpy, Image, {}

    def linear(self, path):
        if path not in self.cache:
            c = self.np.asarray(self.image.open(path).convert("RGB"), dtype=self.np.float64) / 255.0
            self.cache[path] = self.np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
        return self.cache[path]

    def srgb8(self, path):
        return self.np.asarray(self.image.open(path).convert("RGB"), dtype=self.np.int16)

    def hair(self, test, reference, no_hair, second_reference=None):
        np = self.np
        mask = np.any(self.srgb8(test) != self.srgb8(no_hair), axis=2)
        if not mask.any():
            return None
        t, r = self.linear(test)[mask], self.linear(reference)[mask]
        d = t - r
        mse = float(np.mean(d * d))
        offset = np.mean(d, axis=0)
        luma = np.array([0.2126, 0.7152, 0.0722])
        whole = self.linear(test) - self.linear(reference)
        frame_se = float(np.sum(whole * whole))
        out = {
            "pixels": int(mask.sum()),
            # the share of the frame's squared error that lies in the hair (and its shadow)
            "hair_share_of_frame": float(np.sum(d * d)) / frame_se if frame_se > 0 else 0.0,
            "rmse": mse**0.5,
            "bias_share": float(np.mean(offset * offset)) / mse if mse > 0 else 0.0,
            "luminance_ratio": float(np.mean(t @ luma)) / max(float(np.mean(r @ luma)), 1e-9),
        }
        if second_reference:
            n = self.linear(second_reference)[mask] - r
            noise = 0.5 * float(np.mean(n * n))
            out["noise_share"] = min(noise / mse, 1.0) if mse > 0 else 0.0
            out["rmse_without_noise"] = max(mse - noise, 0.0) ** 0.5
        return out


def pixel_stats():
    try:
        return PixelStats()
    except ImportError:
        return None


def settings_of(variant):
    return dict(word.split("=", 1) for word in variant.split() if "=" in word)


def fmt(v, digits=4):
    if v is None:
        return "n/a"
    return f"{v:.{digits}f}"


def mean(values):
    values = [v for v in values if v is not None]
    return sum(values) / len(values) if values else None


def factor_effects(rows, factors, metric):
    """For each factor (a varied setting or a case axis), the mean absolute change of `metric` when
    that factor alone changes, every other one held: how much of the error it accounts for."""
    effects = {}
    for factor in factors:
        others = [f for f in factors if f != factor]
        groups = {}
        for r in rows:
            key = tuple(r["factors"][f] for f in others)
            groups.setdefault(key, []).append(r)
        spreads = []
        for group in groups.values():
            values = [r["hair"][metric] for r in group if r["hair"] and r["hair"][metric] is not None]
            if len(values) >= 2:
                spreads.append(max(values) - min(values))
        if spreads:
            effects[factor] = mean(spreads)
    return effects


def table(args):
    entries = read_manifest(args.manifest)
    work = os.path.dirname(os.path.abspath(args.manifest))
    out = os.path.abspath(args.out)
    cases, order = {}, []
    stats = pixel_stats()
    floors = {e["case"]: e["test"] for e in entries if e["kind"] == "floor"}
    for e in entries:
        test = e["test"]
        try:
            measured = json.load(open(test[: -len(".png")] + ".json", encoding="utf-8"))
        except (OSError, ValueError) as error:
            fail(f"the comparison of {test} could not be read: {error}")
        row = {
            "settings": settings_of(e["variant"]),
            "frame": measured["frame"],
            "hair": measured["hair"],
            "picture": os.path.relpath(test, work),
            "error_image": os.path.relpath(test[: -len(".png")] + "-err.png", work),
            "mask": os.path.relpath(e["mask"], work),
            "reference": os.path.relpath(e["reference"], work),
        }
        if stats and e["kind"] != "floor":
            if e["case"] not in cases:
                stats.cache.clear()  # one case's pictures at a time
            second = floors.get(e["case"]) if e["kind"] == "variant" else None
            row["pixels"] = stats.hair(test, e["reference"], e["mask"], second)
        if e["case"] not in cases:
            order.append(e["case"])
            cases[e["case"]] = {
                "case": e["case"],
                "groom": e["groom"],
                "light": e["light"],
                "colour": e["colour"],
                "reference": dict(reference_facts(e["reference"]), picture=os.path.relpath(e["reference"], work)),
                "variants": [],
                "terms": [],
            }
        c = cases[e["case"]]
        if e["kind"] == "floor":
            # Only the frame's figures: compare's hair mask is where the test differs from the
            # real-time frame without hair, which for a reference is nearly everywhere.
            c["reference"]["second"] = {"picture": row["picture"], "frame": row["frame"]}
        elif e["kind"] == "variant":
            c["variants"].append(row)
        else:
            row["term"] = e["term"]
            row["term_reference"] = dict(reference_facts(e["reference"]), picture=os.path.relpath(e["reference"], work))
            c["terms"].append(row)

    varied = list(settings_of(next(e for e in entries if e["kind"] == "variant")["variant"]).keys())
    case_axes = [a for a in ("groom", "light", "colour") if len({cases[n][a] for n in order}) > 1]
    flat = []
    for name in order:
        for v in cases[name]["variants"]:
            factors = dict(v["settings"])
            factors.update({a: cases[name][a] for a in ("groom", "light", "colour")})
            flat.append(dict(v, case=name, factors=factors))
    rank = lambda v: (v["hair"] or v["frame"])["rmse"]  # noqa: E731: the hair's RMSE, else the frame's

    summary = {"ranked_by": "the hair's RMSE (linear RGB)"}
    for name in order:
        variants = cases[name]["variants"]
        best = min(variants, key=rank)
        worst = max(variants, key=rank)
        cases[name]["best"] = best["settings"]
        cases[name]["worst"] = worst["settings"]
    summary["per_setting"] = {
        s: {
            value: {m: mean([r["hair"][m] for r in flat if r["settings"][s] == value and r["hair"]]) for m in METRICS}
            for value in dict.fromkeys(r["settings"][s] for r in flat)
        }
        for s in varied
    }
    summary["per_case_axis"] = {
        a: {
            value: {m: mean([r["hair"][m] for r in flat if r["factors"][a] == value and r["hair"]]) for m in METRICS}
            for value in dict.fromkeys(r["factors"][a] for r in flat)
        }
        for a in ("groom", "light", "colour")
    }
    summary["effects_on_hair_rmse"] = factor_effects(flat, varied + case_axes, "rmse")
    worst_row = max(flat, key=rank)
    summary["furthest"] = {"case": worst_row["case"], "settings": worst_row["settings"], "hair": worst_row["hair"]}

    result = {
        "command": args.command,
        "devices": [d.strip() for d in args.devices.split(";") if d.strip()],
        "width": args.width,
        "height": args.height,
        "spp": args.spp,
        "frames": args.frames,
        "sets": args.sets.split() if args.sets else [],
        "varied": varied,
        "render_seconds": args.render_seconds,
        "resumed": bool(args.resumed),
        "sheets_by": args.sheets_by,
        "cases": [cases[n] for n in order],
        "summary": summary,
    }

    # The sheets' rows and what is packed.
    for groom, names in groupby(order, key=lambda n: cases[n]["groom"]):
        names = list(names)
        with open(os.path.join(work, f"sheet-{groom}-best.tsv"), "w", encoding="utf-8") as f:
            for n in names:
                c = cases[n]
                best = next(v for v in c["variants"] if v["settings"] == c["best"])
                worst = next(v for v in c["variants"] if v["settings"] == c["worst"])
                row = [c["reference"]["picture"], best["picture"], best["error_image"], worst["picture"],
                       worst["error_image"]]
                f.write("\t".join(os.path.join(work, p) for p in row) + "\n")
        with open(os.path.join(work, f"sheet-{groom}-all.tsv"), "w", encoding="utf-8") as f:
            for n in names:
                c = cases[n]
                row = [c["reference"]["picture"]] + [v["picture"] for v in c["variants"]]
                f.write("\t".join(os.path.join(work, p) for p in row) + "\n")

    priority = []
    for n in order:  # references first, then each case's best and worst, then the rest
        priority.append(cases[n]["reference"]["picture"])
    for n in order:
        c = cases[n]
        for s in (c["best"], c["worst"]):
            v = next(v for v in c["variants"] if v["settings"] == s)
            priority += [v["picture"], v["error_image"]]
    for n in order:
        priority.append(cases[n]["variants"][0]["mask"])
    for n in order:
        for v in cases[n]["variants"]:
            priority.append(v["picture"])
    for n in order:
        for t in cases[n]["terms"]:
            priority += [t["term_reference"]["picture"], t["picture"], t["mask"]]
    for n in order:
        if "second" in cases[n]["reference"]:
            priority.append(cases[n]["reference"]["second"]["picture"])
    for n in order:
        for v in cases[n]["variants"] + cases[n]["terms"]:
            priority.append(v["error_image"])
    packed, left, size = [], [], 0
    for p in dict.fromkeys(priority):
        blocks = 512 + (os.path.getsize(os.path.join(work, p)) + 511) // 512 * 512
        if size + blocks + 1024 <= args.pack_mb * 1024 * 1024:
            packed.append(p)
            size += blocks
        else:
            left.append(p)
    with open(os.path.join(work, "pack.txt"), "w", encoding="utf-8") as f:
        f.write("".join(p + "\n" for p in packed))
    result["packed"] = {"tar": "fidelity-images.tar", "files": len(packed), "left_out": left}

    write_atomically(os.path.join(out, "fidelity.json"), json.dumps(result, indent=2) + "\n")
    write_atomically(os.path.join(out, "fidelity.md"), markdown(result, cases, order, varied, case_axes))


def write_atomically(path, text):
    partial = path + ".partial"
    with open(partial, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(partial, path)


def markdown(result, cases, order, varied, case_axes):
    lines = []
    add = lines.append
    add("# Wisp: the real-time frame against the path-traced reference")
    add("")
    add(f"`{result['command']}`; device: {'; '.join(result['devices']) or 'unknown'}; "
        f"{result['width']} x {result['height']}, references at {result['spp']} samples per pixel, "
        f"{result['frames']} simulated frames before each picture"
        + (f", with `{' '.join('--set ' + s for s in result['sets'])}`" if result["sets"] else "")
        + f"; the renders took {result['render_seconds']} s"
        + (" (the last call of a run completed with --resume: those not drawn before)." if result["resumed"] else "."))
    add("")
    add("Errors over the whole frame and over the hair (the pixels the hair changes: the hair and its "
        "shadow), `wisp compare` against the reference of the same case: RMSE and relative MSE on "
        "linear RGB, SSIM on luma (1 is identical). Lower RMSE and relMSE, higher SSIM, are closer. "
        "Per case, **bold** marks the variant closest to the reference by the hair's RMSE.")
    add("")
    add("At a glance: the hair's RMSE (and SSIM) of each variant, the closest in bold"
        + ("; the last column is the part of the hair's RMSE that is the reference's own noise "
           "(the two references' mean square difference over the hair, halved, square-rooted)."
           if any(cases[n]["variants"][0].get("pixels") for n in order) else "."))
    add("")
    label = lambda v: " ".join(f"{k}={v['settings'][k]}" for k in varied)  # noqa: E731
    first = cases[order[0]]["variants"]
    floor_column = any(cases[n]["variants"][0].get("pixels") for n in order)
    add("| case | " + " | ".join(label(v) for v in first) + (" | reference noise |" if floor_column else " |"))
    add("|---|" + "---|" * (len(first) + floor_column))
    for n in order:
        c = cases[n]
        cells = []
        for v in c["variants"]:
            hair = v["hair"] or {m: None for m in METRICS}
            cell = f"{fmt(hair['rmse'])} ({fmt(hair['ssim'], 3)})"
            cells.append(f"**{cell}**" if v["settings"] == c["best"] else cell)
        if floor_column:
            p = c["variants"][0].get("pixels") or {}
            noise = (p["rmse"] ** 2 - p["rmse_without_noise"] ** 2) ** 0.5 if "rmse_without_noise" in p else None
            cells.append(fmt(noise))
        add(f"| {n} | " + " | ".join(cells) + " |")
    add("")
    add("Every measurement:")
    add("")
    head = ["case"] + varied + ["RMSE", "relMSE", "SSIM", "hair RMSE", "hair relMSE", "hair SSIM"]
    add("| " + " | ".join(head) + " |")
    add("|" + "---|" * len(head))
    for n in order:
        c = cases[n]
        for v in c["variants"]:
            best = v["settings"] == c["best"]
            hair = v["hair"] or {m: None for m in METRICS}
            cells = [n] + [v["settings"][s] for s in varied]
            cells += [fmt(v["frame"][m]) for m in METRICS] + [fmt(hair[m]) for m in METRICS]
            if best:
                cells = [f"**{x}**" for x in cells]
            add("| " + " | ".join(cells) + " |")
    add("")
    if "multiple_scattering" in varied:
        add("`multiple_scattering=off` leaves Karis's approximation (`hairKarisMultiple`) out of `karis` and "
            "`lut`; `kajiya` has none (its diffuse lobe stands in), so its pictures are the same either way.")
    else:
        add("`karis` and `lut` add Karis's multiple-scattering approximation (`hairKarisMultiple`), `kajiya` "
            "has none (its diffuse lobe stands in): `--vary multiple_scattering=on,off` gives its column.")
    add("")
    add("## The references")
    add("")
    add("The noise left in each reference, twice: as the renderer estimates it (of 255 output levels), and "
        "as the RMSE between it and a second reference of other samples (`--sample-seed 2`) over the "
        "frame, divided by sqrt(2): the part of any RMSE in the table that is the reference's noise "
        "(errors add in squares).")
    add("")
    add("| case | picture | traced in | noise (of 255 levels, RMS) | noise (frame RMSE) |")
    add("|---|---|---|---|---|")
    for n in order:
        r = cases[n]["reference"]
        second = r.get("second")
        floor = second["frame"]["rmse"] / 2**0.5 if second else None
        add(f"| {n} | `{r['picture']}` | {fmt(r.get('trace_seconds'), 2)} s | {fmt(r.get('noise_levels'), 2)} | "
            f"{fmt(floor)} |")
    add("")
    s = result["summary"]
    add("## What the error comes from")
    add("")
    add("The mean hair error of each value of each varied setting and of each case axis, over everything else:")
    add("")
    add("| factor | value | hair RMSE | hair relMSE | hair SSIM |")
    add("|---|---|---|---|---|")
    for name, values in list(s["per_setting"].items()) + [(a, s["per_case_axis"][a]) for a in case_axes]:
        for value, m in values.items():
            add(f"| {name} | {value} | {fmt(m['rmse'])} | {fmt(m['rel_mse'])} | {fmt(m['ssim'])} |")
    add("")
    effects = sorted(s["effects_on_hair_rmse"].items(), key=lambda kv: -kv[1])
    if effects:
        add("How much the hair's RMSE changes, on average, when one factor alone changes (every other one "
            "held), largest first: " + ", ".join(f"{k} {fmt(v)}" for k, v in effects) + ".")
        add("")
    if not any(v.get("pixels") for n in order for v in cases[n]["variants"]):
        add("The hair's error is not taken apart here (noise, offset, luminance): the python3 that ran "
            "this lacks numpy or Pillow (PYTHON=path chooses another).")
        add("")
    else:
        add("The hair's error taken apart (numpy, on the pictures): the RMSE over the hair; the same with "
            "the references' noise taken out (the mean square difference of the two references, halved, "
            "subtracted); the share of the mean square error that the reference's noise is; the share "
            "that is one offset per colour channel over the whole hair (brightness or colour: what an "
            "exposure or albedo change would remove); the hair's mean luminance over the reference's; "
            "the share of the whole frame's squared error that lies in the hair (the rest: the head's "
            "shading and edges, the backdrop).")
        add("")
        add("| case | " + " | ".join(varied) + " | hair RMSE | without noise | noise share | offset share | "
            "luminance / reference | hair's share of the frame's error |")
        add("|---|" + "---|" * (len(varied) + 6))
        for n in order:
            for v in cases[n]["variants"]:
                p = v.get("pixels")
                if not p:
                    continue
                add(f"| {n} | " + " | ".join(v["settings"][k] for k in varied)
                    + f" | {fmt(p['rmse'])} | {fmt(p.get('rmse_without_noise'))} | {fmt(p.get('noise_share'), 2)} | "
                    f"{fmt(p['bias_share'], 2)} | {fmt(p['luminance_ratio'], 2)} | {fmt(p['hair_share_of_frame'], 2)} |")
        add("")
        shares = [v["pixels"] for n in order for v in cases[n]["variants"] if v.get("pixels")]
        add(f"Over every row: the references' noise is {fmt(mean([p.get('noise_share') for p in shares]), 2)} of "
            f"the hair's mean square error on average, one offset per channel {fmt(mean([p['bias_share'] for p in shares]), 2)}, "
            f"the rest ({fmt(1 - mean([p.get('noise_share') or 0 for p in shares]) - mean([p['bias_share'] for p in shares]), 2)}) "
            "is where and how the light falls: shadows, highlights, the look of each strand. The hair holds "
            f"{fmt(mean([p['hair_share_of_frame'] for p in shares]), 2)} of the frame's squared error on average.")
        add("")
    f = s["furthest"]
    add(f"Furthest from the reference: {f['case']} with "
        + ", ".join(f"{k}={v}" for k, v in f["settings"].items())
        + f" (hair RMSE {fmt(f['hair']['rmse'] if f['hair'] else None)}, SSIM {fmt(f['hair']['ssim'] if f['hair'] else None)}).")
    add("")
    add("The closest variant of each case, and what is left of the error with it:")
    add("")
    add("| case | closest | hair RMSE | hair SSIM | furthest | hair RMSE | hair SSIM |")
    add("|---|---|---|---|---|---|---|")
    for n in order:
        c = cases[n]
        b = next(v for v in c["variants"] if v["settings"] == c["best"])
        w = next(v for v in c["variants"] if v["settings"] == c["worst"])
        name = lambda v: ", ".join(f"{k}={x}" for k, x in v["settings"].items())  # noqa: E731
        hb, hw = b["hair"] or {}, w["hair"] or {}
        add(f"| {n} | {name(b)} | {fmt(hb.get('rmse'))} | {fmt(hb.get('ssim'))} | {name(w)} | "
            f"{fmt(hw.get('rmse'))} | {fmt(hw.get('ssim'))} |")
    add("")
    if any(cases[n]["terms"] for n in order):
        add("## Which light the error comes from")
        add("")
        add("The first variant ("
            + ", ".join(f"{k}={v}" for k, v in cases[order[0]]["variants"][0]["settings"].items())
            + ") and its reference with every light, with the key light alone, and without it, each "
            "measured against its own reference:")
        add("")
        add("| case | lights | RMSE | SSIM | hair RMSE | hair relMSE | hair SSIM | reference noise |")
        add("|---|---|---|---|---|---|---|---|")
        for n in order:
            c = cases[n]
            rows = [("every light", c["variants"][0], c["reference"])]
            rows += [(TERMS[t["term"]], t, t["term_reference"]) for t in c["terms"]]
            for label, v, ref in rows:
                hair = v["hair"] or {m: None for m in METRICS}
                add(f"| {n} | {label} | {fmt(v['frame']['rmse'])} | {fmt(v['frame']['ssim'])} | "
                    f"{fmt(hair['rmse'])} | {fmt(hair['rel_mse'])} | {fmt(hair['ssim'])} | "
                    f"{fmt(ref.get('noise_levels'), 2)} |")
        add("")
    add("## Pictures")
    add("")
    grooms = list(dict.fromkeys(cases[n]["groom"] for n in order))
    if result["sheets_by"] != "none":
        for g in grooms:
            add(f"- `fidelity-{g}.png` (made by {result['sheets_by']}): a row per case ("
                + ", ".join(n for n in order if cases[n]["groom"] == g)
                + "): the reference, the closest real-time frame, its error, the furthest, its error "
                "(`wisp compare`'s false colour: dark purple 0 to pale yellow 0.1 or more, linear).")
            add(f"- `fidelity-{g}-all.png`: the same rows: the reference, then every variant in the table's order.")
    else:
        add("No sheets were made: neither ffmpeg nor Pillow was found where this ran.")
    p = result["packed"]
    add(f"- `{p['tar']}`: {p['files']} pictures (references first, then each case's closest and furthest, "
        "the frames without hair, the other variants, the light terms, the error images)"
        + (f"; {len(p['left_out'])} left out to keep it small (they stay in work/; the run is "
           "deterministic, so rerunning a case gives them again): " + ", ".join(p["left_out"][:12])
           + (" ..." if len(p["left_out"]) > 12 else "") if p["left_out"] else "; nothing left out")
        + ".")
    add("")
    return "\n".join(lines)


def sheet(args):
    from PIL import Image

    with open(args.rows, encoding="utf-8") as f:
        rows = [line.rstrip("\n").split("\t") for line in f if line.strip()]
    strips = []
    for row in rows:
        pictures = []
        for p in row:
            im = Image.open(p).convert("RGB")
            h = max(1, round(im.height * args.width / im.width))
            pictures.append(im.resize((args.width, h), Image.BOX))
        strip = Image.new("RGB", (sum(p.width for p in pictures), max(p.height for p in pictures)))
        x = 0
        for p in pictures:
            strip.paste(p, (x, 0))
            x += p.width
        strips.append(strip)
    whole = Image.new("RGB", (max(s.width for s in strips), sum(s.height for s in strips)))
    y = 0
    for s in strips:
        whole.paste(s, (0, y))
        y += s.height
    partial = args.out + ".partial.png"
    whole.save(partial)
    os.replace(partial, args.out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="what", required=True)
    t = sub.add_parser("table")
    t.add_argument("--manifest", required=True)
    t.add_argument("--out", required=True)
    t.add_argument("--command", required=True)
    t.add_argument("--devices", default="")
    t.add_argument("--spp", type=int, required=True)
    t.add_argument("--width", type=int, required=True)
    t.add_argument("--height", type=int, required=True)
    t.add_argument("--frames", type=int, required=True)
    t.add_argument("--render-seconds", type=int, required=True)
    t.add_argument("--pack-mb", type=int, required=True)
    t.add_argument("--sets", default="")
    t.add_argument("--sheets-by", default="none")
    t.add_argument("--resumed", type=int, default=0)
    s = sub.add_parser("sheet")
    s.add_argument("--rows", required=True)
    s.add_argument("--width", type=int, required=True)
    s.add_argument("--out", required=True)
    args = parser.parse_args()
    table(args) if args.what == "table" else sheet(args)


if __name__ == "__main__":
    main()
