#!/usr/bin/env bash
# Lightcuts against the reference at one sample per pixel, the issue's setting:
# the furnished room (table, pillars, partition, steel cabinet, varnished
# floor; shadow rays on) with unbounded point lights spread through the volume
# (0.3 m from every surface, 819.2 cd in total), agglomerative tree, bound
# criterion (max cut 1000). Per light count, every frame after a warm-up:
#   reference        every light with its shadow ray (GPU), at every K-th
#                    pixel in x and y where the count's stride K > 1 (render
#                    --pixel-stride: the same work per pixel, its time scaled
#                    by the full image's pixels over the strided ones);
#   reference_check  with stride 1: the same reference at stride 4, to show
#                    that a strided time scales as stated;
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
# G-buffer rasterised beforehand is left out; it costs ~0.1% of a frame).
# Errors against the reference (scripts/speedup_report.py, error_stats.cpp's
# definition), on the reference's pixels only where it was strided. Writes
# docs/bench/speedup.csv and docs/bench/speedup.png.
# Usage: scripts/bench-speedup.sh [build-dir] [light counts] [size] [reference strides]
# (counts and strides comma-separated, one stride per count; default 4,8).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"
counts="${2:-16384,131072}"
size="${3:-256x256}"
strides="${4:-4,8}"
source scripts/lib/furnished_bench.sh
build_bench_client "$build_dir"
client="$LC_CLIENT"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

read -r -a stride_of <<<"${strides//,/ }"
index=0
for lights in ${counts//,/ }; do
  stride="${stride_of[$index]:-1}"
  index=$((index + 1))
  base="$work/$lights"
  mkdir -p "$base"
  make_furnished_room "$base" "$lights"
  render() {  # tag, then render flags
    local tag=$1
    shift
    # Validation would slow the GPU work down; the benchmark measures the renderer alone.
    LC_VALIDATION=0 "$client" render "$base/scene.gltf" --tree "$base/tree.lcut" --size "$size" \
      --criterion bound --threads 2 --stats "$base/$tag.json" --float "$base/$tag.pfm" \
      -o "$base/$tag.png" "$@" >"$base/$tag.log" 2>&1 || { cat "$base/$tag.log"; exit 1; }
    tail -n 1 "$base/$tag.log"
  }
  render reference --mode reference --pixel-stride "$stride"
  if [[ "$stride" == 1 ]]; then
    render reference_check --mode reference --pixel-stride 4
  fi
  for e in 0.02 0.005; do
    render "gpu_$e" --mode lightcuts --error "$e"
    render "shared_$e" --mode lightcuts --error "$e" --share-cuts
    render "reconstruction_$e" --mode lightcuts --error "$e" --spp 1 --spp-method reconstruction
  done
  render shared_0.005_maxcut2500 --mode lightcuts --error 0.005 --share-cuts --max-cut 2500
  render gpu_noshadow --mode lightcuts --error 0.02 --shadows off
  render shared_noshadow --mode lightcuts --error 0.02 --shadows off --share-cuts
done

mkdir -p docs/bench
/usr/bin/python3 scripts/speedup_report.py --work "$work" --counts "$counts" --size "$size" \
  --csv docs/bench/speedup.csv --plot docs/bench/speedup.png
cat docs/bench/speedup.csv
