#!/usr/bin/env bash
# What indirect light costs at render time (issue 16): the emissive Cornell box
# (make-scene cornell-emissive, 4,096 area-light samples of its panel) baked by a
# local lightmass_server with VPL indirect (10^3..10^6 light paths, 64 bounces at
# most) and with progressive radiosity (patch sizes 0.5, 0.25, 0.125, tolerance
# 1e-3), each tree rendered at 128x128 with lightcuts at E = 0.02 (shadow rays on)
# and with the exact reference of the same tree on every 4th 8x8 tile
# (--tile-stride 4; for 10^6 paths one 8x8 tile, --tile-stride 16), so the
# error columns are the lightcut's own error against the exact sum of the same
# lights (the solvers' error against a path-traced reference is
# bench/indirect.csv's). The reference clamps its VPLs exactly, over Newton's
# passes (reference.comp); a third render, the same reference with --indirect
# off, counts the pixels no direct light reaches. Writes
# docs/bench/indirect_render.csv:
#   method, parameter, tree_lights, indirect_lights, bake_wall_s, lightcuts_gpu_ms,
#   lightcuts_wall_s, avg_cut, clamped_energy_fraction, reference_clamped_energy_fraction,
#   reference_gpu_ms_full
#   (the strided reference's time scaled to the full frame), reference_clamp_passes,
#   reference_clamp_change (the largest relative change of a threshold in the last pass),
#   reference_pixels, reference_zero_pixels, direct_zero_pixels (of the strided
#   reference's pixels: black with indirect light, black without), speed_up,
#   rel_err_mean, within_2pct, max_err
# Usage: scripts/bench/indirect_render.sh [build-dir]   (default: build)
# INDIRECT_BENCH_KEEP=DIR keeps the scene, trees and images in DIR.
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
bin="$build_dir/bin"
[[ -x "$bin/editor_client" && -x "$bin/lightmass_server" ]] ||
  cmake --build "$build_dir" --target editor_client lightmass_server -j "$(nproc)"
out=docs/bench/indirect_render.csv
work="${INDIRECT_BENCH_KEEP:-$(mktemp -d)}"
mkdir -p "$work"
server_pid=""
cleanup() {
  [[ -n "$server_pid" ]] && kill "$server_pid" 2>/dev/null && wait "$server_pid" 2>/dev/null
  [[ -n "${INDIRECT_BENCH_KEEP:-}" ]] || rm -rf "$work"
}
trap cleanup EXIT

"$bin/lightmass_server" --listen 127.0.0.1:0 --port-file "$work/port" >"$work/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 100); do
  [[ -s "$work/port" ]] && break
  sleep 0.1
done
port=$(cat "$work/port")
"$bin/editor_client" make-scene cornell-emissive -o "$work/cornell.gltf" >/dev/null

rows="$work/rows.txt"
: >"$rows"
row() {  # method parameter, then bake flags
  local method=$1 parameter=$2 tag="$1_$2"
  shift 2
  local start end
  start=$(date +%s.%N)
  "$bin/editor_client" bake "$work/cornell.gltf" --server "127.0.0.1:$port" --builder agglomerative \
    --area-lights 4096 "$@" -o "$work/$tag.lcut" >"$work/$tag.bake.log" 2>&1 ||
    { cat "$work/$tag.bake.log"; exit 1; }
  end=$(date +%s.%N)
  # The exact reference costs every light with its shadow ray per pixel (1.7e9 rays
  # at 10^6 paths on every 4th tile: about 40 minutes on lavapipe); for a tree
  # of over 200 MB (10^6 paths) it takes one tile in 16x16 (64 pixels of the frame).
  local stride=4
  [[ "$(stat -c %s "$work/$tag.lcut")" -gt 200000000 ]] && stride=16
  # Validation would slow the GPU work down; the benchmark measures the renderer.
  for mode in lightcuts reference direct; do
    local flags=(--mode lightcuts --error 0.02)
    [[ $mode == reference ]] && flags=(--mode reference --tile-stride "$stride")
    [[ $mode == direct ]] && flags=(--mode reference --tile-stride "$stride" --indirect off)
    LC_VALIDATION=0 "$bin/editor_client" render "$work/cornell.gltf" --tree "$work/$tag.lcut" \
      --size 128x128 "${flags[@]}" --stats "$work/$tag.$mode.json" --float "$work/$tag.$mode.pfm" \
      -o "$work/$tag.$mode.png" >"$work/$tag.$mode.log" 2>&1 || { cat "$work/$tag.$mode.log"; exit 1; }
  done
  echo "$method $parameter $(echo "$end - $start" | bc) $work/$tag" >>"$rows"
  echo "$tag done" >&2
}
for paths in 1000 10000 100000 1000000; do
  row vpl "$paths" --indirect vpl --vpl-count "$paths" --bounces 64
done
for size in 0.5 0.25 0.125; do
  row radiosity "$size" --indirect radiosity --patch-size "$size" --tolerance 1e-3
done

mkdir -p docs/bench
/usr/bin/python3 - "$rows" "$out" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(os.getcwd(), "scripts"))
from bench_images import error_columns, read_pfm, write_rows

rows = []
for line in open(sys.argv[1]):
    method, parameter, bake_s, base = line.split()
    lc = json.load(open(base + ".lightcuts.json"))
    ref = json.load(open(base + ".reference.json"))
    stride, tile = ref["pixel_stride"], ref["stride_tile"]
    scale = (lc["width"] * lc["height"]) / (ref["width"] * ref["height"])
    reference_ms = ref["render_ms"] * scale
    reference = read_pfm(base + ".reference.pfm")
    errors = error_columns(base + ".lightcuts.pfm", reference, ref["geometry_pixels"], stride, tile)
    black = lambda image: int((image[:, :, :3].max(axis=2) == 0.0).sum())
    rows.append({
        "method": method, "parameter": parameter, "tree_lights": lc["tree_lights"],
        "indirect_lights": lc["indirect_lights"], "bake_wall_s": round(float(bake_s), 2),
        "lightcuts_gpu_ms": round(lc["render_ms"], 1), "lightcuts_wall_s": round(lc["wall_ms"] / 1000, 2),
        "avg_cut": round(lc["avg_cut"], 1),
        "clamped_energy_fraction": round(lc["clamped_energy_fraction"], 5),
        "reference_clamped_energy_fraction": round(ref["clamped_energy_fraction"], 5),
        "reference_gpu_ms_full": round(reference_ms, 1),
        "reference_clamp_passes": ref.get("reference_clamp_passes", 0),
        "reference_clamp_change": round(ref.get("reference_clamp_change", 0.0), 6),
        "reference_pixels": ref["geometry_pixels"], "reference_zero_pixels": black(reference),
        "direct_zero_pixels": black(read_pfm(base + ".direct.pfm")),
        "speed_up": round(reference_ms / max(lc["render_ms"], 1e-9), 1),
        "rel_err_mean": errors["rel_err_mean"], "within_2pct": errors["within_2pct"],
        "max_err": errors["max_err"],
    })
write_rows(sys.argv[2], list(rows[0].keys()), rows)
print(open(sys.argv[2]).read())
PY
