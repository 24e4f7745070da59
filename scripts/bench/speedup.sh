#!/usr/bin/env bash
# Lightcuts against the reference at one sample per pixel, the issue's setting:
# the furnished room (table, pillars, partition, steel cabinet, varnished
# floor; shadow rays on) with unbounded point lights spread through the volume
# (0.3 m from every surface, 819.2 cd in total), agglomerative tree, bound
# criterion (max cut 1000). Per light count, every frame after a warm-up:
#   reference        every light with its shadow ray (GPU), at every K-th
#                    8x8 tile in x and y where the count's stride K > 1 (render
#                    --tile-stride: the same work per pixel, among the same
#                    neighbours as in the full frame; its time scaled by the
#                    full image's pixels over the strided ones);
#   reference_check  with stride 1: the same reference at tile strides 4 and 8
#                    (reference_check4, reference_check8), to show that a
#                    strided time scales as stated and its pixels are the
#                    full reference's;
#   gpu_E            the GPU lightcuts frame (walk search) at E = 0.02, 0.005;
#   shared_E         the same with --share-cuts (one cut per subgroup of 8
#                    neighbouring pixels, coherent shadow rays);
#   shared_0.005_maxcut2500
#                    shared_0.005 with max cut 2,500: at E = 0.005 the pixels
#                    over 2% are those whose cut stopped at max cut 1,000;
#   gpu_noshadow, shared_noshadow
#                    gpu_0.02 and shared_0.02 with --shadows off: the walk,
#                    its bounds and the cluster shading without a ray;
#   reconstruction_E reconstruction cuts at one eye ray per pixel (render --spp 1
#                    --spp-method reconstruction: CPU lightcuts at the corners of
#                    4x4 blocks, reconstruction cuts for the pixels, 2 workers).
# GPU times are the frames' timestamps; CPU times the shading's wall clock (the
# G-buffer rasterised beforehand is left out; it costs ~0.1% of a frame) and
# the workers' CPU time beside it; every command's CPU time (user + system,
# loading and warm-up included) is kept too. Errors against the reference
# (scripts/bench/speedup_report.py, error_stats.cpp's definition), on the reference's
# pixels only where it was strided, or on every pixel against a full
# reference image kept in the cache (below). Writes docs/bench/speedup.csv and
# docs/bench/speedup.png.
# Usage: scripts/bench/speedup.sh [build-dir] [light counts] [size] [reference tile strides]
# (counts and strides comma-separated, one stride per count; default 4,4).
# LC_BENCH_CACHE=DIR keeps each count's scene and tree in DIR/LIGHTS/ and
# reuses them, and with them a full (stride 1) reference's image and stats,
# copied there as reference_full.pfm/.json when a run renders one: a later run
# times its strided reference again (speed-ups need the reference's time from
# the same run) and measures errors on the full image. LC_BENCH_METHODS (a
# comma-separated list of the frames above, e.g. gpu_0.02,reconstruction_0.02)
# renders only those.
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
counts="${2:-16384,131072}"
size="${3:-256x256}"
strides="${4:-4,4}"
cache="${LC_BENCH_CACHE:-}"
all_methods="gpu_0.02,shared_0.02,reconstruction_0.02,gpu_0.005,shared_0.005,reconstruction_0.005"
all_methods+=",shared_0.005_maxcut2500,shared_0.005_maxcut2500_importance,gpu_noshadow,shared_noshadow"
methods="${LC_BENCH_METHODS:-$all_methods}"
source scripts/lib/furnished_bench.sh
build_bench_client "$build_dir"
client="$LC_CLIENT"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
wanted() { [[ ",$methods," == *",$1,"* ]]; }

read -r -a stride_of <<<"${strides//,/ }"
index=0
for lights in ${counts//,/ }; do
  stride="${stride_of[$index]:-1}"
  index=$((index + 1))
  base="$work/$lights"
  mkdir -p "$base"
  if [[ -n "$cache" && -f "$cache/$lights/tree.lcut" ]]; then
    cp "$cache/$lights/scene.gltf" "$cache/$lights/tree.lcut" "$base/"
  else
    make_furnished_room "$base" "$lights"
    if [[ -n "$cache" ]]; then
      mkdir -p "$cache/$lights"
      cp "$base/scene.gltf" "$base/tree.lcut" "$cache/$lights/"
    fi
  fi
  render() {  # tag, then render flags
    local tag=$1
    shift
    if [[ "$tag" != reference* ]] && ! wanted "$tag"; then return; fi
    # Validation would slow the GPU work down; the benchmark measures the renderer alone.
    # The command's CPU time (user + system, every thread: lavapipe's too) beside the clocks.
    LC_VALIDATION=0 /usr/bin/time -f "%U %S" -o "$base/$tag.cpu" \
      "$client" render "$base/scene.gltf" --tree "$base/tree.lcut" --size "$size" \
      --criterion bound --threads 2 --stats "$base/$tag.json" --float "$base/$tag.pfm" \
      -o "$base/$tag.png" "$@" >"$base/$tag.log" 2>&1 || { cat "$base/$tag.log"; exit 1; }
    tail -n 1 "$base/$tag.log"
  }
  render reference --mode reference --tile-stride "$stride"
  if [[ "$stride" == 1 ]]; then
    render reference_check4 --mode reference --tile-stride 4
    render reference_check8 --mode reference --tile-stride 8
    if [[ -n "$cache" ]]; then
      cp "$base/reference.pfm" "$cache/$lights/reference_full.pfm"
      cp "$base/reference.json" "$cache/$lights/reference_full.json"
    fi
  elif [[ -n "$cache" && -f "$cache/$lights/reference_full.pfm" ]]; then
    cp "$cache/$lights/reference_full.pfm" "$cache/$lights/reference_full.json" "$base/"
  fi
  for e in 0.02 0.005; do
    render "gpu_$e" --mode lightcuts --error "$e"
    render "shared_$e" --mode lightcuts --error "$e" --share-cuts
    render "reconstruction_$e" --mode lightcuts --error "$e" --spp 1 --spp-method reconstruction
  done
  render shared_0.005_maxcut2500 --mode lightcuts --error 0.005 --share-cuts --max-cut 2500
  # Representatives drawn per pixel by importance (docs/BENCHMARKS.md, "Per-pixel representatives").
  render shared_0.005_maxcut2500_importance --mode lightcuts --error 0.005 --share-cuts --max-cut 2500 \
    --representatives importance
  render gpu_noshadow --mode lightcuts --error 0.02 --shadows off
  render shared_noshadow --mode lightcuts --error 0.02 --shadows off --share-cuts
done

mkdir -p docs/bench
/usr/bin/python3 scripts/bench/speedup_report.py --work "$work" --counts "$counts" --size "$size" \
  --methods "$methods" --csv docs/bench/speedup.csv --plot docs/bench/speedup.png
cat docs/bench/speedup.csv
