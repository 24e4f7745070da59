#!/usr/bin/env bash
# Renders the pictures the README shows into docs/images/ (256x256 PNGs):
# the demo room in every mode, the furnished room with shadows (reference,
# lightcuts, error), and the thesis's Test 1 and Test 2 cut pictures.
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=build/bin
[ -x "$bin/editor_client" ] || bash scripts/build.sh default lightmass_server editor_client
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
img=docs/images
mkdir -p "$img"

"$bin/editor_client" add-lights --count 768 --layout random --type point --intensity 0.4 --range 2.5 \
    --seed 7 -o "$work/points.gltf" > /dev/null
"$bin/editor_client" add-lights "$work/points.gltf" --count 256 --layout random --type spot \
    --intensity 1.5 --range 3.5 --seed 8 -o "$work/room.gltf" > /dev/null
"$bin/editor_client" bake "$work/room.gltf" --spawn-server -o "$work/room.lcut" > /dev/null 2>&1
modes=(reference lightcuts cuts cutsize)
if "$bin/editor_client" render --help | grep -q "error"; then modes+=(error); fi
for mode in "${modes[@]}"; do
  "$bin/editor_client" render "$work/room.gltf" --tree "$work/room.lcut" --mode "$mode" --size 256x256 \
      -o "$img/room_$mode.png" --stats "$work/room_$mode.json" 2> /dev/null | tail -1
done

# The furnished room of demo.sh: 1,024 unbounded point lights, shadow rays and glossy lobes on.
"$bin/editor_client" make-scene furnished-room -o "$work/furnished_empty.gltf" > /dev/null
"$bin/editor_client" add-lights "$work/furnished_empty.gltf" --count 1024 --layout random --type point \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity 0.8 --range 0 --seed 9 -o "$work/furnished.gltf" > /dev/null
"$bin/editor_client" bake "$work/furnished.gltf" --spawn-server --builder agglomerative \
    -o "$work/furnished.lcut" > /dev/null 2>&1
for mode in reference lightcuts error; do
  "$bin/editor_client" render "$work/furnished.gltf" --tree "$work/furnished.lcut" --mode "$mode" \
      --size 256x256 -o "$img/furnished_$mode.png" 2> /dev/null | tail -1
done

for scene in thesis-test1 thesis-test2; do
  "$bin/editor_client" make-scene "$scene" -o "$work/$scene.gltf" > /dev/null
  "$bin/editor_client" bake "$work/$scene.gltf" --spawn-server --representative thesis-first \
      -o "$work/$scene.lcut" > /dev/null 2>&1
  "$bin/editor_client" render "$work/$scene.gltf" --tree "$work/$scene.lcut" --mode cuts --criterion radius \
      --size 256x256 -o "$img/${scene}_cuts.png" 2> /dev/null | tail -1
done
