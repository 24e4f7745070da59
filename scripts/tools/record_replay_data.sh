#!/usr/bin/env bash
# Re-records the channel dumps under tests/data/replay/ from the real programs:
# a lightmass_server with --record and editor_client bake with --record. Run it
# on purpose after a deliberate protocol or builder change; tests never run it.
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=build/bin
[ -x "$bin/editor_client" ] || bash scripts/build.sh default
work=$(mktemp -d)
trap 'kill "$server_pid" 2>/dev/null || true; rm -rf "$work"' EXIT

"$bin/lightmass_server" --listen 127.0.0.1:0 --port-file "$work/port" --record "$work/server" --quiet &
server_pid=$!
for _ in $(seq 1 100); do [ -s "$work/port" ] && break; sleep 0.1; done
server="127.0.0.1:$(cat "$work/port")"

record_case() {  # name scene builder representative seed
  local name=$1 scene=$2 builder=$3 rep=$4 seed=$5
  rm -rf "$work/server" "$work/client"
  "$bin/editor_client" bake "$scene" --server "$server" --builder "$builder" --representative "$rep" \
      --seed "$seed" --record "$work/client" -o "$work/tree.lcut" > /dev/null
  local dest=tests/data/replay/$name
  rm -rf "$dest"; mkdir -p "$dest/server" "$dest/client"
  cp "$work/server"/*.dump "$dest/server/"
  cp "$work/client"/*.dump "$dest/client/"
  printf '{"builder": "%s", "representative": "%s", "seed": %s}\n' "$builder" "$rep" "$seed" > "$dest/case.json"
  echo "recorded $dest"
}

"$bin/editor_client" make-scene thesis-fig91 -o "$work/fig91.gltf"
"$bin/editor_client" add-lights --count 64 --layout random --type mixed --seed 3 -o "$work/mixed64.gltf"
record_case fig91_optimal_pair_thesis "$work/fig91.gltf" optimal-pair thesis-first 0
record_case mixed64_optimal_pair "$work/mixed64.gltf" optimal-pair intensity 3
record_case mixed64_agglomerative "$work/mixed64.gltf" agglomerative intensity 3
