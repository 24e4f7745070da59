# Shared by scripts/load_test.sh and scripts/fault_test.sh (sourced, not run).

# start_local_server BIN DIR [SERVER ARGS...]: starts BIN on 127.0.0.1 (any
# free port) and waits up to 20 s for its port file. Sets LC_SERVER_PID and
# LC_SERVER_PORT; returns non-zero when the server did not come up.
start_local_server() {
    local bin=$1 dir=$2
    shift 2
    local port_file="$dir/port.$RANDOM$RANDOM"
    rm -f "$port_file"
    "$bin" --listen 127.0.0.1:0 --port-file "$port_file" "$@" >>"$dir/server.log" 2>&1 &
    LC_SERVER_PID=$!
    for _ in $(seq 1 200); do
        if [ -s "$port_file" ]; then
            LC_SERVER_PORT=$(cat "$port_file")
            return 0
        fi
        kill -0 "$LC_SERVER_PID" 2>/dev/null || break
        sleep 0.1
    done
    echo "lightmass_server did not start (see $dir/server.log)" >&2
    return 1
}

# sample_rss PID CSV INTERVAL_S: writes "seconds,rss_kib" rows from
# /proc/PID/status until the process is gone (at most 100,000 samples).
sample_rss() {
    local pid=$1 csv=$2 interval=$3 start
    start=$(date +%s.%N)
    echo "seconds,rss_kib" >"$csv"
    for _ in $(seq 1 100000); do
        local rss
        rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$pid/status" 2>/dev/null) || break
        [ -n "$rss" ] || break
        awk -v s="$start" -v now="$(date +%s.%N)" -v r="$rss" 'BEGIN { printf "%.1f,%d\n", now - s, r }' >>"$csv"
        sleep "$interval"
    done
}
