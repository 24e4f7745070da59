#!/usr/bin/env bash
# The real-time modes side by side (issue 38): `render --sweep-realtime` on
# three scenes, each variant against the exact reference, the still view's
# frames accumulated (1, 4, 16, 64) and each frame of a 32-frame orbit of
# the scene's camera (the history kept, a reference per frame):
#   furnished  the furnished room with LIGHTS random point lights (16,384);
#   boxes      the Cornell box's two blocks (shadows) lit by its emissive
#              panel (4,096 area-light samples) and LIGHTS / 4 mixed point
#              and spot lights in the box;
#   area       the Cornell box lit by its emissive panel alone (4,096 samples).
# Variants (LC_VARIANTS): deterministic lightcuts at E = 0.02 and stochastic
# lightcuts at K = 8, 16, 32 (a shadow ray per cut node) and at K = 8, 16 with
# a budget of one ray a pixel. A new real-time mode is one more item there.
# Writes docs/bench/rtsweep_SCENE.csv (every row), rtsweep_SCENE_equal.csv
# (each variant at the cheapest one's time and rays), docs/bench/rtsweep.md
# (a table per scene, the winner at equal time) and rtsweep_SCENE.png where
# python3 has matplotlib (scripts/install_deps.sh installs it).
# Usage: scripts/bench/realtime_modes.sh [build-dir] [lights]
# LC_SWEEP_SCENES="furnished boxes area" picks scenes (the report covers those);
# LC_SWEEP_SIZE=WxH (128x128), LC_SWEEP_PATH=N (32), LC_SWEEP_FRAMES=list
# (1,4,16,64) shrink the run (every reference costs a full exact frame: about
# 65 s at 128x128 with 16,384 lights on lavapipe); LC_BENCH_OUT=DIR writes there.
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
lights="${2:-16384}"
size="${LC_SWEEP_SIZE:-128x128}"
path_frames="${LC_SWEEP_PATH:-32}"
frames="${LC_SWEEP_FRAMES:-1,4,16,64}"
scenes="${LC_SWEEP_SCENES:-furnished boxes area}"
variants="${LC_VARIANTS:-lc0.02,K8,K16,K32,K8r1,K16r1}"
bench_out="${LC_BENCH_OUT:-docs/bench}"
source scripts/lib/furnished_bench.sh
if [[ -z "${LC_CLIENT:-}" ]]; then build_bench_client "$build_dir"; fi
client="$LC_CLIENT"
mkdir -p "$bench_out"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

make_boxes() {  # DIR: the Cornell box, its panel and LIGHTS / 4 mixed lights
    "$client" make-scene cornell-emissive -o "$1/empty.gltf" >/dev/null
    "$client" add-lights "$1/empty.gltf" --count "$((lights / 4))" --layout random --type mixed \
        --intensity "$(python3 -c "print(8.0 / $lights)")" --range 0 \
        -o "$1/scene.gltf" >/dev/null
    "$client" bake "$1/scene.gltf" --spawn-server --builder agglomerative --area-lights 4096 \
        -o "$1/tree.lcut" >/dev/null 2>&1
}
make_area() {  # DIR: the Cornell box lit by its emissive panel alone
    "$client" make-scene cornell-emissive -o "$1/scene.gltf" >/dev/null
    "$client" bake "$1/scene.gltf" --spawn-server --builder agglomerative --area-lights 4096 \
        -o "$1/tree.lcut" >/dev/null 2>&1
}

for scene in $scenes; do
    dir="$work/$scene"
    mkdir -p "$dir"
    case "$scene" in
        furnished) make_furnished_room "$dir" "$lights" ;;
        boxes) make_boxes "$dir" ;;
        area) make_area "$dir" ;;
    esac
    echo "sweeping $scene ($size, path $path_frames)" >&2
    "$client" render "$dir/scene.gltf" --tree "$dir/tree.lcut" --size "$size" --mode realtime \
        --sweep-realtime "$variants" --sweep-frames "$frames" --sweep-path "$path_frames" \
        --sweep-csv "$bench_out/rtsweep_$scene.csv" -o "$dir/last.png" > "$bench_out/rtsweep_$scene.txt"
done
python3 scripts/bench/rtsweep_report.py "$bench_out" $scenes \
    --command "scripts/bench/realtime_modes.sh $build_dir $lights (LC_SWEEP_SIZE=$size LC_SWEEP_PATH=$path_frames LC_SWEEP_FRAMES=$frames)"
