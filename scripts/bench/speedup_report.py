#!/usr/bin/python3
"""The table and plot of scripts/bench-speedup.sh.

One CSV row per light count and method: its time, the reference's, the
speed-up, cut size, shadow rays, and the error against the reference
(sweep_accuracy.py's error_stats: error_stats.cpp's definition); the
no-shadow rows are the profile's (no error: they lack the shadows).

A reference rendered at every K-th pixel or 8x8 tile (render --pixel-stride K
or --tile-stride K, its stats' pixel_stride and stride_tile) did the full
reference's work per pixel on a K^2-th of the pixels: reference_ms is its measured time scaled by the full image's pixels
over its own (reference_measured_ms and reference_stride say so), and every
error is measured on its pixels only, unless a full reference image of the
same scene was kept (reference_full.pfm, from the benchmark's cache): then on
every pixel. Where the reference was not strided, strided copies
(reference_check4, reference_check8) are rows of their own: their scaled time
against the full one, and their pixels' error against the full reference's.
The CPU methods' cpu_ms is their workers' CPU time (time_ms is wall);
command_cpu_s is the whole command's (user + system, every thread), where the
benchmark measured it.
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "lib"))
from bench_images import error_columns, read_pfm, write_rows  # noqa: E402

METHODS = {
    "gpu_0.02": "gpu", "shared_0.02": "gpu shared cuts", "reconstruction_0.02": "reconstruction",
    "gpu_0.005": "gpu", "shared_0.005": "gpu shared cuts",
    "reconstruction_0.005": "reconstruction",
    "shared_0.005_maxcut2500": "gpu shared cuts, max cut 2500",
    "shared_0.005_maxcut2500_importance": "gpu shared cuts, max cut 2500, importance",
    "gpu_noshadow": "gpu, no shadow rays", "shared_noshadow": "gpu shared cuts, no shadow rays",
}
COLUMNS = ["lights", "size", "method", "error_ratio", "reference_ms", "reference_stride",
           "reference_tile", "reference_measured_ms", "time_ms", "speedup", "gbuffer_ms",
           "lighting_ms", "avg_cut", "shadow_rays", "reference_shadow_rays", "lightcuts_computed",
           "cpu_ms", "command_cpu_s", "reference_command_cpu_s", "rel_err_mean", "rel_err_p99",
           "within_2pct", "max_err"]


def scaled_ms(stats):
    """A frame's time, scaled to the full image where it was strided."""
    stride = stats.get("pixel_stride", 1)
    return stats["render_ms"] * stride * stride, stride


def command_cpu_s(base, tag):
    """User + system seconds of the command that rendered `tag`, if measured."""
    path = os.path.join(base, tag + ".cpu")
    if not os.path.exists(path):
        return ""
    fields = open(path).read().split()
    return round(float(fields[-2]) + float(fields[-1]), 1)


def stride_name(stride, tile):
    """Every stride-th pixel, or every stride-th tile."""
    return f"every {stride}th pixel" if tile == 1 else f"every {stride}th {tile}x{tile} tile"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--replot", action="store_true", help="only draw --plot from --csv")
    for flag in ("--work", "--counts", "--size"):
        parser.add_argument(flag)
    parser.add_argument("--methods", default=",".join(METHODS), help="the frames rendered")
    for flag in ("--csv", "--plot"):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    if args.replot:
        replot(args.csv, args.plot)
        return
    rows = []
    methods = [m for m in METHODS if m in args.methods.split(",")]
    for lights in args.counts.split(","):
        base = os.path.join(args.work, lights)
        ref = json.load(open(os.path.join(base, "reference.json")))
        reference_ms, stride = scaled_ms(ref)
        tile = ref.get("stride_tile", 1)
        # The errors' reference: the full image where one was kept, else this one.
        error_ref, error_stride, error_tile = ref, stride, tile
        full_path = os.path.join(base, "reference_full.pfm")
        if stride > 1 and os.path.exists(full_path):
            error_ref = json.load(open(os.path.join(base, "reference_full.json")))
            error_stride, error_tile = 1, 1
            reference = read_pfm(full_path)
        else:
            reference = read_pfm(os.path.join(base, "reference.pfm"))
        common = {"lights": lights, "size": args.size, "reference_ms": round(reference_ms, 1),
                  "reference_stride": stride, "reference_tile": tile,
                  "reference_measured_ms": round(ref["render_ms"], 1),
                  "reference_shadow_rays": ref["shadow_rays"],
                  "reference_command_cpu_s": command_cpu_s(base, "reference")}
        for check_stride in (4, 8):
            check_path = os.path.join(base, f"reference_check{check_stride}.json")
            if not os.path.exists(check_path):
                continue
            check = json.load(open(check_path))
            check_ms, check_stride = scaled_ms(check)
            check_tile = check.get("stride_tile", 1)
            row = dict(common, method=f"reference at {stride_name(check_stride, check_tile)}, scaled",
                       time_ms=round(check_ms, 1), speedup=round(reference_ms / check_ms, 3),
                       gbuffer_ms=round(check["gbuffer_ms"], 1),
                       lighting_ms=round(check["lighting_ms"], 1), avg_cut=check["avg_cut"],
                       shadow_rays=check["shadow_rays"],
                       command_cpu_s=command_cpu_s(base, f"reference_check{check_stride}"))
            # The full reference at the strided one's pixels, against it.
            check_image = read_pfm(os.path.join(base, f"reference_check{check_stride}.pfm"))
            row.update(error_columns(os.path.join(base, "reference.pfm"), check_image,
                                     check["geometry_pixels"], check_stride, check_tile))
            rows.append(row)
        for m in methods:
            method = METHODS[m]
            s = json.load(open(os.path.join(base, m + ".json")))
            row = dict(common, method=method,
                       error_ratio=round(s["error_ratio"], 6) if "error_ratio" in s else "",
                       time_ms=round(s["render_ms"], 1),
                       speedup=round(reference_ms / s["render_ms"], 2),
                       gbuffer_ms=round(s["gbuffer_ms"], 1), lighting_ms=round(s["lighting_ms"], 1),
                       avg_cut=round(s["avg_cut"], 1), shadow_rays=s["shadow_rays"],
                       lightcuts_computed=s.get("lightcuts_computed", ""),
                       cpu_ms=round(s["shading_cpu_ms"], 1) if "shading_cpu_ms" in s else "",
                       command_cpu_s=command_cpu_s(base, m))
            if "noshadow" not in m:
                row.update(error_columns(os.path.join(base, m + ".pfm"), reference,
                                         error_ref["geometry_pixels"], error_stride, error_tile))
            rows.append(row)
    write_rows(args.csv, COLUMNS, rows)
    plot(rows, args.size, args.plot)


SHORT = {"gpu": "walk", "gpu shared cuts": "shared", "reconstruction": "reconstr.",
         "gpu shared cuts, max cut 2500": "shared, K 2500",
         "gpu shared cuts, max cut 2500, importance": "shared, K 2500, imp."}


def plot(rows, size, path):
    shown = [r for r in rows if r["method"] in SHORT]
    labels = [f"{SHORT[r['method']]} {int(r['lights']) // 1024}k E={float(r['error_ratio']):g}"
              for r in shown]
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.6))
    bars = axes[0].bar(labels, [float(r["speedup"]) for r in shown], color="#4878a8")
    axes[0].bar_label(bars, fmt="%.0fx", fontsize=7)
    axes[0].set_ylabel("speed-up over the reference")
    axes[0].set_yscale("log")
    # The targets at E = 0.02: 30x at 16,384 lights, 200x at 131,072.
    for target in (30, 200):
        axes[0].axhline(target, color="#a84848", linestyle="--", linewidth=0.8)
    accuracy = axes[1].bar(labels, [100 * float(r["within_2pct"]) for r in shown], color="#58a848")
    axes[1].bar_label(accuracy, fmt="%.2f", fontsize=6, rotation=90, padding=-28, color="white")
    axes[1].set_ylabel("% lit pixels within 2%")
    axes[1].set_ylim(50, 100)
    # The target at E = 0.005: 99% of lit pixels within 2%.
    axes[1].axhline(99, color="#a84848", linestyle="--", linewidth=0.8)
    for ax in axes:
        ax.tick_params(axis="x", labelsize=7, labelrotation=60)
    strided = sorted({f"{r['lights']} lights: reference at "
                      + stride_name(r["reference_stride"], int(r.get("reference_tile") or 1))
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
