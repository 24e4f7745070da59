#!/usr/bin/env bash
# server-status latency while a 1,000,000-path VPL bake runs, before and after
# issue 41's fixes, back to back: "before" is BEFORE_BUILD's client (asio's
# resolver) against bake threads at nice 0; "after" is BUILD's client with
# --timing against the default --bake-nice 10. BUSY busy loops run beside it
# (the other builds of a shared box).
# Usage: scripts/bench/status_latency.sh BUILD BEFORE_BUILD [QUERIES] [BUSY]
set -euo pipefail
build=$1
before=$2
queries=${3:-12}
busy=${4:-0}
bin=$build/bin
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
"$bin/editor_client" make-scene room -o "$work/room.gltf" >/dev/null
"$bin/editor_client" add-lights "$work/room.gltf" --count 24 --layout random --seed 5 \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 -o "$work/room24.gltf" >/dev/null

# Milliseconds one command takes, start to exit (its output in $work/out and err).
elapsed_ms() {
    local start end
    start=$(date +%s%N)
    "$@" >"$work/out" 2>"$work/err"
    end=$(date +%s%N)
    echo $(((end - start) / 1000000))
}
for _ in $(seq "$busy"); do (while :; do :; done) & done

for side in before after; do
    if [ "$side" = before ]; then nice=0 client=("$before/bin/editor_client" server-status)
    else nice=10 client=("$bin/editor_client" server-status --timing); fi
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
    # Queries while the bake runs (not once it streams or is done), up to QUERIES of them.
    for _ in $(seq "$queries"); do
        ms=$(elapsed_ms "${client[@]}" "$address")
        grep -q 'bake 1: running' "$work/out" || break
        status+=("$ms")
        echo "$side: $(grep -o 'bake 1: [a-z]*, [a-z ]*[0-9.]*%' "$work/out") $(cat "$work/err")"
        version+=("$(elapsed_ms "$bin/editor_client" --version)")
        sleep 0.1
    done
    echo "$side: server-status ms: ${status[*]}"
    echo "$side: --version ms:      ${version[*]}"
    echo "$side: load: $(cut -d' ' -f1-3 /proc/loadavg)"
    kill "$bake" 2>/dev/null || true
    wait "$bake" 2>/dev/null || true
    kill "$server"
    wait "$server" || true
done
