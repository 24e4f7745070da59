#!/usr/bin/python3
"""The table, plot and crop of scripts/bench-supersampling.sh.

Reads the renders' stats JSON and float images from --work, measures each
against the reference (sweep_accuracy.py's error_stats: error_stats.cpp's
definition, relative luminance error over the lit pixels), and writes one CSV
row per method, a bar plot of time and shadow rays, and a crop of the 8-bit
images (1 spp lightcuts, reconstruction cuts at N spp) enlarged 4x.
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "lib"))
from bench_images import error_columns, read_pfm, write_rows  # noqa: E402

METHODS = ["reference", "gpu", "lightcuts", "reconstruction", "one_spp"]
COLUMNS = ["method", "lights", "size", "spp", "shading_ms", "shadow_rays", "lightcuts_computed",
           "reconstruction_cuts", "rel_err_mean", "rel_err_p99", "within_2pct", "max_err",
           "nonfinite_pixels"]


def main():
    parser = argparse.ArgumentParser()
    for flag in ("--work", "--lights", "--size", "--spp", "--csv", "--plot", "--crop"):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    stats = {m: json.load(open(os.path.join(args.work, m + ".json"))) for m in METHODS}
    reference = read_pfm(os.path.join(args.work, "reference.pfm"))
    geometry = stats["reference"]["geometry_pixels"]
    rows = []
    for m in METHODS:
        s = stats[m]
        row = {"method": m, "lights": args.lights, "size": args.size,
               "spp": s.get("spp", 1), "shading_ms": round(s["render_ms"], 1),
               "shadow_rays": s["shadow_rays"],
               "lightcuts_computed": s.get("lightcuts_computed", ""),
               "reconstruction_cuts": s.get("reconstruction_cuts", ""),
               "nonfinite_pixels": s["nonfinite_pixels"]}
        if m != "reference":
            row.update(error_columns(os.path.join(args.work, m + ".pfm"), reference, geometry))
        rows.append(row)
    write_rows(args.csv, COLUMNS, rows)

    shown = [r for r in rows if r["method"] in ("reference", "gpu", "lightcuts", "reconstruction")]
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.2))
    names = [r["method"] for r in shown]
    axes[0].bar(names, [r["shading_ms"] / 1000.0 for r in shown], color="#4878a8")
    axes[0].set_ylabel("shading time, s")
    axes[0].set_yscale("log")
    axes[1].bar(names, [max(r["shadow_rays"], 1) for r in shown], color="#a85848")
    axes[1].set_ylabel("shadow rays")
    axes[1].set_yscale("log")
    fig.suptitle(f"furnished room, {args.lights} lights, {args.size}, {args.spp} spp (lavapipe / CPU, 2 cores)")
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)

    crop_edges(args.work, ("one_spp", "reconstruction"), args.crop)


def crop_edges(work, methods, path):
    """The table's front corner, its legs and its shadow, enlarged 4x without smoothing."""
    crops = []
    for m in methods:
        image = Image.open(os.path.join(work, m + ".png")).convert("RGB")
        w, h = image.size
        box = (int(w * 0.12), int(h * 0.40), int(w * 0.52), int(h * 0.80))
        crops.append(image.crop(box).resize((4 * (box[2] - box[0]), 4 * (box[3] - box[1])),
                                            Image.NEAREST))
    out = Image.new("RGB", (sum(c.width for c in crops) + 8 * (len(crops) - 1), crops[0].height),
                    (255, 255, 255))
    x = 0
    for c in crops:
        out.paste(c, (x, 0))
        x += c.width + 8
    out.save(path)


if __name__ == "__main__":
    main()
