#!/usr/bin/env bash
# GPU reconstruction cuts (render --reconstruction BLOCK) against the GPU
# lightcut per pixel, both measured against the exact reference of the same
# run (render --sweep-error): the furnished room (table, pillars, partition,
# cabinet: boxes that cast shadows; glossy floor and cabinet) with LIGHTS
# unbounded lights of TYPE (point, as scripts/bench/speedup.sh; or mixed:
# points, spots and directional lights) through the volume (0.3 m from every
# surface, 819.2 cd in total), agglomerative tree, bound criterion, walk
# search, max cut 1000.
# Per light count, one sweep (render --sweep-error --sweep-blocks): the
# reference frame, then at each error ratio the per-pixel lightcut
# (reconstruction_block 0) and the reconstruction cuts with each block side;
# every frame after a warm-up, GPU timestamps. Writes
# docs/bench/reconstruction.csv (error_sweep.cpp's columns with the light
# count in front; shadow_rays_per_pixel and reconstruction_fallbacks per row).
# Usage: scripts/bench/reconstruction.sh [build-dir] [light counts] [size] [blocks] [ratios] [type]
# (defaults: build 16384 128x128 4,8 0.02,0.005 point; lists comma-separated).
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
counts="${2:-16384}"
size="${3:-128x128}"
blocks="${4:-4,8}"
ratios="${5:-0.02,0.005}"
type="${6:-point}"
source scripts/lib/furnished_bench.sh
build_bench_client "$build_dir"
client="$LC_CLIENT"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

out=docs/bench/reconstruction.csv
mkdir -p docs/bench
header_written=0
: >"$out.tmp"
for lights in ${counts//,/ }; do
  base="$work/$lights"
  mkdir -p "$base"
  intensity="$(python3 -c "print(819.2 / $lights)")"
  "$client" make-scene furnished-room -o "$base/empty.gltf" >/dev/null
  "$client" add-lights "$base/empty.gltf" --count "$lights" --layout random --type "$type" \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity "$intensity" --range 0 -o "$base/scene.gltf" >/dev/null
  "$client" bake "$base/scene.gltf" --spawn-server --builder agglomerative -o "$base/tree.lcut" \
    >/dev/null 2>&1
  # Validation would slow the GPU work down; the benchmark measures the renderer alone.
  LC_VALIDATION=0 "$client" render "$base/scene.gltf" --tree "$base/tree.lcut" --size "$size" \
    --criterion bound --mode lightcuts --sweep-error "$ratios" --sweep-blocks "$blocks" \
    --sweep-csv "$base/sweep.csv" -o "$base/last.png" | tee "$base/sweep.log"
  if [[ $header_written == 0 ]]; then
    echo "light_type,lights_asked,$(head -n 1 "$base/sweep.csv")" >>"$out.tmp"
    header_written=1
  fi
  tail -n +2 "$base/sweep.csv" | sed "s/^/$type,$lights,/" >>"$out.tmp"
done
mv "$out.tmp" "$out"
cat "$out"
