#!/usr/bin/env bash
# Editor frame rate: 4,096 point lights in the generated room, baked once by a
# local lightmass_server, shown by `editor_client view` at 640x360 in lightcuts
# mode (bound criterion, E = 0.02, the editor's default). Three runs:
#   headless          camera still: every frame at full size, never presented
#   headless_moving   camera orbiting every frame (--orbit): the adaptive
#                     resolution renders at reduced size while it moves; the
#                     first frame (full size, before any move) is included
#   xvfb              a real GLFW window and swapchain with the ImGui panels
#                     drawn, camera still (skipped when xvfb-run is missing)
# These three render whole frames (--no-progressive). Then the progressive view
# of the furnished room with 4,096 unbounded point lights and shadow rays at
# 960x600, in an xvfb window with the panels, until its first complete image:
#   xvfb_progressive  the frames drawn while the image refined (the UI's rate)
# against `render` of the same view (camera, mode, criterion, error ratio).
# Writes docs/bench/editor_fps.csv: run, lights, width, height, mode, frames,
# seconds, fps, gpu_ms_last; and docs/bench/editor_progressive.csv: lights,
# width, height, budget_ms, refining_frames, refining_s, ui_fps,
# first_complete_s, render_s (render's frame, wall), render_gpu_s, ratio (the
# first complete image over render's frame). Goals on lavapipe with two cores:
# whole frames >= 5 fps at 640x360; progressive UI > 20 fps, and the first
# complete image within 2x render's frame.
# Usage: scripts/bench/editor.sh [build-dir] [frames]   (default: build, 10; a frame can take
# tens of seconds on lavapipe, see docs/bench/editor_fps.csv)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
frames="${2:-10}"
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build_dir" --target editor_client lightmass_server -j "$(nproc)"
client="$build_dir/bin/editor_client"
export LC_SERVER_BIN="$(realpath "$build_dir")/bin/lightmass_server"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$client" add-lights --count 4096 --layout random --seed 1 --range 0 -o "$work/room.gltf" >/dev/null
"$client" bake "$work/room.gltf" --spawn-server -o "$work/room.lcut" >/dev/null

out=docs/bench/editor_fps.csv
mkdir -p docs/bench
echo "run,lights,width,height,mode,frames,seconds,fps,gpu_ms_last" > "$out"

# "steady: N frames in S s = F fps at WxH, L lights" and "... X ms GPU ..."
record() {
  local run="$1" log="$2"
  python3 - "$run" "$log" "$out" <<'PY'
import re, sys
run, log, out = sys.argv[1:4]
text = open(log).read()
m = re.search(r"steady: (\d+) frames in ([\d.]+) s = ([\d.]+) fps at (\d+)x(\d+), (\d+) lights", text)
g = re.search(r"last in (\w+) mode, ([\d.]+) ms GPU", text)
if not m or not g:
    sys.exit("no frame-rate line in the %s run:\n%s" % (run, text))
frames, seconds, fps, w, h, lights = m.groups()
with open(out, "a") as f:
    f.write("%s,%s,%s,%s,%s,%s,%s,%s,%s\n" % (run, lights, w, h, g.group(1), frames, seconds,
                                             fps, g.group(2)))
PY
}

view=("$client" view "$work/room.gltf" --tree "$work/room.lcut" --mode lightcuts
      --size 640x360 --no-progressive)
LC_VALIDATION=0 "${view[@]}" --frames "$frames" --headless > "$work/headless.log" 2>&1 || { cat "$work/headless.log"; exit 1; }
record headless "$work/headless.log"
LC_VALIDATION=0 "${view[@]}" --headless --frames 40 --orbit 4 > "$work/moving.log" 2>&1 \
  || { cat "$work/moving.log"; exit 1; }
record headless_moving "$work/moving.log"
if command -v xvfb-run >/dev/null 2>&1; then
  LC_VALIDATION=0 xvfb-run -a -s "-screen 0 1280x720x24" "${view[@]}" --frames "$frames" > "$work/xvfb.log" 2>&1 \
    || { cat "$work/xvfb.log"; exit 1; }
  record xvfb_window_with_panels "$work/xvfb.log"
fi

# The progressive view against render, same scene and view.
budget_ms=30
"$client" make-scene furnished-room -o "$work/furnished_empty.gltf" >/dev/null
"$client" add-lights "$work/furnished_empty.gltf" --count 4096 --layout random --type point \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity 0.2 --range 0 --seed 9 -o "$work/furnished.gltf" >/dev/null
"$client" bake "$work/furnished.gltf" --spawn-server --builder agglomerative -o "$work/furnished.lcut" >/dev/null
LC_VALIDATION=0 "$client" render "$work/furnished.gltf" --tree "$work/furnished.lcut" --mode lightcuts \
    --size 960x600 -o "$work/furnished.png" --stats "$work/render.json" > "$work/render.log" 2>&1 \
  || { cat "$work/render.log"; exit 1; }
command -v xvfb-run >/dev/null 2>&1 || { echo "bench-editor: no xvfb-run, no progressive run"; exit 0; }
printf 'wait-refined\nquit\n' > "$work/refine.txt"
LC_VALIDATION=0 xvfb-run -a -s "-screen 0 1280x720x24" "$client" view "$work/furnished.gltf" \
    --tree "$work/furnished.lcut" --size 960x600 --frame-budget-ms "$budget_ms" --script "$work/refine.txt" \
    > "$work/progressive.log" 2>&1 || { cat "$work/progressive.log"; exit 1; }
progressive_out=docs/bench/editor_progressive.csv
python3 - "$work/progressive.log" "$work/render.json" "$out" "$progressive_out" "$budget_ms" <<'PY'
import json, re, sys
log, render_json, fps_csv, out, budget = sys.argv[1:6]
text = open(log).read()
m = re.search(r"progressive: (\d+) frames while refining in ([\d.]+) s = ([\d.]+) fps; "
              r"first complete image in ([\d.]+) s", text)
g = re.search(r"last in (\w+) mode, ([\d.]+) ms GPU", text)
size = re.search(r"at (\d+)x(\d+), (\d+) lights", text)
if not m or not g or not size:
    sys.exit("no progressive figures in the view's output:\n" + text)
frames, seconds, fps, first = m.groups()
lights = size.group(3)
stats = json.load(open(render_json))
render_s, render_gpu_s = stats["wall_ms"] / 1000.0, stats["render_ms"] / 1000.0
with open(fps_csv, "a") as f:
    f.write("xvfb_progressive,%s,960,600,%s,%s,%s,%s,%s\n" % (lights, g.group(1), frames, seconds, fps,
                                                            g.group(2)))
with open(out, "w") as f:
    f.write("lights,width,height,budget_ms,refining_frames,refining_s,ui_fps,first_complete_s,"
            "render_s,render_gpu_s,ratio\n")
    f.write("%s,960,600,%s,%s,%s,%s,%s,%.3f,%.3f,%.2f\n" % (lights, budget, frames, seconds, fps, first,
                                                         render_s, render_gpu_s, float(first) / render_s))
PY
cat "$out" "$progressive_out"
