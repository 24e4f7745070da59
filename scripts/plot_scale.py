"""Plots docs/bench/scale.csv (scripts/bench-scale.sh): time and peak memory
against the light count, log-log. Usage: plot_scale.py SCALE.csv OUT.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    source, target = sys.argv[1], sys.argv[2]
    with open(source) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("no rows in " + source)
    lights = [int(r["lights"]) for r in rows]

    def column(name, scale=1.0):
        return [float(r[name]) * scale for r in rows]

    fig, (time_ax, memory_ax) = plt.subplots(1, 2, figsize=(12, 4.8))
    for name, label, scale in [
        ("bake_wall_s", "bake end to end, agglomerative", 1.0),
        ("bake_wall_lbvh_s", "bake end to end, lbvh", 1.0),
        ("build_agglomerative_ms", "build, agglomerative", 1e-3),
        ("build_lbvh_ms", "build, lbvh", 1e-3),
        ("download_ms", "result stream", 1e-3),
        ("render_wall_s", "render --tree 256x256, wall", 1.0),
        ("render_gpu_ms", "render, GPU", 1e-3),
    ]:
        time_ax.loglog(lights, column(name, scale), marker="o", label=label)
    time_ax.axhline(10.0, color="grey", linestyle=":", label="10 s target (2^20)")
    time_ax.set_xlabel("lights")
    time_ax.set_ylabel("seconds")
    time_ax.set_title("time")
    time_ax.legend(fontsize=7)
    time_ax.grid(True, which="both", alpha=0.3)

    for name, label in [
        ("client_peak_mb", "bake client"),
        ("server_peak_mb", "server"),
        ("render_peak_mb", "render client"),
        ("gltf_mb", "glTF on disk"),
    ]:
        memory_ax.loglog(lights, column(name), marker="o", label=label)
    memory_ax.axhline(1024.0, color="grey", linestyle=":", label="1 GB client target (2^20)")
    memory_ax.set_xlabel("lights")
    memory_ax.set_ylabel("MiB")
    memory_ax.set_title("peak memory")
    memory_ax.legend(fontsize=7)
    memory_ax.grid(True, which="both", alpha=0.3)

    fig.tight_layout()
    fig.savefig(target, dpi=110)
    print("wrote", target)


if __name__ == "__main__":
    main()
