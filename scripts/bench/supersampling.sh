#!/usr/bin/env bash
# Supersampling (render --spp) on the furnished room (shadows, glossy floor and
# cabinet) with unbounded point lights through the volume, agglomerative tree,
# bound criterion at E = 0.02: the same jittered eye rays (--spp-seed 1) shaded
#   reference       every light at every eye ray (GPU frames, reference mode);
#   gpu             a GPU lightcut frame per eye ray (walk search);
#   lightcuts       a CPU lightcut per eye ray (heap search);
#   reconstruction  the paper's reconstruction cuts (CPU): lightcuts at sparse
#                   samples, reconstruction cuts for the other eye rays;
# and one frame at 1 spp (GPU lightcuts), for the aliasing crop. The two CPU
# methods run the same evaluator on the same eye rays with the same workers
# (--threads 2), so their times and shadow-ray counts compare directly; the
# G-buffers they shade are rasterised on the GPU beforehand and not timed.
# Writes docs/bench/supersampling.csv, docs/bench/supersampling.png and the
# crop docs/images/supersampling_edges.png (scripts/bench/supersampling_report.py).
# Usage: scripts/bench/supersampling.sh [build-dir] [lights] [size] [spp]
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
lights="${2:-4096}"
size="${3:-128x128}"
spp="${4:-16}"
source scripts/lib/furnished_bench.sh
build_bench_client "$build_dir"
client="$LC_CLIENT"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

make_furnished_room "$work" "$lights"

render() {  # tag, then render flags
  local tag=$1
  shift
  # Validation would slow the GPU work down; the benchmark measures the renderer alone.
  LC_VALIDATION=0 "$client" render "$work/scene.gltf" --tree "$work/tree.lcut" --size "$size" \
    --criterion bound --error 0.02 --threads 2 --stats "$work/$tag.json" --float "$work/$tag.pfm" \
    -o "$work/$tag.png" "$@" >"$work/$tag.log" 2>&1 || { cat "$work/$tag.log"; exit 1; }
  tail -n 1 "$work/$tag.log"
}

render reference --mode reference --spp "$spp" --spp-method gpu
# Every image is tone-mapped at the reference's exposure, so the crops compare.
exposure="$(/usr/bin/python3 -c "import json; print(json.load(open('$work/reference.json'))['exposure'])")"
render gpu --mode lightcuts --spp "$spp" --spp-method gpu --exposure "$exposure"
render lightcuts --mode lightcuts --spp "$spp" --spp-method lightcuts --exposure "$exposure"
render reconstruction --mode lightcuts --spp "$spp" --spp-method reconstruction \
  --exposure "$exposure"
render one_spp --mode lightcuts --exposure "$exposure"

mkdir -p docs/bench docs/images
/usr/bin/python3 scripts/bench/supersampling_report.py --work "$work" --lights "$lights" --size "$size" \
  --spp "$spp" --csv docs/bench/supersampling.csv --plot docs/bench/supersampling.png \
  --crop docs/images/supersampling_edges.png
cat docs/bench/supersampling.csv
