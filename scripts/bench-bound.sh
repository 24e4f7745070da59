#!/usr/bin/env bash
# Lightcuts with the paper's error-bound criterion against the reference, one
# run per row, on the generated room (add-lights: random point lights,
# intensity 0.05, unbounded), baked with the agglomerative builder on a spawned
# server. Writes docs/bench/bound_targets.csv:
#   lights, size, reference_ms, lightcuts_ms, speedup, avg_cut, max_cut,
#   max_cut_hits, rel_err_mean, rel_err_p99, frac_over_error, error_ratio
# The *_ms columns are the whole frame's GPU time (G-buffer, lighting, tone
# map) by timestamps; speedup = reference_ms / lightcuts_ms. Error statistics
# are over pixels whose reference luminance exceeds 1e-3 x the mean
# (editor_client/render/error_stats.h).
# Usage: scripts/bench-bound.sh [build-dir] [--large]
#   --large adds 131072 lights at 128x128 (a long bake).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"
large="${2:-}"
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build_dir" --target editor_client lightmass_server -j "$(nproc)"
client="$build_dir/bin/editor_client"
out=docs/bench/bound_targets.csv
mkdir -p docs/bench
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

run_case() {  # lights size
  local lights=$1 size=$2
  local scene="$work/room_${lights}.gltf" stats="$work/stats_${lights}.json"
  "$client" add-lights --count "$lights" --layout random --type point --intensity 0.05 \
    --range 0 -o "$scene" >/dev/null
  # Validation would slow the GPU work down; the benchmark measures the renderer alone.
  LC_VALIDATION=0 "$client" render "$scene" --spawn-server --builder agglomerative \
    --mode lightcuts --criterion bound --compare-reference --size "$size" \
    -o "$work/room_${lights}.png" --stats "$stats"
  python3 - "$stats" "$lights" "$size" >>"$work/rows.csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
ref, lc = s["reference_ms"], s["render_ms"]
print(",".join([sys.argv[2], sys.argv[3], "%.1f" % ref, "%.1f" % lc, "%.2f" % (ref / lc),
                "%.1f" % s["avg_cut"], str(s["max_cut"]), str(s["max_cut_hits"]),
                "%.4f" % s["rel_err_mean"], "%.4f" % s["rel_err_p99"],
                "%.4f" % s["frac_over_error"], "%g" % s["error_ratio"]]))
PY
}

run_case 16384 256x256
if [[ "$large" == "--large" ]]; then run_case 131072 128x128; fi
{
  echo "lights,size,reference_ms,lightcuts_ms,speedup,avg_cut,max_cut,max_cut_hits,rel_err_mean,rel_err_p99,frac_over_error,error_ratio"
  cat "$work/rows.csv"
} >"$out"
cat "$out"
