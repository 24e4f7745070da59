#!/usr/bin/env bash
# Load benchmark (not a CI test): CLIENTS concurrent clients each run BAKES
# bakes against one local lightmass_server on 127.0.0.1; counts failures and
# samples the server's RSS from /proc into a CSV.
#   scripts/load_test.sh [--clients 64] [--bakes 10] [--lights 512]
#                        [--server-bin build/bin/lightmass_server]
#                        [--client-bin build/bin/editor_client]
#                        [--csv docs/bench/load_rss.csv] [--limit-s 1800]
# --server-bin build-asan/bin/lightmass_server runs it against the ASan+UBSan
# server (cmake --preset asan && cmake --build build-asan --target lightmass_server).
# Prints one summary line; exits non-zero when a bake failed or the server died.
set -euo pipefail
cd "$(dirname "$0")/.."

clients=64
bakes=10
lights=512
server_bin=build/bin/lightmass_server
client_bin=build/bin/editor_client
csv=docs/bench/load_rss.csv
limit_s=1800
while [ $# -gt 0 ]; do
    case "$1" in
        --clients) clients="$2"; shift 2 ;;
        --bakes) bakes="$2"; shift 2 ;;
        --lights) lights="$2"; shift 2 ;;
        --server-bin) server_bin="$2"; shift 2 ;;
        --client-bin) client_bin="$2"; shift 2 ;;
        --csv) csv="$2"; shift 2 ;;
        --limit-s) limit_s="$2"; shift 2 ;;
        *) echo "unknown option $1" >&2; exit 2 ;;
    esac
done

work=$(mktemp -d /tmp/lc-load.XXXXXX)
server_pid=""
sampler_pid=""
cleanup() {
    if [ -n "$sampler_pid" ]; then kill "$sampler_pid" 2>/dev/null || true; fi
    if [ -n "$server_pid" ]; then kill "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; fi
    rm -rf "$work"
}
trap cleanup EXIT

"$client_bin" add-lights --count "$lights" --layout random --seed 7 --type mixed \
    -o "$work/scene.gltf" >/dev/null

# shellcheck source=scripts/lib/local_server.sh
source scripts/lib/local_server.sh
start_local_server "$server_bin" "$work" --threads 2 --quiet
server_pid=$LC_SERVER_PID
port=$LC_SERVER_PORT

mkdir -p "$(dirname "$csv")"
sample_rss "$server_pid" "$csv" 0.5 &
sampler_pid=$!

start=$(date +%s.%N)
deadline=$(( $(date +%s) + limit_s ))
client_loop() {
    local id=$1 failures=0
    for ((b = 0; b < bakes; b++)); do
        local left=$(( deadline - $(date +%s) ))
        if [ "$left" -le 0 ]; then failures=$((failures + bakes - b)); break; fi
        if ! timeout "$left" "$client_bin" bake "$work/scene.gltf" --server "127.0.0.1:$port" \
            --seed "$b" -o "$work/tree_$id.lcut" >"$work/client_$id.log" 2>&1; then
            failures=$((failures + 1))
            cp "$work/client_$id.log" "$work/failed_${id}_$b.log"
        fi
    done
    echo "$failures" >"$work/failures_$id"
}
pids=()
for ((c = 0; c < clients; c++)); do
    client_loop "$c" &
    pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid" || true; done
end=$(date +%s.%N)

alive=yes
kill -0 "$server_pid" 2>/dev/null || alive=no
# A clean stop, so that a sanitizer build also reports leaks into the log.
kill -TERM "$server_pid" 2>/dev/null || true
wait "$server_pid" 2>/dev/null || true
server_pid=""
reports=$(grep -cE "ERROR: (Address|Leak)Sanitizer|runtime error:" "$work/server.log" || true)
failures=0
for ((c = 0; c < clients; c++)); do failures=$((failures + $(cat "$work/failures_$c" 2>/dev/null || echo "$bakes"))); done
kill "$sampler_pid" 2>/dev/null || true
wait "$sampler_pid" 2>/dev/null || true
sampler_pid=""

read -r first_kib peak_kib last_kib samples < <(awk -F, 'NR > 1 {
    if (n == 0) first = $2; if ($2 > peak) peak = $2; last = $2; n++ }
    END { print first + 0, peak + 0, last + 0, n + 0 }' "$csv")
total=$((clients * bakes))
seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
rate=$(awk -v n=$((total - failures)) -v s="$seconds" 'BEGIN { printf "%.2f", n / s }')
echo "load: $clients clients x $bakes bakes ($lights lights): $failures of $total failed," \
    "$seconds s, $rate bakes/s; server $([ "$alive" = yes ] && echo alive || echo DIED)," \
    "$reports sanitizer reports;" \
    "RSS first $first_kib KiB, peak $peak_kib KiB, last $last_kib KiB ($samples samples in $csv)"
for f in "$work"/failed_*.log; do
    [ -e "$f" ] || break
    echo "first failure ($f):"; tail -3 "$f"; break
done
if [ "$reports" -gt 0 ]; then grep -m 5 -E "ERROR: |runtime error:" "$work/server.log"; fi
[ "$failures" -eq 0 ] && [ "$alive" = yes ] && [ "$reports" -eq 0 ]
