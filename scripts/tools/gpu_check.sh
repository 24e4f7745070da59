#!/usr/bin/env bash
# Every render mode, criterion, bound search and representative choice on
# whatever Vulkan device is present (lavapipe here; NVIDIA's driver on a lent
# GPU), with the validation layers on: which start, which fail and how, their
# per-pass GPU timestamps, and the GPU's lightcuts against the CPU evaluator's
# on the same eye rays. Made for a device machine: build here, pack with
# ../shared/tools/gpu-bundle.sh, run there as
#   bash .gpu/enter.sh bash scripts/tools/gpu_check.sh BIN_DIR OUT_DIR [LIGHTS] [SIZE]
# Writes OUT_DIR/gpu_check.csv (one row per run: name, status, the stats'
# timings and counters, the first line of an error) and prints a summary;
# exits 1 when a run fails or a GPU/CPU pair disagrees beyond 1% mean error.
set -uo pipefail
bin="${1:?usage: tools/gpu_check.sh BIN_DIR OUT_DIR [LIGHTS] [SIZE]}"
out="${2:?usage: tools/gpu_check.sh BIN_DIR OUT_DIR [LIGHTS] [SIZE]}"
lights="${3:-4096}"
size="${4:-64x64}"
client="$bin/editor_client"
export LC_SERVER_BIN="$bin/lightmass_server"
mkdir -p "$out"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$client" make-scene furnished-room -o "$work/empty.gltf" >/dev/null
"$client" add-lights "$work/empty.gltf" --count "$lights" --layout random --type mixed \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity "$(python3 -c "print(819.2 / $lights)")" --range 0 \
    --seed 9 -o "$work/scene.gltf" >/dev/null
"$client" bake "$work/scene.gltf" --spawn-server --builder agglomerative -o "$work/tree.lcut" >/dev/null 2>&1

# name and the render flags of each run.
runs=(
  "reference|--mode reference"
  "radius|--mode lightcuts --criterion radius"
  "bound_walk|--mode lightcuts"
  "bound_walk_shared|--mode lightcuts --share-cuts"
  "bound_walk_raster|--mode lightcuts --primary raster"
  "bound_walk_rays|--mode lightcuts --primary rays"
  "bound_heap|--mode lightcuts --bound-search heap"
  "pixel_representatives|--mode lightcuts --representatives pixel"
  "importance_representatives|--mode lightcuts --representatives importance"
  "cuts|--mode cuts"
  "cutsize|--mode cutsize"
  "realtime_8|--mode realtime --realtime-cut 8"
  "realtime_32_frames_16|--mode realtime --realtime-cut 32 --frames 16"
  "spp2_gpu|--mode lightcuts --spp 2 --spp-method gpu"
  "spp2_cpu_lightcuts|--mode lightcuts --spp 2 --spp-method lightcuts"
  "spp1_cpu_reconstruction|--mode lightcuts --spp 1 --spp-method reconstruction"
)
csv="$out/gpu_check.csv"
echo "name,status,device,render_ms,render_clock,gbuffer_ms,lighting_ms,output_ms,wall_ms,avg_cut,shadow_rays,loop_limit_stops,nonfinite_pixels,validation_enabled,validation_messages,error" > "$csv"
failures=0
for run in "${runs[@]}"; do
  name="${run%%|*}"
  flags="${run#*|}"
  # shellcheck disable=SC2086
  if "$client" render "$work/scene.gltf" --tree "$work/tree.lcut" --size "$size" --validation $flags \
      -o "$out/$name.png" --float "$out/$name.pfm" --stats "$out/$name.json" > "$work/$name.log" 2>&1; then
    python3 - "$out/$name.json" "$name" >> "$csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
keys = ["device", "render_ms", "render_clock", "gbuffer_ms", "lighting_ms", "output_ms", "wall_ms", "avg_cut",
        "shadow_rays", "loop_limit_stops", "nonfinite_pixels", "validation_enabled", "validation_messages"]
print(",".join([sys.argv[2], "ok"] + [str(s.get(k, "")).replace(",", " ") for k in keys] + [""]))
PY
  else
    failures=$((failures + 1))
    error="$(grep -m1 -i "error\|fail" "$work/$name.log" | tr ',' ' ' | cut -c1-200)"
    echo "$name,failed,,,,,,,,,,,,,,$error" >> "$csv"
  fi
done

# The GPU's lightcuts against the CPU evaluator's on the same jittered eye rays.
python3 - "$out" <<'PY' || failures=$((failures + 1))
import struct, sys
def pfm(path):
    with open(path, "rb") as f:
        f.readline()
        w, h = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = f.read()
    return struct.unpack(("<" if scale < 0 else ">") + "f" * (w * h * 3), data)
out = sys.argv[1]
try:
    gpu, cpu = pfm(out + "/spp2_gpu.pfm"), pfm(out + "/spp2_cpu_lightcuts.pfm")
except OSError as e:
    sys.exit("GPU/CPU comparison: " + str(e))
lum = lambda im, i: 0.2126 * im[i] + 0.7152 * im[i + 1] + 0.0722 * im[i + 2]
errors = [abs(lum(gpu, i) - lum(cpu, i)) / lum(cpu, i) for i in range(0, len(cpu), 3) if lum(cpu, i) > 1e-6]
mean = sum(errors) / max(len(errors), 1)
print("GPU against CPU lightcuts on the same eye rays: mean relative difference %.5f over %d pixels" % (mean, len(errors)))
sys.exit(0 if mean < 0.01 else 1)
PY
{ column -s, -t < "$csv" 2>/dev/null || cat "$csv"; } | cut -c1-180
echo "gpu-check: $failures failure(s); $csv"
[ "$failures" -eq 0 ]
