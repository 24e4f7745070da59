#!/usr/bin/env bash
# A million triangles (issue 28): the client's shadow BVH build, its bytes
# per triangle and the CPU time per shadow ray (tests/benchmarks/
# heavy_mesh_bench, one case per process), then the furnished room with and
# without a 10^6-triangle sphere (make-scene heavy-room), 4,096 random point
# lights each: a bake with VPL bounces (the .geom upload and the server's
# Embree build are in it) and a 128x128 lightcuts render, its lighting time
# per shadow ray. Writes docs/bench/heavy_mesh_cpu.csv and
# docs/bench/heavy_mesh_scene.csv.
# Usage: scripts/bench/heavy_mesh.sh [build-dir]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
cmake --build "$build_dir" --target heavy_mesh_bench lightmass_server editor_client -j "$(nproc)"
bin="$build_dir/bin"
mkdir -p docs/bench
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

for name in $("$bin/heavy_mesh_bench" --benchmark_list_tests); do
  echo "running $name" >&2
  "$bin/heavy_mesh_bench" --benchmark_filter="^${name}\$" --benchmark_format=json \
    --benchmark_min_time=0.3 > "$tmp/$(echo "$name" | tr '/:' '__').json"
done
python3 - "$tmp" docs/bench/heavy_mesh_cpu.csv <<'PY'
import csv, glob, json, sys
rows = []
for path in sorted(glob.glob(sys.argv[1] + "/*.json")):
    for b in json.load(open(path))["benchmarks"]:
        name = b["name"].split("/")[0]
        ms = b["real_time"] if b["time_unit"] == "ms" else float("nan")
        rows.append([name, int(b["triangles"]), "%.1f" % ms,
                     "%.1f" % b.get("bytes_per_triangle", float("nan")),
                     "%.1f" % (b.get("seconds_per_ray", float("nan")) * 1e9)])
rows.sort(key=lambda r: (r[0], r[1]))
with open(sys.argv[2], "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["case", "triangles", "wall_ms_per_iteration", "bvh_bytes_per_triangle", "ns_per_ray"])
    w.writerows(rows)
print("wrote", sys.argv[2])
PY

echo "scene,shadow_triangles,bake_wall_s,upload_ms,render_lighting_ms,shadow_rays,us_per_shadow_ray,client_peak_rss_mb" \
  > docs/bench/heavy_mesh_scene.csv
for scene in furnished-room heavy-room; do
  "$bin/editor_client" make-scene "$scene" -o "$tmp/$scene.glb" > /dev/null
  "$bin/editor_client" add-lights "$tmp/$scene.glb" --count 4096 --layout random --seed 1 \
    -o "$tmp/${scene}_lit.glb" > /dev/null
  start=$(date +%s.%N)
  "$bin/editor_client" bake "$tmp/${scene}_lit.glb" --spawn-server --indirect vpl --vpl-count 10000 \
    -o "$tmp/$scene.lcut" > "$tmp/$scene.bake.log" 2>&1
  end=$(date +%s.%N)
  /usr/bin/time -f "%M" -o "$tmp/$scene.rss" "$bin/editor_client" render "$tmp/${scene}_lit.glb" \
    --tree "$tmp/$scene.lcut" --mode lightcuts --size 128x128 --stats "$tmp/$scene.json" \
    -o "$tmp/$scene.png" > /dev/null 2>&1
  python3 - "$scene" "$tmp" "$start" "$end" >> docs/bench/heavy_mesh_scene.csv <<'PY'
import json, re, sys
scene, tmp, start, end = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
stats = json.load(open("%s/%s.json" % (tmp, scene)))
upload = re.search(r"upload ([0-9.]+) ms", open("%s/%s.bake.log" % (tmp, scene)).read())
rss = int(open("%s/%s.rss" % (tmp, scene)).read().split()[-1]) / 1024.0
rays = stats["shadow_rays"]
print("%s,%d,%.2f,%s,%.1f,%d,%.3f,%.0f" % (scene, stats["shadow_triangles"], end - start,
      upload.group(1) if upload else "", stats["lighting_ms"], rays,
      1e3 * stats["lighting_ms"] / max(rays, 1), rss))
PY
done
cat docs/bench/heavy_mesh_scene.csv
