#!/usr/bin/env bash
# A bake over several hosts on one machine (issue 42): HOSTS network-namespace
# hosts (scripts/tools/netns_hosts.sh) with RANKS_PER_HOST ranks each, the
# furnished room's 64 lights with VPL_COUNT light paths bounced on the server
# (about 0.98 lights a path), LBVH builder. The server and the client run in
# host 1, the host file names every host; the tree over the ranks must be the
# in-process tree, byte for byte. One CSV row for the in-process bake (ranks 0)
# and one per rank:
#   ranks,hosts,vpl_paths,tree_lights,wall_ms,coordinator_peak_mb,rank,rank_lights,rank_bytes_sent,rank_peak_mb
# Root only. The namespaces are removed on every exit.
# Usage: scripts/bench/hosts.sh [build-dir]
#   env: VPL_COUNT (default 1000000), HOSTS (3), RANKS_PER_HOST (2), OUT (docs/bench/hosts.csv)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin="$(cd "${1:-build}" && pwd)/bin"
vpl_count="${VPL_COUNT:-1000000}"
host_count="${HOSTS:-3}"
per_host="${RANKS_PER_HOST:-2}"
out="${OUT:-docs/bench/hosts.csv}"
hosts_tool="$PWD/scripts/tools/netns_hosts.sh"
export LC_NETNS_PREFIX="lc$$b" LC_NETNS_SUBNET="10.213.43"  # names of this run alone
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
tmp="$(mktemp -d)"
trap '"$hosts_tool" down "$host_count"; rm -rf "$tmp"' EXIT
"$hosts_tool" up "$host_count"
h1="${LC_NETNS_PREFIX}1"
for i in $(seq "$host_count"); do echo "$LC_NETNS_PREFIX$i slots=$per_host"; done > "$tmp/hosts.txt"
mkdir "$tmp/jobs"
mapfile -t mpi_args < <("$hosts_tool" mpi-args)

"$bin/editor_client" make-scene furnished-room -o "$tmp/room.gltf" >/dev/null
"$bin/editor_client" add-lights "$tmp/room.gltf" --count 64 --layout random -o "$tmp/lit.gltf" >/dev/null
echo "ranks,hosts,vpl_paths,tree_lights,wall_ms,coordinator_peak_mb,rank,rank_lights,rank_bytes_sent,rank_peak_mb" > "$out"

for ranks in 0 $((host_count * per_host)); do
  "$hosts_tool" exec "$h1" "$bin/lightmass_server" --port-file "$tmp/port" --quiet \
    --mpi-hostfile "$tmp/hosts.txt" --mpi-work-dir "$tmp/jobs" "${mpi_args[@]/#/--mpi-arg=}" >/dev/null 2>&1 &
  server=$!
  for _ in $(seq 100); do [[ -s "$tmp/port" ]] && break; sleep 0.1; done
  start=$(date +%s%N)
  "$hosts_tool" exec "$h1" "$bin/editor_client" bake "$tmp/lit.gltf" --server "127.0.0.1:$(cat "$tmp/port")" \
    --builder lbvh --indirect vpl --vpl-count "$vpl_count" --ranks "$ranks" -o "$tmp/tree$ranks.lcut" \
    2>/dev/null > "$tmp/bake$ranks.txt"
  wall_ms=$(( ($(date +%s%N) - start) / 1000000 ))
  coordinator_mb=$(( $(awk '/^VmHWM:/ {print $2}' "/proc/$server/status") / 1024 ))
  kill -TERM "$server"; wait "$server" || true
  rm -f "$tmp/port"
  leaves=$(sed -n 's/^baked .* into \([0-9]*\) nodes.*/\1/p' "$tmp/bake$ranks.txt")
  lights=$(( (leaves + 1) / 2 ))
  if [[ "$ranks" == 0 ]]; then
    echo "0,1,$vpl_count,$lights,$wall_ms,$coordinator_mb,,,," >> "$out"
    continue
  fi
  cmp -s "$tmp/tree0.lcut" "$tmp/tree$ranks.lcut" ||
    { echo "the tree over $ranks ranks on $host_count hosts differs from the in-process tree" >&2; exit 1; }
  echo "tree over $ranks ranks on $host_count hosts: the in-process tree, $(stat -c %s "$tmp/tree0.lcut") bytes" >&2
  sed -n 's/^rank \([0-9]*\) lights \([0-9]*\) bytes_sent \([0-9]*\) peak_rss_kb \([0-9]*\)$/\1 \2 \3 \4/p' "$tmp/bake$ranks.txt" |
    while read -r rank rank_lights sent rss; do
      echo "$ranks,$host_count,$vpl_count,$lights,$wall_ms,$coordinator_mb,$rank,$rank_lights,$sent,$(( rss / 1024 ))" >> "$out"
    done
done
cat "$out"
