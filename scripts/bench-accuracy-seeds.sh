#!/usr/bin/env bash
# The accuracy target at E = 0.005 over several trees of the same lights:
# the furnished room of scripts/bench-speedup.sh (16,384 lights by default),
# its agglomerative tree baked with each seed (bake --seed: the
# representatives' draws, nothing else), each rendered as the speed-up
# benchmark's E = 0.005 row (shared cuts, max cut 2,500), all against one
# reference. One tree fixes one draw of every cluster's representative for
# the whole image, so one seed's share of lit pixels within 2% is one sample
# of the method's spread (docs/BENCHMARKS.md, "Accuracy at E = 0.005").
# Writes docs/bench/accuracy_seeds.csv.
# Usage: scripts/bench-accuracy-seeds.sh [build-dir] [lights] [size] [seeds] [reference-dir]
# reference-dir: a work folder of bench-speedup.sh for the same count
# (scene.gltf, tree.lcut, reference.pfm, reference.json): its scene and
# reference are reused (the reference alone takes 12 minutes on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"
lights="${2:-16384}"
size="${3:-256x256}"
seeds="${4:-0,1,2,3}"
reference_dir="${5:-}"
source scripts/lib/furnished_bench.sh
build_bench_client "$build_dir"
client="$LC_CLIENT"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

if [[ -n "$reference_dir" ]]; then
  cp "$reference_dir"/{scene.gltf,tree.lcut,reference.pfm,reference.json} "$work/"
else
  make_furnished_room "$work" "$lights"
  LC_VALIDATION=0 "$client" render "$work/scene.gltf" --tree "$work/tree.lcut" --size "$size" \
    --mode reference --stats "$work/reference.json" --float "$work/reference.pfm" \
    -o "$work/reference.png" >"$work/reference.log" 2>&1 || { cat "$work/reference.log"; exit 1; }
fi
for seed in ${seeds//,/ }; do
  tree="$work/tree.lcut"
  if [[ "$seed" != 0 ]]; then
    tree="$work/tree$seed.lcut"
    "$client" bake "$work/scene.gltf" --spawn-server --builder agglomerative --seed "$seed" \
      -o "$tree" >/dev/null 2>&1
  fi
  # Validation would slow the GPU work down; the benchmark measures the renderer alone.
  /usr/bin/time -f "%U %S %e" -o "$work/seed$seed.time" env LC_VALIDATION=0 "$client" render \
    "$work/scene.gltf" --tree "$tree" --size "$size" --criterion bound --mode lightcuts \
    --error 0.005 --share-cuts --max-cut 2500 --stats "$work/seed$seed.json" \
    --float "$work/seed$seed.pfm" -o "$work/seed$seed.png" >"$work/seed$seed.log" 2>&1 ||
    { cat "$work/seed$seed.log"; exit 1; }
  tail -n 1 "$work/seed$seed.log"
done

mkdir -p docs/bench
/usr/bin/python3 scripts/accuracy_seeds_report.py --work "$work" --lights "$lights" --size "$size" \
  --seeds "$seeds" --csv docs/bench/accuracy_seeds.csv
cat docs/bench/accuracy_seeds.csv
