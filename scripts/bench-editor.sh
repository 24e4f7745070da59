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
# Writes docs/bench/editor_fps.csv: run, lights, width, height, mode, frames,
# seconds, fps, gpu_ms_last. The goal on lavapipe with two cores: >= 5 fps.
# Usage: scripts/bench-editor.sh [build-dir] [frames]   (default: build, 10; a frame can take
# tens of seconds on lavapipe, see docs/bench/editor_fps.csv)
set -euo pipefail
cd "$(dirname "$0")/.."
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
      --size 640x360)
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
cat "$out"
