#!/usr/bin/env bash
# The README's main job: install, build, start a local bake server, make two scenes, bake them,
# render them, print what lightcuts saves against the exact reference, write images and stats
# into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh default lightmass_server editor_client

bin=build/bin
out=out
mkdir -p "$out"

# A bake server on loopback, as a separate process; its port lands in a file.
rm -f "$out/server.port"
# Open MPI refuses root without these, and more ranks than cores without --oversubscribe
# (a bake over MPI ranks, below); in containers its shared memory may need TCP instead.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$bin/lightmass_server" --listen 127.0.0.1:0 --port-file "$out/server.port" --threads 2 \
    --mpi-arg=--oversubscribe --mpi-arg=--mca --mpi-arg=btl --mpi-arg=self,tcp \
    > "$out/server.log" 2>&1 &
server_pid=$!
trap 'kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true' EXIT
for _ in $(seq 1 100); do [ -s "$out/server.port" ] && break; sleep 0.1; done
[ -s "$out/server.port" ] || { echo "demo: the server did not start (see $out/server.log)"; exit 1; }
server="127.0.0.1:$(cat "$out/server.port")"
echo "demo: bake server at $server"

# First, where lightcuts pays: the furnished room (a table, two pillars, a partition, a steel
# cabinet, a varnished floor) with 16,384 unbounded point lights. The scene analysis turns shadows
# and glossy reflection on (the furniture can hide lights): the reference traces a shadow ray per
# light and pixel, lightcuts one per cut node.
"$bin/editor_client" make-scene furnished-room -o "$out/furnished_empty.gltf"
"$bin/editor_client" add-lights "$out/furnished_empty.gltf" --count 16384 --layout random --type point \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity 0.05 --range 0 --seed 9 -o "$out/furnished.gltf"
"$bin/editor_client" bake "$out/furnished.gltf" --server "$server" --builder agglomerative \
    -o "$out/furnished.lcut" > /dev/null
# The comparison at 128x128 (the reference's 16,384 shadow rays per pixel take minutes at 256x256),
# at two error ratios against one reference: GPU times of the same frame, and the error of each
# lit pixel against the exact sum. Lightcuts shares one cut among each 4x2 block of pixels
# (--share-cuts: coherent shadow rays) and lets a cut grow to 2,500 nodes (at E = 0.005 the pixels
# stopped at 1,000 were the ones over 2%).
"$bin/editor_client" render "$out/furnished.gltf" --tree "$out/furnished.lcut" --size 128x128 \
    --share-cuts --max-cut 2500 --sweep-error 0.02,0.005 --sweep-csv "$out/furnished_sweep.csv" \
    -o "$out/furnished_sweep.png" > "$out/furnished_sweep.txt"
# E = 0.005 again with each cluster's leaf drawn per pixel in proportion to intensity x a bound of
# its geometry (--representatives importance): fewer pixels over 2% for more time.
"$bin/editor_client" render "$out/furnished.gltf" --tree "$out/furnished.lcut" --size 128x128 \
    --share-cuts --max-cut 2500 --representatives importance --sweep-error 0.005 \
    --sweep-csv "$out/furnished_sweep_importance.csv" -o "$out/furnished_sweep_importance.png" \
    > "$out/furnished_sweep_importance.txt"
# Reconstruction cuts on the GPU (--reconstruction 4): full lightcuts only at the corners of 4x4
# pixel blocks; the pixels between follow their corners' cuts and trace a shadow ray only where the
# corners disagree about a cluster's visibility. Beside a lightcut per pixel, against the reference.
"$bin/editor_client" render "$out/furnished.gltf" --tree "$out/furnished.lcut" --size 128x128 \
    --sweep-error 0.02 --sweep-blocks 4 --sweep-csv "$out/furnished_reconstruction.csv" \
    -o "$out/furnished_reconstruction.png" > "$out/furnished_reconstruction.txt"
# The default lightcuts frame at 256x256: reconstruction cuts in 4x4 blocks (--reconstruction auto).
"$bin/editor_client" render "$out/furnished.gltf" --tree "$out/furnished.lcut" --mode lightcuts \
    --size 256x256 -o "$out/furnished_lightcuts.png" --stats "$out/furnished_lightcuts.json"
# The speed-up and the error side by side.
python3 - "$out/furnished_sweep.csv" "$out/furnished_sweep_importance.csv" "$out/furnished_reconstruction.csv" <<'PY'
import csv, sys
for path, how in ((sys.argv[1], "shared cuts"), (sys.argv[2], "shared cuts, importance representatives"),
                  (sys.argv[3], "")):
    for r in csv.DictReader(open(path)):
        lightcuts, reference = float(r["lightcuts_ms"]) / 1000.0, float(r["reference_ms"]) / 1000.0
        block = int(r.get("reconstruction_block") or 0)
        label = how or ("reconstruction cuts, 4x4 blocks" if block else "a cut per pixel")
        print("demo: furnished room, %s lights, shadows, 128x128, E = %s: lightcuts (%s) %.2f s vs reference %.1f s: "
              "%.1fx faster, %.0f shadow rays a pixel, %.1f%% of lit pixels within 2%%, mean error %.2f%%"
              % (r["lights"], r["error_ratio"], label, lightcuts, reference, float(r["speedup"]),
                 float(r.get("shadow_rays_per_pixel") or 0), 100.0 * (1.0 - float(r["frac_over_2pct"])),
                 100.0 * float(r["rel_err_mean"])))
PY

# The real-time mode on the same room and view: stochastic lightcuts, one cut per 8x8 block of at
# most K nodes, one light drawn in each node per pixel and its shadow ray: at most K shadow rays per
# pixel whatever the number of lights; unbiased, so it trades lightcuts' bias for noise that the
# frames of a still view average away (each draw's uniform steps along a Weyl sequence from frame
# to frame, so they spread evenly). What its accuracy costs in time (--sweep-realtime): K = 8, 16 and 32,
# each measured after 1, 4, 16 and 64 frames against one exact reference; the image is K = 16's
# mean of 64 frames.
"$bin/editor_client" render "$out/furnished.gltf" --tree "$out/furnished.lcut" --size 128x128 \
    --mode realtime --sweep-realtime 8,16,32 --sweep-frames 1,4,16,64 --sweep-path 0 --frames 64 \
    --sweep-csv "$out/furnished_realtime_sweep.csv" -o "$out/furnished_realtime_64.png" \
    > "$out/furnished_realtime_sweep.txt"
python3 - "$out/furnished_realtime_sweep.csv" <<'PY'
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    if r["camera"] != "still" or r["frames"] not in ("1", "64"):
        continue
    frame_ms, reference = float(r["frame_ms"]), float(r["reference_ms"])
    print("demo: furnished room, %s lights, shadows, 128x128, real-time mode (K = %s, %.1f shadow rays a pixel): "
          "%.1f ms a frame vs reference %.1f s (%.0fx), %s: %.1f%% of lit pixels within 2%%, mean error %.2f%%"
          % (r["lights"], r["realtime_cut"], float(r["shadow_rays_per_pixel"]), frame_ms, reference / 1000.0,
             reference / frame_ms,
             "one frame" if r["frames"] == "1" else "mean of 64 frames (%.2f s)" % (float(r["total_ms"]) / 1000.0),
             100.0 * (1.0 - float(r["frac_over_2pct"])), 100.0 * float(r["rel_err_mean"])))
PY

# The real-time modes side by side (scripts/bench/realtime_modes.sh runs the full table on three
# scenes): deterministic lightcuts at E = 0.02 and stochastic lightcuts at K = 8 and 16 and at K = 8
# with one shadow ray a pixel, still (1, 4, 16 frames) and along an 8-frame orbit of the camera, each
# frame against its own reference; small (32x32) so that its 9 references take about a minute on lavapipe.
"$bin/editor_client" render "$out/furnished.gltf" --tree "$out/furnished.lcut" --size 32x32 \
    --mode realtime --sweep-realtime lc0.02,K8,K16,K8r1 --sweep-frames 1,4,16 --sweep-path 8 \
    --sweep-csv "$out/furnished_side_by_side.csv" -o "$out/furnished_side_by_side.png" \
    > "$out/furnished_side_by_side.txt"
python3 - "$out/furnished_side_by_side_equal.csv" <<'PY'
import csv, sys
def at_equal_time(text):  # n/a: the variant's first frames alone cost more than the baseline's all
    return "n/a (its first frame alone costs more)" if text in ("", "nan") else "%.3g" % float(text)
for r in csv.DictReader(open(sys.argv[1])):
    print("demo: side by side, furnished room 32x32, %s: %.1f ms a frame, still rel MSE at %s's time %s, "
          "moving rel MSE %.3g a frame" % (r["variant"], float(r["frame_ms"]), r["baseline"],
                                          at_equal_time(r["equal_time_rel_mse"]), float(r["path_rel_mse"])))
PY

# Then the empty room (10 x 3 x 10 m) with 768 point and 256 spot lights of limited range, made by
# the project itself so the job needs nothing outside the repository, in every mode: no surface can
# hide a light here, so the scene analysis proves shadows unnecessary and skips them.
"$bin/editor_client" add-lights --count 768 --layout random --type point --intensity 0.4 --range 2.5 \
    --seed 7 -o "$out/room_points.gltf"
"$bin/editor_client" add-lights "$out/room_points.gltf" --count 256 --layout random --type spot \
    --intensity 1.5 --range 3.5 --seed 8 -o "$out/room.gltf"

"$bin/editor_client" bake "$out/room.gltf" --server "$server" --builder optimal-pair -o "$out/room.lcut" \
    --json > "$out/bake.json"
cat "$out/bake.json"

for mode in reference lightcuts cuts cutsize; do
  "$bin/editor_client" render "$out/room.gltf" --tree "$out/room.lcut" --mode "$mode" --size 512x512 \
      -o "$out/room_$mode.png" --float "$out/room_$mode.pfm" --stats "$out/room_$mode.json"
done

# Open air under a Preetham sun and sky, named in the glTF itself (asset.extras.lightcuts_sky:
# 30 degrees up, azimuth 40, turbidity 3; --sky ELEVATION,AZIMUTH,TURBIDITY would override it): the
# server samples the sun's disc and the sky into 3,000 directional lights of the tree (the census
# says so in the bake's progress, the log and the stats); the ground and the boxes cast the sun's
# shadows, and the sky is the background above the horizon.
/usr/bin/python3 scripts/tools/make_sky_scene.py "$out/yard.gltf"
"$bin/editor_client" bake "$out/yard.gltf" --server "$server" -o "$out/yard.lcut" > /dev/null
"$bin/editor_client" render "$out/yard.gltf" --tree "$out/yard.lcut" --size 256x256 \
    --camera 12,2.5,12,0,2,0,55 -o "$out/yard_sky.png" --stats "$out/yard_sky.json"
python3 - "$out/yard_sky.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
for d in s["effects_simulated"] + s["effects_skipped"]:
    print("yard effect: %s: %s" % (d["name"], ("simulated, " if d in s["effects_simulated"] else "skipped, ") + d["reason"]))
PY

python3 - "$out/room_reference.json" "$out/furnished_lightcuts.json" <<'PY'
import json, sys
for path in sys.argv[1:]:
    s = json.load(open(path))
    for d in s["effects_simulated"] + s["effects_skipped"]:
        for effect in ("shadows", "glossy"):
            if d["name"].startswith(effect):
                on = d in s["effects_simulated"]
                print("demo: %s: %s %s (%s)" % (path, effect, "on" if on else "off", d["reason"]))
PY
# The Cornell box lit only by an emissive ceiling panel (no punctual light at all): the client
# sends the scene's geometry, the server samples the panel into 4,096 oriented lights (area
# lights) and builds their tree; the panel itself still renders as emission.
"$bin/editor_client" make-scene cornell-emissive -o "$out/cornell.gltf"
"$bin/editor_client" bake "$out/cornell.gltf" --server "$server" --builder agglomerative \
    --area-lights 4096 -o "$out/cornell.lcut" --json > "$out/cornell_bake.json"
"$bin/editor_client" render "$out/cornell.gltf" --tree "$out/cornell.lcut" --mode lightcuts \
    --size 256x256 -o "$out/cornell_lightcuts.png" --stats "$out/cornell_lightcuts.json"
python3 - "$out/cornell_bake.json" "$out/cornell_lightcuts.json" <<'PY'
import json, sys
bake, render = (json.load(open(p)) for p in sys.argv[1:])
print("demo: cornell-emissive bake: " + "; ".join(bake["effects"]))
print("demo: cornell-emissive effects report:")
for d in render["effects_simulated"]:
    print("  simulated: %s (%s)" % (d["name"], d["reason"]))
for d in render["effects_skipped"]:
    print("  skipped:   %s (%s)" % (d["name"], d["reason"]))
PY

# Indirect light on the same box (issue 16): direct light only, then VPL (instant radiosity) and
# progressive radiosity bounces added to the tree as oriented lights, side by side in one PNG.
for indirect in vpl radiosity; do
  "$bin/editor_client" bake "$out/cornell.gltf" --server "$server" --builder agglomerative \
      --area-lights 4096 --indirect "$indirect" --bounces 4 --vpl-count 20000 --patch-size 0.3 \
      -o "$out/cornell_$indirect.lcut" --json > "$out/cornell_${indirect}_bake.json"
  "$bin/editor_client" render "$out/cornell.gltf" --tree "$out/cornell_$indirect.lcut" --mode lightcuts \
      --size 256x256 -o "$out/cornell_$indirect.png" --stats "$out/cornell_${indirect}_render.json"
done
# The same VPL bake as one MPI job of 3 ranks (issue 30): each rank traces its range of the paths
# and samples its range of the panel; rank 0 gathers them and builds the tree: the same bytes.
if command -v mpirun > /dev/null && [ -x "$bin/lightmass_rank" ]; then
  "$bin/editor_client" bake "$out/cornell.gltf" --server "$server" --builder agglomerative \
      --area-lights 4096 --indirect vpl --bounces 4 --vpl-count 20000 --ranks 3 \
      -o "$out/cornell_vpl_3ranks.lcut" | grep -E "^(indirect|rank)"
  cmp -s "$out/cornell_vpl.lcut" "$out/cornell_vpl_3ranks.lcut" \
      || { echo "demo: the tree baked over 3 MPI ranks differs from the one-process tree"; exit 1; }
  echo "demo: 3 MPI ranks baked the same tree, byte for byte"
else
  echo "demo: mpirun or lightmass_rank missing: the bake over MPI ranks is left out (scripts/install_deps.sh)"
fi
/usr/bin/python3 - "$out" <<'PY'
import json, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg
import numpy as np
out = sys.argv[1]
for indirect in ("vpl", "radiosity"):
    bake = json.load(open("%s/cornell_%s_bake.json" % (out, indirect)))
    print("demo: cornell %s bake: %s" % (indirect, "; ".join(bake["effects"])))
    render = json.load(open("%s/cornell_%s_render.json" % (out, indirect)))
    print("demo: cornell %s render: %d indirect lights, clamped energy %.3g%%" %
          (indirect, render["indirect_lights"], 100.0 * render["clamped_energy_fraction"]))
panels = [mpimg.imread("%s/cornell_%s.png" % (out, name)) for name in ("lightcuts", "vpl", "radiosity")]
mpimg.imsave("%s/cornell_indirect_side_by_side.png" % out, np.concatenate(panels, axis=1))
print("demo: cornell_indirect_side_by_side.png: direct only | VPL indirect | radiosity indirect")
PY

echo "demo: images and stats in $out/"
ls -1 "$out"
