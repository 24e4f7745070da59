#!/usr/bin/env bash
# A bake over MPI ranks: one scene (the furnished room, 64 point lights) with
# VPL_COUNT server-made VPL paths, baked with the LBVH builder in one process
# and over each rank count in RANKS. Writes docs/bench/mpi_ranks.csv:
#   ranks, vpl_paths, tree_lights, wall_ms, coordinator_peak_mb, rank, rank_lights, rank_bytes_sent, rank_peak_mb
# (one row per rank; ranks 0 is the in-process bake, with no rank rows) and
# checks that every rank count's tree is the in-process tree, byte for byte.
# Usage: scripts/bench-mpi.sh [build-dir]   env: VPL_COUNT (default 1000000), RANKS (default "1 2 4")
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"
bin="$build_dir/bin"
vpl_count="${VPL_COUNT:-1000000}"
ranks_list="${RANKS:-1 2 4}"
out=docs/bench/mpi_ranks.csv
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

"$bin/editor_client" make-scene furnished-room -o "$tmp/room.gltf" >/dev/null
"$bin/editor_client" add-lights "$tmp/room.gltf" --count 64 --layout random -o "$tmp/lit.gltf" >/dev/null
echo "ranks,vpl_paths,tree_lights,wall_ms,coordinator_peak_mb,rank,rank_lights,rank_bytes_sent,rank_peak_mb" > "$out"

for ranks in 0 $ranks_list; do
  # The coordinator under GNU time, so its own peak RSS is measured.
  /usr/bin/time -f "%M" -o "$tmp/server_rss" "$bin/lightmass_server" --port-file "$tmp/port" --quiet \
    --mpi-arg=--oversubscribe --mpi-arg=--mca --mpi-arg=btl --mpi-arg=self,tcp >/dev/null &
  timer=$!
  for _ in $(seq 100); do [[ -s "$tmp/port" ]] && break; sleep 0.1; done
  start=$(date +%s%N)
  "$bin/editor_client" bake "$tmp/lit.gltf" --server "127.0.0.1:$(cat "$tmp/port")" --builder lbvh \
    --indirect vpl --vpl-count "$vpl_count" --ranks "$ranks" -o "$tmp/tree$ranks.lcut" 2>/dev/null > "$tmp/bake$ranks.txt"
  wall_ms=$(( ($(date +%s%N) - start) / 1000000 ))
  # Stop the server itself (GNU time's child), so time writes its peak.
  kill -TERM "$(pgrep -P "$timer")"; wait "$timer" || true
  rm -f "$tmp/port"
  leaves=$(sed -n 's/^baked .* into \([0-9]*\) nodes.*/\1/p' "$tmp/bake$ranks.txt")
  coordinator_mb=$(( $(cat "$tmp/server_rss") / 1024 ))
  if [[ "$ranks" == 0 ]]; then
    echo "0,$vpl_count,$(( (leaves + 1) / 2 )),$wall_ms,$coordinator_mb,,,," >> "$out"
    continue
  fi
  cmp -s "$tmp/tree0.lcut" "$tmp/tree$ranks.lcut" || { echo "tree at $ranks ranks differs from the in-process tree" >&2; exit 1; }
  sed -n 's/^rank \([0-9]*\) lights \([0-9]*\) bytes_sent \([0-9]*\) peak_rss_kb \([0-9]*\)$/\1 \2 \3 \4/p' "$tmp/bake$ranks.txt" |
    while read -r rank lights sent rss; do
      echo "$ranks,$vpl_count,$(( (leaves + 1) / 2 )),$wall_ms,$coordinator_mb,$rank,$lights,$sent,$(( rss / 1024 ))" >> "$out"
    done
done
cat "$out"
