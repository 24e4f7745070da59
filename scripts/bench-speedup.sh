#!/usr/bin/env bash
# Lightcuts against the reference at one sample per pixel, the issue's setting:
# the furnished room (table, pillars, partition, steel cabinet, varnished
# floor; shadow rays on) with unbounded point lights spread through the volume
# (0.3 m from every surface, 819.2 cd in total), agglomerative tree, bound
# criterion (walk search, max cut 1000), 256x256, 16,384 and 131,072 lights.
# For each count: one reference frame and lightcuts at E = 0.02 and 0.005
# (`render --sweep-error`, every frame after a warm-up, GPU time of the whole
# frame by timestamps), then the profile of the E = 0.02 frame: the same sweep
# with --shadows off (the walk, its bounds and the cluster shading without a
# ray; its reference is cheap), and the passes' timestamps of one frame with
# shadows (render --stats: G-buffer, lighting, tone map).
# Writes docs/bench/speedup.csv (the sweep's columns after scene, size,
# shadows_setting) and docs/bench/speedup_profile.csv, and plots
# docs/bench/speedup.png.
# Usage: scripts/bench-speedup.sh [build-dir] [light counts, comma-separated]
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"
counts="${2:-16384,131072}"
size=256x256
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build_dir" --target editor_client lightmass_server -j "$(nproc)"
client="$build_dir/bin/editor_client"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p docs/bench
echo "scene,size,shadows_setting,lights,shadows,reference_ms,error_ratio,lightcuts_ms,speedup,avg_cut,cut_p99,max_cut_hits,rel_err_mean,rel_err_p99,frac_over_error,frac_over_2pct,max_err,reference_shadow_rays,shadow_rays,loop_limit_stops" >"$work/speedup.csv"
echo "lights,gbuffer_ms,lighting_ms,output_ms,render_ms,avg_cut,shadow_rays" >"$work/profile.csv"

for lights in ${counts//,/ }; do
  base="$work/furnished_$lights"
  intensity="$(python3 -c "print(819.2 / $lights)")"
  "$client" make-scene furnished-room -o "$base.empty.gltf" >/dev/null
  "$client" add-lights "$base.empty.gltf" --count "$lights" --layout random --type point \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity "$intensity" --range 0 -o "$base.gltf" >/dev/null
  "$client" bake "$base.gltf" --spawn-server --builder agglomerative -o "$base.lcut" >/dev/null
  for shadows in auto off; do
    # Validation would slow the GPU work down; the benchmark measures the renderer alone.
    LC_VALIDATION=0 "$client" render "$base.gltf" --tree "$base.lcut" --criterion bound \
      --shadows "$shadows" --sweep-error 0.02,0.005 --sweep-csv "$base.$shadows.csv" \
      --size "$size" -o "$base.png" >"$base.$shadows.log" 2>&1 || { cat "$base.$shadows.log"; exit 1; }
    grep -A3 '^reference' "$base.$shadows.log"
    tail -n +2 "$base.$shadows.csv" | sed "s/^/furnished-room,$size,$shadows,/" >>"$work/speedup.csv"
  done
  LC_VALIDATION=0 "$client" render "$base.gltf" --tree "$base.lcut" --criterion bound --error 0.02 \
    --size "$size" -o "$base.png" --stats "$base.json" >/dev/null 2>&1
  /usr/bin/python3 -c "
import json; s = json.load(open('$base.json'))
print('$lights,%.1f,%.1f,%.1f,%.1f,%.1f,%d' % (s['gbuffer_ms'], s['lighting_ms'], s['output_ms'],
      s['render_ms'], s['avg_cut'], s['shadow_rays']))" >>"$work/profile.csv"
done
cp "$work/speedup.csv" docs/bench/speedup.csv
cp "$work/profile.csv" docs/bench/speedup_profile.csv
/usr/bin/python3 - <<'PLOT'
import csv
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
rows = [r for r in csv.DictReader(open("docs/bench/speedup.csv")) if r["shadows_setting"] == "auto"]
fig, axes = plt.subplots(1, 2, figsize=(9, 3.2))
labels = [f"{int(r['lights']):,}\nE={float(r['error_ratio']):g}" for r in rows]
axes[0].bar(labels, [float(r["speedup"]) for r in rows], color="#4878a8")
axes[0].set_ylabel("speed-up over the reference")
axes[1].bar(labels, [100 * (1 - float(r["frac_over_2pct"])) for r in rows], color="#58a848")
axes[1].set_ylabel("% lit pixels within 2%")
axes[1].set_ylim(50, 100)
fig.suptitle("furnished room, volume lights, 256x256, 1 spp (lavapipe, 2 cores)")
fig.tight_layout()
fig.savefig("docs/bench/speedup.png", dpi=110)
PLOT
cat docs/bench/speedup.csv docs/bench/speedup_profile.csv
