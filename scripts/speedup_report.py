#!/usr/bin/python3
"""The table and plot of scripts/bench-speedup.sh.

One CSV row per light count and method: its time, the reference's, the
speed-up, cut size, shadow rays, and the error against the reference
(sweep_accuracy.py's error_stats: error_stats.cpp's definition); the
gpu_noshadow row is the profile's (no error: it lacks the shadows).
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_images import error_columns, read_pfm, write_rows  # noqa: E402

METHODS = ["gpu_0.02", "reconstruction_0.02", "gpu_0.005", "reconstruction_0.005", "gpu_noshadow"]
COLUMNS = ["lights", "size", "method", "error_ratio", "reference_ms", "time_ms", "speedup",
           "gbuffer_ms", "lighting_ms", "avg_cut", "shadow_rays", "reference_shadow_rays",
           "lightcuts_computed", "rel_err_mean", "rel_err_p99", "within_2pct", "max_err"]


def main():
    parser = argparse.ArgumentParser()
    for flag in ("--work", "--counts", "--size", "--csv", "--plot"):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    rows = []
    for lights in args.counts.split(","):
        base = os.path.join(args.work, lights)
        ref = json.load(open(os.path.join(base, "reference.json")))
        reference = read_pfm(os.path.join(base, "reference.pfm"))
        for m in METHODS:
            s = json.load(open(os.path.join(base, m + ".json")))
            row = {"lights": lights, "size": args.size, "method": m.split("_")[0],
                   "error_ratio": round(s["error_ratio"], 6) if "error_ratio" in s else "", "reference_ms": round(ref["render_ms"], 1),
                   "time_ms": round(s["render_ms"], 1),
                   "speedup": round(ref["render_ms"] / s["render_ms"], 2),
                   "gbuffer_ms": round(s["gbuffer_ms"], 1), "lighting_ms": round(s["lighting_ms"], 1),
                   "avg_cut": round(s["avg_cut"], 1), "shadow_rays": s["shadow_rays"],
                   "reference_shadow_rays": ref["shadow_rays"],
                   "lightcuts_computed": s.get("lightcuts_computed", "")}
            if m == "gpu_noshadow":
                row["method"] = "gpu, no shadow rays"
            else:
                row.update(error_columns(os.path.join(base, m + ".pfm"), reference,
                                         ref["geometry_pixels"]))
            rows.append(row)
    write_rows(args.csv, COLUMNS, rows)

    shown = [r for r in rows if r["method"] in ("gpu", "reconstruction")]
    labels = [f"{r['method']}\n{int(r['lights']):,}, E={float(r['error_ratio']):g}" for r in shown]
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.4))
    axes[0].bar(labels, [r["speedup"] for r in shown], color="#4878a8")
    axes[0].set_ylabel("speed-up over the reference")
    axes[1].bar(labels, [100 * r["within_2pct"] for r in shown], color="#58a848")
    axes[1].set_ylabel("% lit pixels within 2%")
    axes[1].set_ylim(50, 100)
    for ax in axes:
        ax.tick_params(axis="x", labelsize=7)
    fig.suptitle(f"furnished room, volume lights, {args.size}, 1 spp (lavapipe / CPU, 2 cores)")
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)


if __name__ == "__main__":
    main()
