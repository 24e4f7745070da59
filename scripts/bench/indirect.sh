#!/usr/bin/env bash
# Indirect-light benchmark (issue 16): builds tests/benchmarks/indirect_bench,
# runs it once on the Cornell box lit by its ceiling panel and writes
#   docs/bench/indirect.csv: method, parameter (VPL paths or patch size),
#     lights, bake_s, max_wall_error, mean_wall_error
#     (relative error of each wall's mean reflected radiosity, per channel,
#     against a path-traced reference of 10^6 paths per wall)
#   docs/bench/indirect_convergence.csv: patch_size, step, seconds, shot_fraction
# and plots both into docs/images/indirect_*.png.
# Usage: scripts/bench/indirect.sh [build-dir]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build_dir" --target indirect_bench -j "$(nproc)"
mkdir -p docs/bench docs/images
"$build_dir/bin/indirect_bench" docs/bench/indirect.csv docs/bench/indirect_convergence.csv

/usr/bin/python3 - <<'PY'
import csv
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open("docs/bench/indirect.csv")))
fig, ax = plt.subplots(figsize=(6, 4))
for method, marker in (("vpl", "o"), ("radiosity", "s")):
    pts = [(float(r["bake_s"]), float(r["max_wall_error"])) for r in rows if r["method"] == method]
    labels = [r["parameter"] for r in rows if r["method"] == method]
    ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker=marker, label=method)
    for (x, y), label in zip(pts, labels):
        ax.annotate(label, (x, y), fontsize=7)
ax.set_xlabel("bake time (s)")
ax.set_ylabel("max relative error of a wall's mean")
ax.set_title("Indirect light, Cornell box: error against bake time")
ax.legend()
fig.tight_layout()
fig.savefig("docs/images/indirect_error_time.png", dpi=110)

conv = list(csv.DictReader(open("docs/bench/indirect_convergence.csv")))
fig, ax = plt.subplots(figsize=(6, 4))
for size in sorted({r["patch_size"] for r in conv}, key=float, reverse=True):
    pts = [(float(r["seconds"]), 1.0 - float(r["shot_fraction"])) for r in conv if r["patch_size"] == size]
    ax.semilogy([p[0] for p in pts], [max(p[1], 1e-6) for p in pts], label="patch " + size)
ax.set_xlabel("time (s)")
ax.set_ylabel("unshot fraction of the power")
ax.set_title("Progressive radiosity convergence")
ax.legend()
fig.tight_layout()
fig.savefig("docs/images/indirect_convergence.png", dpi=110)
PY
echo "wrote docs/bench/indirect.csv, docs/bench/indirect_convergence.csv, docs/images/indirect_*.png"
