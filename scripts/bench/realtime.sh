#!/usr/bin/env bash
# What the real-time mode's accuracy costs in time (issue #29): the furnished
# room with LIGHTS unbounded point lights (agglomerative tree, shadow rays on),
# one run, every frame after a warm-up:
#   reference          every light with its shadow ray (GPU), the exact answer;
#   lightcuts_0.02     the deterministic frame at E = 0.02 (walk search);
#   realtime_K_S_F     the real-time mode at K = 8, 16, 32 nodes per 8x8 block's
#                      cut and a budget of S = 0 (one shadow ray per cut node),
#                      4 or 1 shadow rays per pixel and frame, its image the
#                      mean of F = 1, 4, 16, 64 frames of the still view
#                      (render --mode realtime --realtime-cut K --realtime-rays S
#                      --frames F --realtime-filter off: the plain mean, whose
#                      error is the estimator's);
#   filtered_K         one frame at K as the editor shows it (the spatial
#                      filter on, the default budget).
# Times are GPU timestamps per frame (the mean over F frames); errors against
# the reference (error_stats.cpp's definition, scripts/lib/sweep_accuracy.py) on
# every lit pixel, and the relative MSE. Writes docs/bench/realtime.csv and
# docs/bench/realtime.png (error against frames per K, and against time).
# Then the editor (`view --headless --mode realtime`, whole frames of the same
# room at 480x300, camera still, 30 frames) at K = 8 and 16, with and without
# a budget: docs/bench/realtime_editor.csv (K, S, frames, seconds, fps, GPU ms
# of the last frame).
# Usage: scripts/bench/realtime.sh [build-dir] [lights] [size]
# LC_BENCH_CACHE=DIR keeps the scene, tree and reference in DIR/realtime_LIGHTS/.
# On a device machine (scripts/bench/gpu.sh): LC_CLIENT=PATH uses that client
# without building, LC_BENCH_OUT=DIR writes the CSVs and plot there instead of
# docs/bench, LC_EDITOR_SIZE=WxH sizes the editor's frames, LC_KEEP=DIR keeps
# every frame's stats JSON (and the K = 16 PNGs) there, LC_PYTHON=PATH is a
# Python with numpy and matplotlib.
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
lights="${2:-16384}"
size="${3:-256x256}"
source scripts/lib/furnished_bench.sh
if [[ -z "${LC_CLIENT:-}" ]]; then build_bench_client "$build_dir"; fi
client="$LC_CLIENT"
bench_out="${LC_BENCH_OUT:-docs/bench}"
editor_size="${LC_EDITOR_SIZE:-480x300}"
mkdir -p "$bench_out"
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
    for s in 0 4 1; do
        for f in 1 4 16 64; do
            render "realtime_${k}_${s}_${f}" --mode realtime --realtime-cut "$k" --realtime-rays "$s" \
                --frames "$f" --realtime-filter off
        done
    done
    render "filtered_${k}" --mode realtime --realtime-cut "$k" --frames 1
done
echo "realtime_cut,realtime_rays,width,height,frames,seconds,fps,gpu_ms_last" > "$work/editor.csv"
for ks in 8,1 8,4 16,4 16,0; do
    k=${ks%,*} s=${ks#*,}
    line="$("$client" view "$base/scene.gltf" --tree "$base/tree.lcut" --mode realtime --realtime-cut "$k" \
        --realtime-rays "$s" --headless --size "$editor_size" --frames 30 --exposure 1 2>/dev/null |
        grep -E '^steady:|ms GPU')"
    gpu="$(echo "$line" | sed -n 's/.*, \([0-9.]*\) ms GPU.*/\1/p')"
    steady="$(echo "$line" | sed -n 's/^steady: \([0-9]*\) frames in \([0-9.]*\) s = \([0-9.]*\) fps.*/\1,\2,\3/p')"
    echo "$k,$s,${editor_size%x*},${editor_size#*x},$steady,$gpu" >> "$work/editor.csv"
done
cp "$work/editor.csv" "$bench_out/realtime_editor.csv"
cat "$bench_out/realtime_editor.csv"
if [[ -n "${LC_KEEP:-}" ]]; then
    mkdir -p "$LC_KEEP"; cp "$work"/*.json "$LC_KEEP/"
    [[ -f "$LC_KEEP/reference.json" ]] || cp "$base/reference.json" "$LC_KEEP/"
    cp "$work"/realtime_16_0_1.png "$work"/realtime_16_4_1.png "$work"/filtered_16.png "$work"/lightcuts_0.02.png "$LC_KEEP/" 2>/dev/null || true
fi
"${LC_PYTHON:-/usr/bin/python3}" scripts/bench/realtime_report.py "$work" "$base" "$lights" "$size" "$bench_out/realtime.csv" \
    "$bench_out/realtime.png"
