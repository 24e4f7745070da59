"""Plots docs/bench/scale.csv (scripts/bench/scale.sh): time and peak memory
against the light count, log-log. Usage: plot_scale.py SCALE.csv OUT.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TIME_SERIES = [  # column, label, factor to seconds
    ("bake_wall_s", "bake end to end, agglomerative", 1.0),
    ("bake_wall_lbvh_s", "bake end to end, lbvh", 1.0),
    ("build_agglomerative_ms", "build, agglomerative", 1e-3),
    ("build_lbvh_ms", "build, lbvh", 1e-3),
    ("download_ms", "result stream", 1e-3),
    ("render_wall_s", "render --tree 256x256, wall", 1.0),
    ("render_gpu_ms", "render, GPU", 1e-3),
]
MEMORY_SERIES = [  # column, label, factor to MiB
    ("client_peak_mb", "bake client", 1.0),
    ("server_peak_mb", "server", 1.0),
    ("render_peak_mb", "render client", 1.0),
    ("gltf_mb", "glTF on disk", 1.0),
]


def panel(ax, rows, lights, series, target, target_label, unit, title):
    for name, label, factor in series:
        ax.loglog(lights, [float(r[name]) * factor for r in rows], marker="o", label=label)
    ax.axhline(target, color="grey", linestyle=":", label=target_label)
    ax.set_xlabel("lights")
    ax.set_ylabel(unit)
    ax.set_title(title)
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)


def main():
    source, target = sys.argv[1], sys.argv[2]
    with open(source) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("no rows in " + source)
    lights = [int(r["lights"]) for r in rows]
    fig, (time_ax, memory_ax) = plt.subplots(1, 2, figsize=(12, 4.8))
    panel(time_ax, rows, lights, TIME_SERIES, 10.0, "10 s target (2^20)", "seconds", "time")
    panel(memory_ax, rows, lights, MEMORY_SERIES, 1024.0, "1 GB client target (2^20)", "MiB",
          "peak memory")
    fig.tight_layout()
    fig.savefig(target, dpi=110)
    print("wrote", target)


if __name__ == "__main__":
    main()
