#!/usr/bin/env bash
# What the real-time mode's accuracy costs in time (issue #29): the furnished
# room with LIGHTS unbounded point lights (agglomerative tree, shadow rays on),
# one run, every frame after a warm-up:
#   reference          every light with its shadow ray (GPU), the exact answer;
#   lightcuts_0.02     the deterministic frame at E = 0.02 (walk search);
#   realtime_K_F       the real-time mode at K = 8, 16, 32 nodes per 8x8 block's
#                      cut (at most K shadow rays per pixel and frame), its image
#                      the mean of F = 1, 4, 16, 64 frames of the still view
#                      (render --mode realtime --realtime-cut K --frames F).
# Times are GPU timestamps per frame (the mean over F frames); errors against
# the reference (error_stats.cpp's definition, scripts/sweep_accuracy.py) on
# every lit pixel, and the relative MSE. Writes docs/bench/realtime.csv and
# docs/bench/realtime.png (error against frames per K, and against time).
# Usage: scripts/bench-realtime.sh [build-dir] [lights] [size]
# LC_BENCH_CACHE=DIR keeps the scene, tree and reference in DIR/realtime_LIGHTS/.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"
lights="${2:-16384}"
size="${3:-256x256}"
source scripts/lib/furnished_bench.sh
build_bench_client "$build_dir"
client="$LC_CLIENT"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
base="$work"
if [[ -n "${LC_BENCH_CACHE:-}" ]]; then base="$LC_BENCH_CACHE/realtime_$lights"; mkdir -p "$base"; fi
[[ -f "$base/tree.lcut" ]] || make_furnished_room "$base" "$lights"
render() {  # render TAG ARGS...: the frame's PFM and stats in $work
    local tag=$1; shift
    "$client" render "$base/scene.gltf" --tree "$base/tree.lcut" --size "$size" \
        -o "$work/$tag.png" --float "$work/$tag.pfm" --stats "$work/$tag.json" "$@" >/dev/null
}
if [[ ! -f "$base/reference.pfm" ]]; then
    render reference --mode reference
    cp "$work/reference.pfm" "$work/reference.json" "$base/"
fi
render lightcuts_0.02 --mode lightcuts --error 0.02
for k in 8 16 32; do
    for f in 1 4 16 64; do render "realtime_${k}_${f}" --mode realtime --realtime-cut "$k" --frames "$f"; done
done
/usr/bin/python3 scripts/realtime_report.py "$work" "$base" "$lights" "$size" docs/bench/realtime.csv \
    docs/bench/realtime.png
