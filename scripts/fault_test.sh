#!/usr/bin/env bash
# Fault benchmarks (not CI tests) against a local lightmass_server on 127.0.0.1.
#   scripts/fault_test.sh kill [--iterations 100] [--lights 16384]
#       kill -9 the server mid-bake, ITERATIONS times; every time the client's
#       previous tree (bake -o TREE.lcut) must be intact, byte for byte
#   scripts/fault_test.sh stall [--peers 16] [--seconds 30]
#       slow-byte peers (one byte every 0.5 s), silent peers, and peers silent
#       after opening a 200 MB channel (hostile_bake_bench), while normal bakes
#       run: when does the server drop them, and do the bakes still pass?
#   scripts/fault_test.sh hostile [--budget-mb 512] [--hostile-csv docs/bench/hostile_bake.csv]
#       issue 27's rows, each against a fresh server at --memory-budget-mb
#       BUDGET with its RSS sampled every 50 ms: deep and huge VPL bakes,
#       radiosity with 1,000 point lights, an 8192 x 4096 environment, 4 M
#       area-light samples (each cancelled 1.5 s into its first stage: cancel
#       latency, peak RSS), a small bake beside a 10^9-path one, SIGTERM during
#       a radiosity bake, and a peer silent after opening a channel
#   scripts/fault_test.sh tree-cancel [--tree-lights 32768] [--cancels 24] [--label before|after]
#       an optimal-pair build of TREE_LIGHTS lights (every level exact) in
#       process, cancelled CANCELS times spread over it: milliseconds from
#       cancel() to the build's return, appended to docs/bench/tree_cancel.csv
#   scripts/fault_test.sh sigterm [--runs 2] [--sigterm-limit-ms 100] [--sigterm-csv docs/bench/sigterm_exit.csv]
#       SIGTERM to exit (waitpid) of a server in a 4 M-sample area bake at
#       0.5 to 12 s, after its client disconnected, and in a radiosity bake,
#       RUNS times each; fails on a clean stop slower than the limit
#   scripts/fault_test.sh footprint [--footprint-csv docs/bench/bake_footprint.csv] [--footprint-full]
#       each stage's bake run to the end on a fresh server: its VmHWM against
#       the estimate it was admitted by (bake_footprint.h); fails where the
#       peak is above the estimate plus the stored channels; --footprint-full
#       adds the 4,194,304-sample area bake (minutes of one core)
#   scripts/fault_test.sh soak [--minutes 60] [--csv docs/bench/soak_rss.csv]
#       4 clients bake without pause; the server's RSS is sampled every 2 s
#   scripts/fault_test.sh all  (kill, stall, then a 10-minute soak)
# Common: [--server-bin build/bin/lightmass_server] [--client-bin build/bin/editor_client]
# Every loop is bounded in count and in time. Exits non-zero on a broken check
# or on a sanitizer report in the servers' log (a sanitizer build's server).
set -euo pipefail
cd "$(dirname "$0")/.."

mode="${1:-}"
shift || true
iterations=100
lights=16384
peers=16
seconds=30
minutes=60
server_bin=build/bin/lightmass_server
client_bin=build/bin/editor_client
csv=docs/bench/soak_rss.csv
budget_mb=512
hostile_csv=docs/bench/hostile_bake.csv
hostile_bin=build/bin/hostile_bake_bench
tree_lights=32768
cancels=24
runs=2
sigterm_limit_ms=100
sigterm_csv=docs/bench/sigterm_exit.csv
footprint_csv=docs/bench/bake_footprint.csv
footprint_full=no
label=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
while [ $# -gt 0 ]; do
    case "$1" in
        --iterations) iterations="$2"; shift 2 ;;
        --lights) lights="$2"; shift 2 ;;
        --peers) peers="$2"; shift 2 ;;
        --seconds) seconds="$2"; shift 2 ;;
        --minutes) minutes="$2"; shift 2 ;;
        --csv) csv="$2"; shift 2 ;;
        --budget-mb) budget_mb="$2"; shift 2 ;;
        --hostile-csv) hostile_csv="$2"; shift 2 ;;
        --hostile-bin) hostile_bin="$2"; shift 2 ;;
        --tree-lights) tree_lights="$2"; shift 2 ;;
        --cancels) cancels="$2"; shift 2 ;;
        --runs) runs="$2"; shift 2 ;;
        --sigterm-limit-ms) sigterm_limit_ms="$2"; shift 2 ;;
        --sigterm-csv) sigterm_csv="$2"; shift 2 ;;
        --footprint-csv) footprint_csv="$2"; shift 2 ;;
        --footprint-full) footprint_full=yes; shift ;;
        --label) label="$2"; shift 2 ;;
        --server-bin) server_bin="$2"; shift 2 ;;
        --client-bin) client_bin="$2"; shift 2 ;;
        *) echo "unknown option $1" >&2; exit 2 ;;
    esac
done

work=$(mktemp -d /tmp/lc-fault.XXXXXX)
LC_SERVER_PID=""
background=()
cleanup() {
    for pid in "${background[@]}" $LC_SERVER_PID; do kill -9 "$pid" 2>/dev/null || true; done
    rm -rf "$work"
}
trap cleanup EXIT
# shellcheck source=scripts/lib/local_server.sh
source scripts/lib/local_server.sh

stop_server() {
    if [ -n "$LC_SERVER_PID" ]; then
        kill "$LC_SERVER_PID" 2>/dev/null || true
        wait "$LC_SERVER_PID" 2>/dev/null || true
        LC_SERVER_PID=""
    fi
}

make_scene() {  # make_scene LIGHTS OUT.gltf
    "$client_bin" add-lights --count "$1" --layout random --seed 11 --type mixed -o "$2" >/dev/null
}

bake() {  # bake PORT SCENE OUT.lcut SEED [timeout s]
    timeout "${5:-120}" "$client_bin" bake "$2" --server "127.0.0.1:$1" --seed "$4" -o "$3"
}

run_kill() {
    make_scene "$lights" "$work/scene.gltf"
    start_local_server "$server_bin" "$work" --quiet
    bake "$LC_SERVER_PORT" "$work/scene.gltf" "$work/tree.lcut" 0 >/dev/null 2>&1
    stop_server
    # How long an undisturbed bake takes: the kills land inside it.
    start_local_server "$server_bin" "$work" --quiet
    local t0 t1
    t0=$(date +%s%N)
    bake "$LC_SERVER_PORT" "$work/scene.gltf" "$work/timing.lcut" 0 >/dev/null 2>&1
    t1=$(date +%s%N)
    stop_server
    local bake_ms=$(( (t1 - t0) / 1000000 ))
    local previous
    previous=$(sha256sum "$work/tree.lcut" | cut -d' ' -f1)
    local killed=0 finished=0 broken=0 leftovers=0
    for ((i = 1; i <= iterations; i++)); do
        start_local_server "$server_bin" "$work" --quiet
        bake "$LC_SERVER_PORT" "$work/scene.gltf" "$work/tree.lcut" "$i" 60 >"$work/kill_client.log" 2>&1 &
        local client=$!
        background=("$client")
        # Spread the kills over the whole bake: upload, build and download.
        local delay_ms=$(( (RANDOM % 1000) * bake_ms / 1000 ))
        sleep "$(awk -v ms="$delay_ms" 'BEGIN { printf "%.3f", ms / 1000 }')"
        kill -9 "$LC_SERVER_PID" 2>/dev/null || true
        wait "$LC_SERVER_PID" 2>/dev/null || true
        LC_SERVER_PID=""
        local rc=0
        wait "$client" || rc=$?
        background=()
        local now
        now=$(sha256sum "$work/tree.lcut" | cut -d' ' -f1)
        if [ "$rc" -ne 0 ]; then
            killed=$((killed + 1))
            if [ "$now" != "$previous" ]; then
                broken=$((broken + 1))
                echo "iteration $i: the bake failed (rc $rc) and the previous tree changed" >&2
            fi
        else
            finished=$((finished + 1))
            if ! "$client_bin" inspect "$work/tree.lcut" >/dev/null 2>&1; then
                broken=$((broken + 1))
                echo "iteration $i: the bake succeeded but its tree does not read back" >&2
            fi
            previous=$now
        fi
        if ! "$client_bin" inspect "$work/tree.lcut" >/dev/null 2>&1; then
            broken=$((broken + 1))
            echo "iteration $i: the tree on disk does not read back" >&2
        fi
        leftovers=$(find "$work" -maxdepth 1 -name 'tree.lcut?*' | wc -l)
    done
    echo "kill: $iterations kill -9 of the server during a ${bake_ms} ms bake of $lights lights:" \
        "$killed bakes failed (previous tree intact in $((killed - broken > 0 ? killed - broken : 0)))," \
        "$finished finished before the kill, $broken broken trees, $leftovers stray temporary files"
    [ "$broken" -eq 0 ] && [ "$leftovers" -eq 0 ]
}

# stall_open_channel PORT: PEERS peers each open a 200 MB scene channel, send 2 bytes and go silent
# (issue 27: the idle timeout never applied with a channel open); a bake runs meanwhile. Each must be
# dropped by the read deadline; adds the peers not dropped and a failed bake to $failed.
stall_open_channel() {
    [ -x "$hostile_bin" ] || { echo "stall (silent after opening a channel): skipped, $hostile_bin not built"; return 0; }
    local p pids=() closed=0 slowest=0 ms
    for ((p = 0; p < peers; p++)); do
        timeout 60 "$hostile_bin" "127.0.0.1:$1" silent-channel >"$work/silent_channel_$p.csv" 2>&1 &
        pids+=($!)
    done
    background=("${pids[@]}")
    sleep 0.5
    if bake "$1" "$work/small.gltf" "$work/stall.lcut" 7 60 >/dev/null 2>&1; then baked=$((baked + 1)); else failed=$((failed + 1)); fi
    for p in "${pids[@]}"; do wait "$p" || true; done
    background=()
    for ((p = 0; p < peers; p++)); do
        grep -q '^silent-channel,closed,' "$work/silent_channel_$p.csv" || continue
        closed=$((closed + 1))
        ms=$(sed -n 's/.*closed \([0-9]*\) ms after going silent.*/\1/p' "$work/silent_channel_$p.csv")
        [ "${ms:-0}" -gt "$slowest" ] && slowest=$ms
    done
    echo "stall (silent after opening a 200 MB channel): $closed of $peers dropped, the last ${slowest} ms after going silent"
    failed=$((failed + peers - closed))
}

run_stall() {
    make_scene 1024 "$work/small.gltf"
    # Short limits so the figures come within the run; the defaults are 30 s, 600 s and 60 s
    # (a whole frame, however its bytes trickle in).
    start_local_server "$server_bin" "$work" --quiet --read-timeout-ms 2000 --idle-timeout-ms 3000 \
        --frame-timeout-ms 5000
    local port=$LC_SERVER_PORT failed=0 baked=0
    for stall in slow silent; do
        /usr/bin/python3 scripts/lib/stalling_peer.py --port "$port" --mode "$stall" \
            --peers "$peers" --seconds "$seconds" >"$work/$stall.json" &
        local peer=$!
        background=("$peer")
        sleep 0.5
        local t_end=$(( $(date +%s) + seconds ))
        local max_ms=0
        for ((b = 0; b < 1000 && $(date +%s) < t_end; b++)); do
            local t0 t1
            t0=$(date +%s%N)
            if bake "$port" "$work/small.gltf" "$work/stall.lcut" "$b" 60 >/dev/null 2>&1; then
                baked=$((baked + 1))
            else
                failed=$((failed + 1))
            fi
            t1=$(date +%s%N)
            max_ms=$(( (t1 - t0) / 1000000 > max_ms ? (t1 - t0) / 1000000 : max_ms ))
        done
        wait "$peer" || true
        background=()
        echo "stall ($stall): $(cat "$work/$stall.json"); bakes meanwhile: slowest ${max_ms} ms"
    done
    stall_open_channel "$port"
    kill -0 "$LC_SERVER_PID" 2>/dev/null || { echo "stall: the server died" >&2; failed=$((failed + 1)); }
    stop_server
    echo "stall: $baked bakes of 1024 lights passed and $failed failed while stalling peers were attached"
    [ "$failed" -eq 0 ]
}

# peak_rss_mib CSV: the largest RSS sample, in MiB.
peak_rss_mib() { awk -F, 'NR > 1 && $2 > p { p = $2 } END { printf "%.0f", p / 1024 }' "$1"; }

# hostile_row BUDGET_MB SCENARIO [BENCH ARGS...]: one scenario against a fresh server; appends its CSV row.
hostile_row() {
    local budget=$1 scenario=$2
    shift 2
    start_local_server "$server_bin" "$work" --quiet --memory-budget-mb "$budget" --max-bake-seconds 120 \
        --read-timeout-ms 2000 --idle-timeout-ms 600000
    sample_rss "$LC_SERVER_PID" "$work/rss_$scenario.csv" 0.05 &
    local sampler=$! row
    background=("$sampler")
    row=$(timeout 300 "$hostile_bin" "127.0.0.1:$LC_SERVER_PORT" "$scenario" "$@" || echo "$scenario,FAILED,,,,,")
    sleep 0.3  # the memory the bake held, given back
    local after
    after=$(awk '/^VmRSS:/ { printf "%.0f", $2 / 1024 }' "/proc/$LC_SERVER_PID/status" 2>/dev/null || echo "?")
    stop_server
    wait "$sampler" 2>/dev/null || true
    background=()
    echo "$row,$(peak_rss_mib "$work/rss_$scenario.csv"),$after,$budget" | tee -a "$hostile_csv"
}

# sigterm_row SCENARIO AT_MS [DISCONNECT_AT_MS]: SIGTERM to a fresh server AT_MS after the client
# started (its client killed at DISCONNECT_AT_MS first when given), timed to waitpid (sigterm_timer.py);
# appends the row to $sigterm_csv and says "over" when a clean stop took longer than the limit.
sigterm_row() {
    local row ms status
    row=$(/usr/bin/python3 scripts/lib/sigterm_timer.py --server-bin "$server_bin" --hostile-bin "$hostile_bin" \
        --scenario "$1" --at-ms "$2" --disconnect-at-ms "${3:-0}" --log "$work/server.log" || true)
    [ -n "$row" ] || row="$1,$2,${3:-0},,,NO-ROW,"
    echo "$(git rev-parse --short HEAD 2>/dev/null || echo unknown),$row" | tee -a "$sigterm_csv" >&2
    ms=$(echo "$row" | cut -d, -f5)
    status=$(echo "$row" | cut -d, -f6)
    if [ "$status" != 0 ] || awk -v m="$ms" -v l="$sigterm_limit_ms" 'BEGIN { exit !(m == "" || m > l) }'; then
        echo over
    fi
}

# SIGTERM to exit, RUNS times at each point: a 4 M-sample area bake (its sampling ends about
# 0.4 s in, then the tree build's first steps and approximate levels), the same after its client
# disconnected (the bake cancelled 0.05 s and 2 s before the signal), and a radiosity bake's
# point-light pass.
run_sigterm() {
    [ -x "$hostile_bin" ] || { echo "build $hostile_bin first (cmake --build build --target hostile_bake_bench)" >&2; return 2; }
    [ -s "$sigterm_csv" ] || echo "code,scenario,signal_at_ms,disconnect_at_ms,rss_at_signal_mib,exit_ms,status,load1,freed_after_disconnect_ms" \
        >"$sigterm_csv"
    local over=0 total=0 verdict
    for ((r = 0; r < runs; r++)); do
        for point in "area 500" "area 700" "area 2000" "area 4000" "area 8000" "area 12000" "area 4000 3950" "area 10000 8000" \
            "area 6000 4000" "radiosity 5000"; do
            # shellcheck disable=SC2086
            verdict=$(sigterm_row $point)
            total=$((total + 1))
            [ "$verdict" = over ] && over=$((over + 1))
        done
    done
    echo "sigterm: $total signals, $over took longer than ${sigterm_limit_ms} ms or did not stop cleanly" \
        "(load average now $(cut -d' ' -f1-3 /proc/loadavg); rows in $sigterm_csv)"
    [ "$over" -eq 0 ]
}

# footprint_row SCENARIO [BENCH ARGS...]: one bake to the end on a fresh server, its peak against its estimate.
footprint_row() {
    local row
    row=$(/usr/bin/python3 scripts/lib/footprint_peak.py --server-bin "$server_bin" --hostile-bin "$hostile_bin" \
        "$@" || true)
    echo "$(git rev-parse --short HEAD 2>/dev/null || echo unknown),$row" | tee -a "$footprint_csv" >&2
    case "$row" in *,baked | *,cancelled*) [ "$(echo "$row" | cut -d, -f10)" -ge 0 ] || echo over ;; *) echo over ;; esac
}

# Issue 27: each stage's estimate (bake_footprint.h) is an upper bound of what the server holds.
run_footprint() {
    [ -x "$hostile_bin" ] || { echo "build $hostile_bin first (cmake --build build --target hostile_bake_bench)" >&2; return 2; }
    [ -s "$footprint_csv" ] || echo "code,stage,size,builder,threads,estimate_mib,channels_mib,base_mib,peak_mib,bake_peak_mib,headroom_mib,outcome" \
        >"$footprint_csv"
    local over=0 total=0 case
    local cases=(
        "points --size 4096" "points --size 32768" "points --size 65536" "points --size 262144"
        "points --size 1048576" "points --size 262144 --builder lbvh" "points --size 262144 --builder agglomerative"
        "points --size 1048576 --builder lbvh" "points --size 1048576 --builder agglomerative"
        "points --size 16384 --exact" "points --size 65536 --exact" "area --size 262144" "area --size 400000" "area --size 1048576"
        "vpl-fit --size 30000" "vpl-fit --size 100000" "vpl-fit --size 300000" "radiosity --size 4 --patch-size 0.4"
        "radiosity --size 1000 --cancel-after-ms 5000" "environment --size 2048" "environment --size 8192")
    [ "$footprint_full" = yes ] && cases+=("area")
    for case in "${cases[@]}"; do
        # shellcheck disable=SC2086
        [ "$(footprint_row $case)" = over ] && over=$((over + 1))
        total=$((total + 1))
    done
    echo "footprint: $total bakes run to the end, $over above their estimate plus their stored channels" \
        "(rows in $footprint_csv)"
    [ "$over" -eq 0 ]
}

run_hostile() {
    [ -x "$hostile_bin" ] || { echo "build $hostile_bin first (cmake --build build --target hostile_bake_bench)" >&2; return 2; }
    mkdir -p "$(dirname "$hostile_csv")"
    echo "scenario,outcome,stage,cancel_ms,small_idle_ms,small_busy_ms,detail,peak_rss_mib,rss_after_mib,budget_mib" \
        >"$hostile_csv"
    # The issue's rows under a small budget: each refused up front, or baked within it.
    for scenario in vpl-deep radiosity environment area vpl-huge; do
        hostile_row "$budget_mb" "$scenario" --cancel-after-ms 1500
    done
    # Bakes that fit, run to the end: their peak RSS against the estimate they were admitted by.
    hostile_row "$budget_mb" area-fit
    hostile_row "$budget_mb" vpl-fit
    hostile_row "$budget_mb" silent-channel
    # The same heavy bakes admitted (the default 4 GiB budget), each cancelled inside its heaviest stage.
    hostile_row 4096 vpl-deep --cancel-after-ms 1000
    hostile_row 4096 radiosity --cancel-after-ms 1500
    hostile_row 4096 environment --cancel-after-ms 150
    hostile_row 4096 area --cancel-after-ms 1500
    hostile_row 4096 area --cancel-after-ms 4000
    hostile_row 4096 vpl-huge --cancel-after-ms 1500 --small
    # SIGTERM to exit within --sigterm-limit-ms: during radiosity, the 4 M-sample build, and after a disconnect.
    [ -s "$sigterm_csv" ] || echo "code,scenario,signal_at_ms,disconnect_at_ms,rss_at_signal_mib,exit_ms,status,load1,freed_after_disconnect_ms" \
        >"$sigterm_csv"
    local point over=0
    for point in "radiosity 5000" "area 4000" "area 6000 4000"; do
        # shellcheck disable=SC2086
        [ "$(sigterm_row $point)" = over ] && over=$((over + 1))
    done
    echo "hostile: SIGTERM to exit over ${sigterm_limit_ms} ms (or not clean) in $over of 3 (rows in $sigterm_csv)"
    [ "$over" -eq 0 ]
}

# Issue 27: the exact (LEMON) levels of a tree build stop within milliseconds of a cancel.
run_tree_cancel() {
    local bench=build/bin/tree_cancel_bench out=docs/bench/tree_cancel.csv
    [ -x "$bench" ] || { echo "build $bench first (cmake --build build --target tree_cancel_bench)" >&2; return 2; }
    [ -s "$out" ] || echo "code,lights,cancel_after_ms,outcome,latency_ms,full_build_ms" >"$out"
    timeout 600 "$bench" "$tree_lights" "$cancels" | sed "s/^/$label,/" | tee -a "$out"
}

run_soak() {
    make_scene 4096 "$work/soak.gltf"
    start_local_server "$server_bin" "$work" --threads 2 --quiet
    local port=$LC_SERVER_PORT
    mkdir -p "$(dirname "$csv")"
    sample_rss "$LC_SERVER_PID" "$csv" 2 &
    local sampler=$!
    local t_end=$(( $(date +%s) + minutes * 60 ))
    local loops=()
    for c in 0 1 2 3; do
        (
            ok=0 bad=0
            for ((b = 0; b < 1000000 && $(date +%s) < t_end; b++)); do
                if bake "$port" "$work/soak.gltf" "$work/soak_$c.lcut" "$b" 120 >/dev/null 2>&1; then
                    ok=$((ok + 1))
                else
                    bad=$((bad + 1))
                fi
            done
            echo "$ok $bad" >"$work/soak_$c.count"
        ) &
        loops+=($!)
    done
    background=("${loops[@]}" "$sampler")
    for pid in "${loops[@]}"; do wait "$pid" || true; done
    kill "$sampler" 2>/dev/null || true
    wait "$sampler" 2>/dev/null || true
    background=()
    local alive=yes
    kill -0 "$LC_SERVER_PID" 2>/dev/null || alive=no
    stop_server
    local ok=0 bad=0
    for c in 0 1 2 3; do
        read -r o b <"$work/soak_$c.count"
        ok=$((ok + o))
        bad=$((bad + b))
    done
    # RSS after the first minute (allocator warm-up) against the last minute.
    awk -F, -v ok="$ok" -v bad="$bad" -v alive="$alive" -v minutes="$minutes" -v csv="$csv" '
        NR > 1 { t = $1; r = $2; if (r > peak) peak = r
                 if (t >= 60 && t < 120) { early += r; ne++ }
                 last_t = t; rows[NR] = t "," r }
        END {
            for (i in rows) { split(rows[i], f, ","); if (f[1] >= last_t - 60) { late += f[2]; nl++ } }
            printf "soak: %d minutes, 4 clients, %d bakes of 4096 lights passed, %d failed, server %s; " \
                   "RSS mean 1-2 min %.0f KiB, last minute %.0f KiB, peak %d KiB (%s)\n",
                   minutes, ok, bad, alive == "yes" ? "alive" : "DIED",
                   ne ? early / ne : 0, nl ? late / nl : 0, peak, csv }' "$csv"
    [ "$bad" -eq 0 ] && [ "$alive" = yes ]
}

# Every server of the run logged into $work/server.log; a sanitizer build
# (cmake --preset asan, --server-bin build-asan/bin/lightmass_server) reports
# there, LeakSanitizer's at each clean stop. Any report fails the run.
check_sanitizer_reports() {
    [ -f "$work/server.log" ] || return 0
    local reports
    reports=$(grep -cE "ERROR: (Address|Leak)Sanitizer|runtime error:" "$work/server.log" || true)
    echo "sanitizer reports in the server's log: $reports"
    if [ "$reports" -gt 0 ]; then
        grep -m 5 -E "ERROR: |runtime error:" "$work/server.log"
        return 1
    fi
}

case "$mode" in
    kill) run_kill ;;
    stall) run_stall ;;
    soak) run_soak ;;
    hostile) run_hostile ;;
    tree-cancel) run_tree_cancel ;;
    sigterm) run_sigterm ;;
    footprint) run_footprint ;;
    all) run_kill; run_stall; minutes=10; run_soak ;;
    *) sed -n '2,35p' "$0"; exit 2 ;;
esac
check_sanitizer_reports
