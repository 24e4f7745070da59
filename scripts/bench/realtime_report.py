"""scripts/bench/realtime.sh's report: each frame's time and error against the
reference into a CSV, and a plot of error against accumulated frames (per K)
and against GPU time (the deterministic E = 0.02 frame beside it)."""
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "lib"))
from bench_images import error_columns, read_pfm, write_rows  # noqa: E402

COLUMNS = ["lights", "size", "method", "realtime_cut", "realtime_rays", "frames", "gpu_ms_per_frame", "gpu_ms_total",
           "shadow_rays_per_pixel", "rel_mse", "rel_err_mean", "rel_err_p99", "within_2pct", "max_err"]


def relative_mse(image, reference):
    return float(((image - reference) ** 2).sum() / max((reference ** 2).sum(), 1e-30))


def row(work, tag, reference, geometry_pixels, lights, size):
    stats = json.load(open(os.path.join(work, tag + ".json")))
    pfm = os.path.join(work, tag + ".pfm")
    frames = int(stats.get("realtime_frames", 1)) if "realtime_cut" in stats else 1
    r = {"lights": lights, "size": size, "method": tag.split("_")[0],
         "realtime_cut": stats.get("realtime_cut", ""), "realtime_rays": stats.get("realtime_rays", ""),
         "frames": frames,
         "gpu_ms_per_frame": round(stats["render_ms"], 2),
         "gpu_ms_total": round(stats["render_ms"] * frames, 2),
         "shadow_rays_per_pixel": round(stats["shadow_rays"] / max(stats["geometry_pixels"], 1), 2),
         "rel_mse": round(relative_mse(read_pfm(pfm), reference), 6)}
    if tag != "reference":
        r.update(error_columns(pfm, reference, geometry_pixels))
    return r


def plot(rows, out, device):
    fig, (by_frames, by_time) = plt.subplots(1, 2, figsize=(11, 4.2))
    deterministic = next(r for r in rows if r["method"] == "lightcuts")
    styles = {0: "o-", 4: "s--", 1: "^:"}
    for k in sorted({r["realtime_cut"] for r in rows if r["method"] == "realtime"}):
        colour = f"C{[8, 16, 32].index(k) if k in (8, 16, 32) else 3}"
        for s in sorted({r["realtime_rays"] for r in rows if r["method"] == "realtime"}):
            series = [r for r in rows if r["method"] == "realtime" and r["realtime_cut"] == k
                      and r["realtime_rays"] == s]
            if not series:
                continue
            label = f"K = {k}, " + ("a ray per node" if s == 0 else f"{s} rays")
            frames = np.array([r["frames"] for r in series])
            mse = np.array([r["rel_mse"] for r in series])
            by_frames.loglog(frames, mse, styles.get(s, "x-"), color=colour, label=label)
            by_time.loglog([r["gpu_ms_total"] for r in series], [r["rel_err_mean"] for r in series],
                           styles.get(s, "x-"), color=colour, label=label)
    first = [r for r in rows if r["method"] == "realtime" and r["frames"] == 1][0]
    f = np.array([1, 64])
    by_frames.loglog(f, first["rel_mse"] / f, "k:", label="1 / frames")
    by_frames.axhline(deterministic["rel_mse"], color="tab:red", ls="--", label="lightcuts E = 0.02")
    by_frames.set_xlabel("frames accumulated")
    by_frames.set_ylabel("relative MSE against the reference")
    by_time.scatter([deterministic["gpu_ms_total"]], [deterministic["rel_err_mean"]], color="tab:red",
                    marker="s", zorder=3, label="lightcuts E = 0.02, one frame")
    by_time.set_xlabel("GPU time, all frames (ms)")
    by_time.set_ylabel("mean relative error of lit pixels")
    for ax in (by_frames, by_time):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"Real-time mode: {rows[0]['lights']} lights, {rows[0]['size']}, {device}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    work, base, lights, size, csv_out, png_out = sys.argv[1:7]
    reference = read_pfm(os.path.join(base, "reference.pfm"))
    geometry_pixels = json.load(open(os.path.join(base, "reference.json")))["geometry_pixels"]
    tags = ["lightcuts_0.02"] + [f"realtime_{k}_{s}_{f}" for k in (8, 16, 32) for s in (0, 4, 1)
                                 for f in (1, 4, 16, 64)]
    tags += [f"filtered_{k}" for k in (8, 16, 32)]
    rows = [row(work, t, reference, geometry_pixels, lights, size) for t in tags]
    ref_stats = json.load(open(os.path.join(base, "reference.json")))
    rows.insert(0, {"lights": lights, "size": size, "method": "reference", "frames": 1,
                    "gpu_ms_per_frame": round(ref_stats["render_ms"], 2),
                    "gpu_ms_total": round(ref_stats["render_ms"], 2),
                    "shadow_rays_per_pixel": round(ref_stats["shadow_rays"] / max(geometry_pixels, 1), 2),
                    "rel_mse": 0.0})
    write_rows(csv_out, COLUMNS, rows)
    plot(rows[1:], png_out, ref_stats.get("device", "unknown device"))
    for r in rows:
        print(", ".join(f"{c} {r.get(c, '')}" for c in COLUMNS if r.get(c, "") != ""))


if __name__ == "__main__":
    main()
