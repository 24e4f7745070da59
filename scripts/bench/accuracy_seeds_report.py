#!/usr/bin/python3
"""The table of scripts/bench-accuracy-seeds.sh.

One CSV row per tree seed and way of choosing representatives: the same
lights, the same frame settings and the same reference, only the
representatives' draws differ (bake --seed for the tree's, render
--representative-seed for the per-pixel ones). Error
columns as scripts/bench/speedup_report.py writes them (error_stats.cpp's
definition), plus the signed side: the mean signed error and how many lit
pixels are over 2% too dark and too bright.
"""
import argparse
import itertools
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "lib"))
from bench_images import error_columns, read_pfm, write_rows  # noqa: E402
from sweep_accuracy import NEGLIGIBLE_FRACTION, luminance  # noqa: E402

COLUMNS = ["lights", "size", "error_ratio", "max_cut", "representatives", "seed", "time_ms",
           "cpu_s", "avg_cut", "shadow_rays", "max_cut_hits", "rel_err_mean", "rel_err_p99",
           "within_2pct", "max_err", "signed_mean", "over_2pct_dark", "over_2pct_bright"]


def signed_columns(image, reference, geometry_pixels):
    """The signed relative errors over error_stats' lit pixels."""
    y_ref = luminance(reference)
    lit = np.isfinite(y_ref) & (y_ref > NEGLIGIBLE_FRACTION * y_ref[np.isfinite(y_ref)].sum()
                                / max(geometry_pixels, 1))
    e = (luminance(image)[lit] - y_ref[lit]) / y_ref[lit]
    return {"signed_mean": round(float(e.mean()), 5), "over_2pct_dark": int((e < -0.02).sum()),
            "over_2pct_bright": int((e > 0.02).sum())}


def main():
    parser = argparse.ArgumentParser()
    for flag in ("--work", "--lights", "--size", "--seeds", "--representatives", "--csv"):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    ref = json.load(open(os.path.join(args.work, "reference.json")))
    reference = read_pfm(os.path.join(args.work, "reference.pfm"))
    rows = []
    for representatives, seed in itertools.product(args.representatives.split(","),
                                                   args.seeds.split(",")):
        base = os.path.join(args.work, f"{representatives}-seed{seed}")
        s = json.load(open(base + ".json"))
        user, system = (float(v) for v in open(base + ".time").read().split()[:2])
        row = {"lights": args.lights, "size": args.size, "error_ratio": round(s["error_ratio"], 6),
               "max_cut": s["max_cut_setting"] if "max_cut_setting" in s else "",
               "representatives": representatives, "seed": seed,
               "time_ms": round(s["render_ms"], 1), "cpu_s": round(user + system, 1),
               "avg_cut": round(s["avg_cut"], 1), "shadow_rays": s["shadow_rays"],
               "max_cut_hits": s["max_cut_hits"]}
        row.update(error_columns(base + ".pfm", reference, ref["geometry_pixels"]))
        row.update(signed_columns(read_pfm(base + ".pfm"), reference, ref["geometry_pixels"]))
        rows.append(row)
    write_rows(args.csv, COLUMNS, rows)


if __name__ == "__main__":
    main()
