#!/usr/bin/env bash
# A bake over MPI ranks: one scene (the furnished room, 64 point lights) with
# its bounced light made on the server, baked with the LBVH builder in one
# process and over each rank count in RANKS, checking that every rank count's
# tree is the in-process tree, byte for byte. One row per rank (ranks 0 is the
# in-process bake, with no rank rows):
#   INDIRECT=vpl (default): VPL_COUNT light paths -> docs/bench/mpi_ranks.csv
#     ranks, vpl_paths, tree_lights, wall_ms, coordinator_peak_mb, rank, rank_lights, rank_bytes_sent, rank_peak_mb
#   INDIRECT=radiosity: patches of PATCH_SIZE, TOLERANCE -> docs/bench/mpi_radiosity.csv
#     the same columns with patch_size in place of vpl_paths
# IN_PROCESS=0 leaves the in-process bake out (above 2^22 VPLs one process
# refuses the bake): every rank count's tree is then checked against the first
# rank count's (an LBVH is the same tree at any rank count).
# Usage: scripts/bench/mpi.sh [build-dir]
#   env: INDIRECT, VPL_COUNT (default 1000000), PATCH_SIZE (0.1), TOLERANCE (0.05), RANKS (default "1 2 4"),
#        IN_PROCESS (default 1), OUT (the CSV; default by INDIRECT)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
bin="$build_dir/bin"
indirect="${INDIRECT:-vpl}"
vpl_count="${VPL_COUNT:-1000000}"
patch_size="${PATCH_SIZE:-0.1}"
tolerance="${TOLERANCE:-0.05}"
ranks_list="${RANKS:-1 2 4}"
case "$indirect" in
  vpl) out=docs/bench/mpi_ranks.csv; work=vpl_paths; amount="$vpl_count"
       bake_args=(--indirect vpl --vpl-count "$vpl_count") ;;
  radiosity) out=docs/bench/mpi_radiosity.csv; work=patch_size; amount="$patch_size"
       bake_args=(--indirect radiosity --patch-size "$patch_size" --tolerance "$tolerance") ;;
  *) echo "INDIRECT must be vpl or radiosity, not '$indirect'" >&2; exit 2 ;;
esac
out="${OUT:-$out}"
in_process="${IN_PROCESS:-1}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

"$bin/editor_client" make-scene furnished-room -o "$tmp/room.gltf" >/dev/null
"$bin/editor_client" add-lights "$tmp/room.gltf" --count 64 --layout random -o "$tmp/lit.gltf" >/dev/null
echo "ranks,$work,tree_lights,wall_ms,coordinator_peak_mb,rank,rank_lights,rank_bytes_sent,rank_peak_mb" > "$out"

first=""
for ranks in $([[ "$in_process" == 1 ]] && echo 0) $ranks_list; do
  first="${first:-$ranks}"
  # The coordinator's own peak RSS is its VmHWM, read before it stops (GNU time's
  # figure would be the largest of it and the ranks it reaped through mpirun).
  "$bin/lightmass_server" --port-file "$tmp/port" --quiet \
    --mpi-arg=--oversubscribe --mpi-arg=--mca --mpi-arg=btl --mpi-arg="${BTL:-self,tcp}" \
    --mpi-arg=--mca --mpi-arg=mpi_yield_when_idle --mpi-arg=1 --mpi-arg=--bind-to --mpi-arg=none >/dev/null &
  server=$!
  for _ in $(seq 100); do [[ -s "$tmp/port" ]] && break; sleep 0.1; done
  start=$(date +%s%N)
  "$bin/editor_client" bake "$tmp/lit.gltf" --server "127.0.0.1:$(cat "$tmp/port")" --builder lbvh \
    "${bake_args[@]}" --ranks "$ranks" -o "$tmp/tree$ranks.lcut" 2>/dev/null > "$tmp/bake$ranks.txt"
  wall_ms=$(( ($(date +%s%N) - start) / 1000000 ))
  grep -m1 "indirect:" "$tmp/bake$ranks.txt" >&2 || true
  grep -m1 "^lbvh over" "$tmp/bake$ranks.txt" >&2 || true
  coordinator_mb=$(( $(awk '/^VmHWM:/ {print $2}' "/proc/$server/status") / 1024 ))
  kill -TERM "$server"; wait "$server" || true
  rm -f "$tmp/port"
  leaves=$(sed -n 's/^baked .* into \([0-9]*\) nodes.*/\1/p' "$tmp/bake$ranks.txt")
  # Hashes, not the files: a 2^24-light tree is 6 GB.
  sha256sum < "$tmp/tree$ranks.lcut" > "$tmp/tree$ranks.sha"
  rm -f "$tmp/tree$ranks.lcut"
  echo "tree at $ranks ranks: sha256 $(cut -c1-16 "$tmp/tree$ranks.sha")" >&2
  if [[ "$ranks" == 0 ]]; then
    echo "0,$amount,$(( (leaves + 1) / 2 )),$wall_ms,$coordinator_mb,,,," >> "$out"
    continue
  fi
  cmp -s "$tmp/tree$first.sha" "$tmp/tree$ranks.sha" ||
    { echo "tree at $ranks ranks differs from the tree at $first ranks (0: in process)" >&2; exit 1; }
  sed -n 's/^rank \([0-9]*\) lights \([0-9]*\) bytes_sent \([0-9]*\) peak_rss_kb \([0-9]*\)$/\1 \2 \3 \4/p' "$tmp/bake$ranks.txt" |
    while read -r rank lights sent rss; do
      echo "$ranks,$amount,$(( (leaves + 1) / 2 )),$wall_ms,$coordinator_mb,$rank,$lights,$sent,$(( rss / 1024 ))" >> "$out"
    done
done
cat "$out"
