#!/usr/bin/python3
"""The table and plot of scripts/bench-speedup.sh.

One CSV row per light count and method: its time, the reference's, the
speed-up, cut size, shadow rays, and the error against the reference
(sweep_accuracy.py's error_stats: error_stats.cpp's definition); the
no-shadow rows are the profile's (no error: they lack the shadows).

A reference rendered at every K-th pixel (render --pixel-stride K, its stats'
pixel_stride) did the full reference's work per pixel on a K^2-th of the
pixels: reference_ms is its measured time scaled by the full image's pixels
over its own (reference_measured_ms and reference_stride say so), and every
error is measured on its pixels only. Where the reference was not strided, a
strided copy (reference_check) is one more row: its scaled time against the
full one, and its pixels' error against the full reference's (rounding only).
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_images import error_columns, read_pfm, write_rows  # noqa: E402

METHODS = {
    "gpu_0.02": "gpu", "shared_0.02": "gpu shared cuts", "reconstruction_0.02": "reconstruction",
    "gpu_0.005": "gpu", "shared_0.005": "gpu shared cuts",
    "reconstruction_0.005": "reconstruction",
    "shared_0.005_maxcut2500": "gpu shared cuts, max cut 2500",
    "gpu_noshadow": "gpu, no shadow rays", "shared_noshadow": "gpu shared cuts, no shadow rays",
}
COLUMNS = ["lights", "size", "method", "error_ratio", "reference_ms", "reference_stride",
           "reference_measured_ms", "time_ms", "speedup", "gbuffer_ms", "lighting_ms", "avg_cut",
           "shadow_rays", "reference_shadow_rays", "lightcuts_computed", "rel_err_mean",
           "rel_err_p99", "within_2pct", "max_err"]


def scaled_ms(stats):
    """A frame's time, scaled to the full image where it was strided."""
    stride = stats.get("pixel_stride", 1)
    return stats["render_ms"] * stride * stride, stride


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--replot", action="store_true", help="only draw --plot from --csv")
    for flag in ("--work", "--counts", "--size"):
        parser.add_argument(flag)
    for flag in ("--csv", "--plot"):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    if args.replot:
        replot(args.csv, args.plot)
        return
    rows = []
    for lights in args.counts.split(","):
        base = os.path.join(args.work, lights)
        ref = json.load(open(os.path.join(base, "reference.json")))
        reference = read_pfm(os.path.join(base, "reference.pfm"))
        reference_ms, stride = scaled_ms(ref)
        common = {"lights": lights, "size": args.size, "reference_ms": round(reference_ms, 1),
                  "reference_stride": stride, "reference_measured_ms": round(ref["render_ms"], 1),
                  "reference_shadow_rays": ref["shadow_rays"]}
        check_path = os.path.join(base, "reference_check.json")
        if os.path.exists(check_path):
            check = json.load(open(check_path))
            check_ms, check_stride = scaled_ms(check)
            row = dict(common, method=f"reference at stride {check_stride}, scaled",
                       time_ms=round(check_ms, 1), speedup=round(reference_ms / check_ms, 3),
                       gbuffer_ms=round(check["gbuffer_ms"], 1),
                       lighting_ms=round(check["lighting_ms"], 1), avg_cut=check["avg_cut"],
                       shadow_rays=check["shadow_rays"])
            # The full reference at the strided one's pixels, against it.
            row.update(error_columns(os.path.join(base, "reference.pfm"),
                                     read_pfm(os.path.join(base, "reference_check.pfm")),
                                     check["geometry_pixels"], check_stride))
            rows.append(row)
        for m, method in METHODS.items():
            s = json.load(open(os.path.join(base, m + ".json")))
            row = dict(common, method=method,
                       error_ratio=round(s["error_ratio"], 6) if "error_ratio" in s else "",
                       time_ms=round(s["render_ms"], 1),
                       speedup=round(reference_ms / s["render_ms"], 2),
                       gbuffer_ms=round(s["gbuffer_ms"], 1), lighting_ms=round(s["lighting_ms"], 1),
                       avg_cut=round(s["avg_cut"], 1), shadow_rays=s["shadow_rays"],
                       lightcuts_computed=s.get("lightcuts_computed", ""))
            if "noshadow" not in m:
                row.update(error_columns(os.path.join(base, m + ".pfm"), reference,
                                         ref["geometry_pixels"], stride))
            rows.append(row)
    write_rows(args.csv, COLUMNS, rows)
    plot(rows, args.size, args.plot)


SHORT = {"gpu": "walk", "gpu shared cuts": "shared", "reconstruction": "reconstr.",
         "gpu shared cuts, max cut 2500": "shared, K 2500"}


def plot(rows, size, path):
    shown = [r for r in rows if r["method"] in SHORT]
    labels = [f"{SHORT[r['method']]} {int(r['lights']) // 1024}k E={float(r['error_ratio']):g}"
              for r in shown]
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.6))
    axes[0].bar(labels, [float(r["speedup"]) for r in shown], color="#4878a8")
    axes[0].set_ylabel("speed-up over the reference")
    axes[0].set_yscale("log")
    axes[1].bar(labels, [100 * float(r["within_2pct"]) for r in shown], color="#58a848")
    axes[1].set_ylabel("% lit pixels within 2%")
    axes[1].set_ylim(50, 100)
    for ax in axes:
        ax.tick_params(axis="x", labelsize=7, labelrotation=60)
    strided = sorted({f"{r['lights']} lights: reference at every {r['reference_stride']}th pixel"
                      for r in shown if int(r["reference_stride"]) > 1})
    fig.suptitle(f"furnished room, volume lights, {size}, 1 spp (lavapipe / CPU, 2 cores)"
                 + (f"\n({'; '.join(strided)})" if strided else ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def replot(csv_path, plot_path):
    """The plot again from a written CSV (its size column)."""
    rows = list(csv.DictReader(open(csv_path)))
    plot(rows, rows[0]["size"], plot_path)


if __name__ == "__main__":
    main()
