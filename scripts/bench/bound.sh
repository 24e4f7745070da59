#!/usr/bin/env bash
# Lightcuts with the paper's error-bound criterion (walk search) against the
# reference, on two room-like scenes, each lit two ways:
#   room            the empty room: nothing can hide a light, so the scene
#                   analysis turns shadows off (V = 1 everywhere);
#   furnished-room  the room with a table, two pillars, a partition, a steel
#                   cabinet and a varnished floor: shadows on (one shadow ray
#                   per light in the reference, one per cut node in lightcuts:
#                   the paper's setting, its speed-ups are counted in shadow
#                   rays) and glossy reflection on;
#   volume          unbounded point lights at random through the volume, 0.3 m
#                   from every surface (add-lights --layout random);
#   ceiling         hemispherical emitters at random over the ceiling, facing
#                   down (add-lights --layout surface --type spot): the paper's
#                   area lights sampled as point lights, spread over the ceiling.
# 819.2 cd in total whatever the count. Each scene is baked once
# (agglomerative, spawned server) and rendered with
# `render --sweep-error 0.02,0.01,0.005 --sweep-csv`: one reference frame, then
# lightcuts at each ratio, every frame timed after a warm-up (lavapipe compiles
# shaders on first use). Writes docs/bench/bound_targets.csv:
#   scene, layout, size, then the sweep's columns (editor_client/render/sweeps/error_sweep.h):
#   lights, shadows, reference_ms, error_ratio, lightcuts_ms, speedup, avg_cut,
#   cut_p99, max_cut_hits, rel_err_mean, rel_err_p99, frac_over_error,
#   frac_over_2pct, max_err, reference_shadow_rays, shadow_rays, loop_limit_stops
# The *_ms columns are the whole frame's GPU time (G-buffer, lighting, tone map)
# by timestamps. Error statistics are over pixels whose reference luminance
# exceeds 1e-3 x the mean (editor_client/render/analysis/error_stats.h).
# Usage: scripts/bench/bound.sh [build-dir] [--large]
#   --large adds 131072 lights at 128x128 (the shadowed reference takes minutes).
set -euo pipefail
cd "$(dirname "$0")/../.."
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

run_case() {  # scene layout lights size
  local scene_name=$1 layout=$2 lights=$3 size=$4
  local base="$work/${scene_name}_${layout}_${lights}"
  local intensity
  intensity="$(python3 -c "print(819.2 / $lights)")"
  "$client" make-scene "$scene_name" -o "$base.empty.gltf" >/dev/null
  if [[ "$layout" == volume ]]; then
    # The room's default light box: 0.3 m from every wall, the floor and the ceiling.
    "$client" add-lights "$base.empty.gltf" --count "$lights" --layout random --type point \
      --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity "$intensity" --range 0 -o "$base.gltf" >/dev/null
  else
    # Only the ceiling's triangles have their centroid in this slab.
    "$client" add-lights "$base.empty.gltf" --count "$lights" --layout surface --type spot \
      --box -5,2.9,-5,5,3.1,5 --intensity "$intensity" --range 0 -o "$base.gltf" >/dev/null
  fi
  "$client" bake "$base.gltf" --spawn-server --builder agglomerative -o "$base.lcut" >/dev/null
  # Validation would slow the GPU work down; the benchmark measures the renderer alone.
  LC_VALIDATION=0 "$client" render "$base.gltf" --tree "$base.lcut" --criterion bound \
    --reconstruction off --sweep-error 0.02,0.01,0.005 --sweep-csv "$base.csv" --size "$size" -o "$base.png" \
    >"$base.log" 2>&1 || { cat "$base.log"; exit 1; }
  grep -A4 '^reference' "$base.log"
  tail -n +2 "$base.csv" | sed "s/^/$scene_name,$layout,$size,/" >>"$work/rows.csv"
}

for scene in room furnished-room; do
  for layout in volume ceiling; do
    run_case "$scene" "$layout" 16384 256x256
    if [[ "$large" == "--large" ]]; then run_case "$scene" "$layout" 131072 128x128; fi
  done
done
{
  echo "scene,layout,size,lights,shadows,reference_ms,error_ratio,lightcuts_ms,speedup,avg_cut,cut_p99,max_cut_hits,rel_err_mean,rel_err_p99,frac_over_error,frac_over_2pct,max_err,reference_shadow_rays,shadow_rays,loop_limit_stops"
  cat "$work/rows.csv"
} >"$out"
cat "$out"
