#!/usr/bin/env bash
# Every kind of glTF the product writes, through Khronos' glTF-Validator
# (issue 28: "every glTF the product writes still passes"): the generated
# scenes (make-scene, heavy-room at 20,000 triangles), add-lights' output on
# the surfaces of the furnished room, and any files given as arguments. The
# validator is the npm package gltf-validator, installed into BUILD/gltf-validator
# (npm's registry must be reachable). Exits 1 when a file has an error.
# Usage: scripts/tools/validate_gltf.sh [build-dir] [extra.gltf ...]
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
shift || true
client="$build_dir/bin/editor_client"
tools="$build_dir/gltf-validator"
if [[ ! -d "$tools/node_modules/gltf-validator" ]]; then
    mkdir -p "$tools"
    (cd "$tools" && npm install --silent --no-audit --no-fund gltf-validator >/dev/null)
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for scene in thesis-fig91 thesis-test1 room furnished-room cornell-emissive; do
    "$client" make-scene "$scene" -o "$work/$scene.gltf" >/dev/null
done
"$client" make-scene heavy-room --triangles 20000 -o "$work/heavy-room.gltf" >/dev/null
"$client" add-lights "$work/furnished-room.gltf" --count 500 --layout surface --type mixed --seed 3 \
    -o "$work/surface-lights.gltf" >/dev/null
NODE_PATH="$tools/node_modules" node scripts/lib/validate_gltf.js "$work"/*.gltf "$@"
