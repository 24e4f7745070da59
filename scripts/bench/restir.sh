#!/usr/bin/env bash
# The ReSTIR DI mode beside the real-time mode (issue 38): the furnished room
# with LIGHTS unbounded point lights (agglomerative tree, shadow rays on), one
# run at SIZE:
#   reference            every light with its shadow ray, the exact answer;
#   realtime_K_S_F       --mode realtime --realtime-cut K --realtime-rays S, the plain
#                        mean of F still frames (--realtime-filter off);
#   restir_NAME_F        --mode restir with the variant's flags, the mean of F still frames.
# Writes docs/bench/restir_SIZE.csv: GPU ms per frame, shadow rays per lit
# pixel, relative MSE and mean relative error against the reference
# (scripts/bench/restir_report.py).
# Usage: scripts/bench/restir.sh [build-dir] [lights] [size] [frames list] [variants]
# variants: a space-separated subset of the names below (default: all).
# LC_BENCH_CACHE=DIR keeps the scene, tree and reference in DIR/restir_LIGHTS/ (the reference per size).
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
lights="${2:-16384}"
size="${3:-128x128}"
frame_counts="${4:-1 16}"
source scripts/lib/furnished_bench.sh
LC_CLIENT="${LC_CLIENT:-$build_dir/bin/editor_client}"
client="$LC_CLIENT"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
base="$work"
if [[ -n "${LC_BENCH_CACHE:-}" ]]; then base="$LC_BENCH_CACHE/restir_${lights}"; mkdir -p "$base"; fi
[[ -f "$base/tree.lcut" ]] || make_furnished_room "$base" "$lights"
render() {  # render TAG ARGS...: the frame's PFM and stats in $work
    local tag=$1; shift
    "$client" render "$base/scene.gltf" --tree "$base/tree.lcut" --size "$size" --exposure 1 \
        -o "$work/$tag.png" --float "$work/$tag.pfm" --stats "$work/$tag.json" "$@" >/dev/null
}
if [[ ! -f "$base/reference_$size.pfm" ]]; then
    render reference --mode reference
    cp "$work/reference.pfm" "$base/reference_$size.pfm"
fi
declare -A variants=(
    [realtime_16_0]="--mode realtime --realtime-cut 16 --realtime-rays 0 --realtime-filter off"
    [realtime_8_1]="--mode realtime --realtime-cut 8 --realtime-rays 1 --realtime-filter off"
    [restir_default]="--mode restir --realtime-filter off"
    [restir_power]="--mode restir --realtime-filter off --restir-source power"
    [restir_m16]="--mode restir --realtime-filter off --restir-candidates 16"
    [restir_m32]="--mode restir --realtime-filter off --restir-candidates 32"
    [restir_k0]="--mode restir --realtime-filter off --restir-spatial 0"
    [restir_k5]="--mode restir --realtime-filter off --restir-spatial 5"
    [restir_unbiased]="--mode restir --realtime-filter off --restir-bias unbiased"
    [restir_notemporal]="--mode restir --realtime-filter off --restir-temporal off"
    [restir_visibility]="--mode restir --realtime-filter off --restir-visibility on"
)
names="${5:-${!variants[*]}}"
tags=()
for name in $names; do
    for f in $frame_counts; do
        # shellcheck disable=SC2086
        render "${name}_$f" ${variants[$name]} --frames "$f"
        tags+=("${name}_$f")
    done
done
mkdir -p docs/bench
python3 scripts/bench/restir_report.py "$work" "$base/reference_$size.pfm" "docs/bench/restir_$size.csv" "${tags[@]}"
