#!/usr/bin/env bash
# Light-tree build benchmark: builds tests/benchmarks/tree_build_bench, runs each
# case in its own process (so peak RSS belongs to that case alone) and writes
# docs/bench/tree_build.csv:
#   builder, lights, build_ms, peak_rss_mb, bytes_per_light, pairing_cost,
#   lower_bound, exact, depth, cluster_metric
# and each build's steps (BuildReport::phases) to docs/bench/tree_build_phases.csv:
#   builder, lights, phase, ms
# pairing_cost / lower_bound / exact are the optimal-pair builder's (sums over
# levels); cluster_metric is the paper's I_C * alpha_C^2 summed over clusters.
# Usage: scripts/bench/build.sh [build-dir]   (default: build, the default preset)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build_dir" --target tree_build_bench -j "$(nproc)"
bench="$build_dir/bin/tree_build_bench"
out=docs/bench/tree_build.csv
mkdir -p docs/bench
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

cases=$("$bench" --benchmark_list_tests)
for name in $cases; do
  echo "running $name" >&2
  # Exact name match: the filter is a regular expression.
  "$bench" --benchmark_filter="^${name}\$" --benchmark_format=json \
    > "$tmp/$(echo "$name" | tr '/:' '__').json"
done

python3 - "$tmp" "$out" docs/bench/tree_build_phases.csv <<'PY'
import csv, glob, json, sys
tmp, out, phases_out = sys.argv[1], sys.argv[2], sys.argv[3]
rows = []
phases = []
for path in sorted(glob.glob(tmp + "/*.json")):
    with open(path) as f:
        for b in json.load(f)["benchmarks"]:
            if b.get("error_occurred"):
                sys.exit("benchmark %s failed: %s" % (b["name"], b.get("error_message")))
            builder = b["name"].split("/")[0].replace("_", "-")
            lights = int(b["lights"])
            rss = float(b["peak_rss_mb"])
            pairing = builder.startswith("optimal-pair")
            rows.append([builder, lights, "%.2f" % b["build_ms"], "%.1f" % rss,
                         "%.0f" % (rss * 1024 * 1024 / lights),
                         "%.6g" % b["pairing_cost"] if pairing else "",
                         "%.6g" % b["lower_bound"] if pairing else "",
                         int(b["exact"]) if pairing else "", int(b["depth"]),
                         "%.6g" % b["cluster_metric"]])
            for key, value in b.items():
                if key.startswith("ms "):
                    phases.append([builder, lights, key[3:], "%.2f" % value])
rows.sort(key=lambda r: (r[0], r[1]))
phases.sort(key=lambda r: (r[0], r[1]))
with open(phases_out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["builder", "lights", "phase", "ms"])
    w.writerows(phases)
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["builder", "lights", "build_ms", "peak_rss_mb", "bytes_per_light",
                "pairing_cost", "lower_bound", "exact", "depth", "cluster_metric"])
    w.writerows(rows)
print("wrote", out, "(%d rows)" % len(rows))
PY
