#!/usr/bin/env bash
# server-status latency while a 1,000,000-path VPL bake runs, with the bake
# threads at nice 0 (as before --bake-nice) and at the default 10, back to back.
# BUSY busy loops run beside it (the other builds of a shared box).
# Usage: scripts/bench/status_latency.sh [BUILD_DIR] [QUERIES] [BUSY]
set -euo pipefail
build=${1:-build}
queries=${2:-12}
busy=${3:-0}
bin=$build/bin
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
"$bin/editor_client" make-scene room -o "$work/room.gltf" >/dev/null
"$bin/editor_client" add-lights "$work/room.gltf" --count 24 --layout random --seed 5 \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 -o "$work/room24.gltf" >/dev/null

# Milliseconds one command takes, start to exit (its output in $work/out).
elapsed_ms() {
    local start end
    start=$(date +%s%N)
    "$@" >"$work/out" 2>"$work/err"
    end=$(date +%s%N)
    echo $(((end - start) / 1000000))
}
for _ in $(seq "$busy"); do (while :; do :; done) & done

for nice in 0 10; do
    rm -f "$work/port"
    "$bin/lightmass_server" --listen 127.0.0.1:0 --port-file "$work/port" --threads 2 --bake-nice "$nice" \
        --quiet >/dev/null &
    server=$!
    while [ ! -s "$work/port" ]; do sleep 0.05; done
    address=127.0.0.1:$(cat "$work/port")
    "$bin/editor_client" bake "$work/room24.gltf" --server "$address" --builder lbvh --indirect vpl \
        --vpl-count 1000000 -o "$work/tree.lcut" >/dev/null 2>&1 &
    bake=$!
    sleep 1
    status=() version=()
    for _ in $(seq "$queries"); do
        status+=("$(elapsed_ms "$bin/editor_client" server-status --timing "$address")")
        echo "$(grep -o 'bake 1: [a-z]*, [a-z ]*[0-9.]*%' "$work/out" || echo "no bake") $(cat "$work/err")"
        version+=("$(elapsed_ms "$bin/editor_client" --version)")
        sleep 0.25
    done
    echo "bake-nice $nice: server-status ms: ${status[*]}"
    echo "bake-nice $nice: --version ms:      ${version[*]}"
    echo "bake-nice $nice: load: $(cut -d' ' -f1-3 /proc/loadavg); bake still running: $(kill -0 $bake 2>/dev/null && echo yes || echo no)"
    kill "$bake" 2>/dev/null || true
    wait "$bake" 2>/dev/null || true
    kill "$server"
    wait "$server" || true
done
