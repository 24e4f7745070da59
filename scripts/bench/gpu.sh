#!/usr/bin/env bash
# Everything issue #29 measures on a lent GPU, as one prepared run (device time
# is short): build and pack here (../shared/tools/gpu-bundle.sh, then
# scripts/tools/gpu_pack_validation.sh for the validation layer), then on the device machine
#   bash .gpu/enter.sh bash scripts/bench/gpu.sh "$OUT"      (carry [".gpu"])
# 1. scripts/tools/gpu_check.sh: every mode, criterion, bound search and
#    representative choice starts, GPU against CPU on small frames, per-pass
#    timestamps (4,096 lights, 64x64);
# 2. the heap search at several max cuts (which capacities the driver compiles);
# 3. scripts/bench/realtime.sh at LIGHTS (131,072) and SIZE (1920x1080): the
#    reference, lightcuts E = 0.02, the real-time mode at K = 8/16/32 over
#    1-64 frames, the editor at SIZE; then the same frames without shadow rays
#    (what the walk and the light draws cost) and the deterministic editor;
# 3b. the G-buffer rasterised and cast as rays (--primary) at three sizes;
# 4. BIG_LIGHTS (1,048,576): bake time, the real-time frame at K = 8 and 16, the
#    deterministic E = 0.02 frame and the real-time editor (no reference: it
#    would take minutes).
# Writes OUT/gpu_bench.tar.gz (CSVs, stats JSONs, logs, a few PNGs) and prints
# the CSVs. Each stage has its own time limit, so a slow stage costs only itself,
# and all of them end within GPU_BENCH_SECONDS (540).
# GPU_BENCH_LIGHTS, GPU_BENCH_BIG_LIGHTS and GPU_BENCH_SIZE shrink it for a
# rehearsal on lavapipe.
set -uo pipefail
cd "$(dirname "$0")/../.."
out_root="${1:?usage: bench/gpu.sh OUT_DIR}"
lights="${GPU_BENCH_LIGHTS:-131072}"
big_lights="${GPU_BENCH_BIG_LIGHTS:-1048576}"
size="${GPU_BENCH_SIZE:-1920x1080}"
bin="$PWD/build/bin"
out="$(mktemp -d)/gpu_bench"
mkdir -p "$out"
export LC_CLIENT="$bin/editor_client" LC_SERVER_BIN="${LC_SERVER_BIN:-$bin/lightmass_server}"
export LC_PYTHON="${LC_PYTHON:-$(command -v python3)}"
client="$LC_CLIENT"
cache="$(mktemp -d)"
source scripts/lib/furnished_bench.sh
deadline=$((SECONDS + ${GPU_BENCH_SECONDS:-540}))  # the whole run's, within the device call's limit
stage() {  # stage NAME SECONDS COMMAND...: runs it under a limit, logs it, says how it ended
    local name=$1 limit=$2; shift 2
    local start=$SECONDS
    (( limit > deadline - SECONDS )) && limit=$((deadline - SECONDS))
    if (( limit < 10 )); then echo "stage $name: skipped (out of time)" | tee -a "$out/stages.txt"; return; fi
    # A function runs in a child bash (timeout cannot run one itself).
    if declare -F "$1" >/dev/null; then
        timeout "$limit" bash -c "$(declare -f); $(declare -p client cache out lights big_lights size); $*" \
            > "$out/$name.log" 2>&1
    else
        timeout "$limit" "$@" > "$out/$name.log" 2>&1
    fi
    local rc=$?
    echo "stage $name: exit $rc after $((SECONDS - start)) s" | tee -a "$out/stages.txt"
}
frame() {  # frame DIR TAG ARGS...: one render of DIR's scene at SIZE, stats in OUT/frames
    local dir=$1 tag=$2; shift 2
    mkdir -p "$out/frames"
    "$client" render "$dir/scene.gltf" --tree "$dir/tree.lcut" --size "$size" -o "$cache/$tag.png" \
        --stats "$out/frames/$tag.json" "$@"
}
editor() {  # editor DIR TAG ARGS...: 30 whole frames of the headless editor at SIZE
    local dir=$1 tag=$2; shift 2
    "$client" view "$dir/scene.gltf" --tree "$dir/tree.lcut" --headless --no-adaptive --size "$size" --frames 30 \
        --exposure 1 "$@" > "$out/editor_$tag.txt" 2>&1
}
heap_probe() {  # which heap capacities (max cut) the driver compiles and runs
    local m
    for m in 16 64 256 1000 4096; do
        if "$client" render "$cache/realtime_$lights/scene.gltf" --tree "$cache/realtime_$lights/tree.lcut" \
            --size 32x32 --bound-search heap --max-cut "$m" -o "$cache/heap.png" > "$cache/heap.log" 2>&1; then
            echo "max_cut $m: ok"
        else
            echo "max_cut $m: failed: $(grep -m1 -i 'error\|fail' "$cache/heap.log")"
        fi
    done
}
small_scene() {  # the real-time bench's scene at LIGHTS, kept for the later stages
    mkdir -p "$cache/realtime_$lights" && make_furnished_room "$cache/realtime_$lights" "$lights"
}
big_scene() {
    mkdir -p "$cache/big" && make_furnished_room "$cache/big" "$big_lights"
}
splits() {  # the same frames without shadow rays, and the deterministic editor
    local dir="$cache/realtime_$lights"
    frame "$dir" lightcuts_0.02_noshadow --mode lightcuts --error 0.02 --shadows off
    frame "$dir" realtime_16_noshadow --mode realtime --realtime-cut 16 --frames 8 --shadows off
    # The shadow-ray budget (--realtime-rays; 0, a ray per node, by default): per node, and one ray.
    frame "$dir" realtime_16_pernode --mode realtime --realtime-cut 16 --realtime-rays 0 --frames 8
    frame "$dir" realtime_16_oneray --mode realtime --realtime-cut 16 --realtime-rays 1 --frames 8
    frame "$dir" lightcuts_0.02_shared --mode lightcuts --error 0.02 --share-cuts
    editor "$dir" lightcuts --mode lightcuts --no-progressive
}
gbuffer_scaling() {  # the raster G-buffer's time against the pixels, and primary rays beside it
    local dir="$cache/realtime_$lights" s
    for s in 1920x1080 960x540 480x270; do
        size=$s frame "$dir" "gbuffer_raster_$s" --mode realtime --realtime-cut 8 --frames 8 --primary raster
        size=$s frame "$dir" "gbuffer_rays_$s" --mode realtime --realtime-cut 8 --frames 8 --primary rays
    done
    frame "$dir" lightcuts_0.02_rays --mode lightcuts --error 0.02 --primary rays
    frame "$dir" realtime_16_raster --mode realtime --realtime-cut 16 --frames 8 --primary raster
}
big() {
    local dir="$cache/big"
    frame "$dir" big_realtime_16 --mode realtime --realtime-cut 16 --frames 8
    frame "$dir" big_realtime_8 --mode realtime --realtime-cut 8 --frames 8
    frame "$dir" big_realtime_16_noshadow --mode realtime --realtime-cut 16 --frames 8 --shadows off
    frame "$dir" big_lightcuts_0.02 --mode lightcuts --error 0.02
    editor "$dir" big_realtime --mode realtime --realtime-cut 16
}

{ nvidia-smi -L 2>&1; nproc; } > "$out/machine.txt"
# The validation layer, when scripts/tools/gpu_pack_validation.sh packed it: the
# check's --validation runs then validate on this driver (the timed stages
# after it run without --validation, so the layer costs them nothing).
if [[ -f .gpu/validation.tar.xz ]]; then
    layers="$(mktemp -d)"
    tar -xJf .gpu/validation.tar.xz -C "$layers" && export VK_LAYER_PATH="$layers"
    echo "validation layer: $VK_LAYER_PATH" >> "$out/machine.txt"
else
    echo "validation layer: not packed (scripts/tools/gpu_pack_validation.sh)" >> "$out/machine.txt"
fi
stage check 150 bash scripts/tools/gpu_check.sh "$bin" "$out/check" 4096 64x64
rm -f "$out"/check/*.pfm
stage scene 60 small_scene
stage heap 45 heap_probe
LC_BENCH_CACHE="$cache" LC_BENCH_OUT="$out/realtime" LC_EDITOR_SIZE="$size" LC_KEEP="$out/realtime_frames" \
    stage realtime 240 bash scripts/bench/realtime.sh build "$lights" "$size"
stage splits 90 splits
stage gbuffer 60 gbuffer_scaling
stage big_scene 120 big_scene
stage big 150 big

summary() {  # one CSV of every frame's stats JSON: the figures the closing note quotes
    "$LC_PYTHON" - "$out" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
keys = ["device", "mode", "primary", "render_ms", "gbuffer_ms", "lighting_ms", "output_ms", "wall_ms", "avg_cut",
        "shadow_rays", "geometry_pixels", "realtime_cut", "realtime_frames", "loop_limit_stops",
        "nonfinite_pixels"]
rows = []
for path in sorted(glob.glob(os.path.join(out, "frames", "*.json")) +
                   glob.glob(os.path.join(out, "realtime_frames", "*.json"))):
    s = json.load(open(path))
    rows.append([os.path.basename(path)[:-5]] + [str(s.get(k, "")).replace(",", " ") for k in keys])
with open(os.path.join(out, "frames.csv"), "w") as f:
    f.write(",".join(["tag"] + keys) + "\n")
    for r in rows:
        f.write(",".join(r) + "\n")
PY
}
summary
cp "$cache"/big_realtime_16.png "$cache"/lightcuts_0.02_noshadow.png "$out/" 2>/dev/null || true
for f in "$out"/stages.txt "$out"/check/gpu_check.csv "$out"/heap.log "$out"/realtime/*.csv "$out"/frames.csv \
    "$out"/editor_*.txt; do
    [[ -f "$f" ]] && { echo "== $f"; cat "$f"; }
done
mkdir -p "$out_root"
tar -C "$(dirname "$out")" -czf "$out_root/gpu_bench.tar.gz" gpu_bench
