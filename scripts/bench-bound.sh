#!/usr/bin/env bash
# Lightcuts with the paper's error-bound criterion (walk search) against the
# reference, one run per row, on the generated room (add-lights: random point
# lights, unbounded, 819.2 cd in total: 0.05 cd each at 16,384), baked with the
# agglomerative builder on a spawned server, at E = 0.02 and 0.005. Each frame
# is timed after a warm-up frame (lavapipe compiles shaders on first use). Writes docs/bench/bound_targets.csv:
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

run_case() {  # lights size error
  local lights=$1 size=$2 error=$3
  local scene="$work/room_${lights}.gltf" tree="$work/room_${lights}.lcut"
  local stats="$work/stats_${lights}_${error}.json"
  if [[ ! -f "$tree" ]]; then
    # Total intensity held at 819 cd whatever the count, so images compare.
    "$client" add-lights --count "$lights" --layout random --type point \
      --intensity "$(python3 -c "print(819.2 / $lights)")" --range 0 -o "$scene" >/dev/null
    "$client" bake "$scene" --spawn-server --builder agglomerative -o "$tree" >/dev/null
  fi
  # Validation would slow the GPU work down; the benchmark measures the renderer alone.
  LC_VALIDATION=0 "$client" render "$scene" --tree "$tree" \
    --mode lightcuts --criterion bound --error "$error" --compare-reference --size "$size" \
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

for error in 0.02 0.005; do run_case 16384 256x256 "$error"; done
if [[ "$large" == "--large" ]]; then
  for error in 0.02 0.005; do run_case 131072 128x128 "$error"; done
fi
{
  echo "lights,size,reference_ms,lightcuts_ms,speedup,avg_cut,max_cut,max_cut_hits,rel_err_mean,rel_err_p99,frac_over_error,error_ratio"
  cat "$work/rows.csv"
} >"$out"
cat "$out"
