#!/usr/bin/env bash
# The whole pipeline against the light count: 2^10, 2^12, ..., 2^20 point lights
# through the empty room (add-lights --layout random), and 2^22 with --huge.
# Per count, one run each:
#   - `bake` end to end against a lightmass_server started apart (both under
#     /usr/bin/time -v, so each peak RSS is its own process's), once per builder
#     (agglomerative, lbvh), with the parts from `bake --json`: load, upload,
#     build, download (the stream), write (the dump), import (the tree store);
#   - `render --tree` (the agglomerative tree) at 256x256, lightcuts with the
#     bound criterion: wall clock of the process, GPU time of the frame, peak RSS.
# Writes docs/bench/scale.csv and docs/bench/scale.png (/usr/bin/python3 with
# Debian's matplotlib).
# Usage: scripts/bench/scale.sh [--huge] [--build-dir DIR] [--max-log2 K]
#   --huge        adds 2^22 lights (writes a 2.9 GB glTF; the client peaked at
#                 1.6 GB, the server at 3.5 GB, render at 3.5 GB in session 8)
#   --max-log2 K  stops at 2^K lights (a quick run: --max-log2 14)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir=build
huge=0
max_log2=20
while [[ $# -gt 0 ]]; do
  case "$1" in
    --huge) huge=1 ;;
    --build-dir) build_dir="$2"; shift ;;
    --max-log2) max_log2="$2"; shift ;;
    *) echo "unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build_dir" --target editor_client lightmass_server -j "$(nproc)"
client="$build_dir/bin/editor_client"
server_bin="$build_dir/bin/lightmass_server"
out=docs/bench/scale.csv
mkdir -p docs/bench
work="$(mktemp -d)"
server_pid=""
stop_server() {  # SIGTERM to the server under /usr/bin/time, so time writes its report
  if [[ -n "$server_pid" ]]; then
    pkill -TERM -P "$server_pid" 2>/dev/null || true
    wait "$server_pid" 2>/dev/null || true
    server_pid=""
  fi
}
trap 'stop_server; rm -rf "$work"' EXIT

# Peak RSS in MiB from a /usr/bin/time -v report.
peak_mb() { awk -F': ' '/Maximum resident set size/ {printf "%.1f", $2 / 1024}' "$1"; }
# Elapsed wall clock in seconds from a /usr/bin/time -v report (h:mm:ss or m:ss.ss).
wall_s() {
  awk -F': ' '/Elapsed \(wall clock\)/ {
    n = split($2, p, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + p[i]; printf "%.3f", s }' "$1"
}
json_field() {  # one number from a JSON file, to 0.1
  /usr/bin/python3 -c "import json,sys; print('%.1f' % json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"
}

# One bake through a fresh server (its peak RSS is this bake's alone).
bake_once() {  # scene builder tag
  local scene=$1 builder=$2 tag=$3
  rm -f "$work/port"
  /usr/bin/time -v -o "$work/$tag.server.time" "$server_bin" --listen 127.0.0.1:0 \
    --port-file "$work/port" --threads "$(nproc)" --quiet --memory-budget-mb 16384 \
    >"$work/$tag.server.log" 2>&1 &
  server_pid=$!
  for _ in $(seq 1 200); do [[ -s "$work/port" ]] && break; sleep 0.05; done
  [[ -s "$work/port" ]] || { cat "$work/$tag.server.log"; exit 1; }
  /usr/bin/time -v -o "$work/$tag.client.time" "$client" bake "$scene" \
    --server "127.0.0.1:$(cat "$work/port")" --builder "$builder" -o "$work/$tag.lcut" --json \
    >"$work/$tag.json" 2>"$work/$tag.client.log" || { cat "$work/$tag.client.log"; exit 1; }
  stop_server
}

header="lights,gltf_mb,bake_wall_s,load_ms,upload_ms,build_agglomerative_ms,download_ms,write_ms,import_ms,bake_network_ms,client_peak_mb,server_peak_mb,bake_wall_lbvh_s,build_lbvh_ms,render_wall_s,render_gpu_ms,render_peak_mb"
# Appended after every count: a failure at 2^22 keeps the rows before it.
echo "$header" >"$out"
counts=()
for k in $(seq 10 2 "$max_log2"); do counts+=("$k"); done
if [[ "$huge" == 1 ]]; then counts+=(22); fi

for k in "${counts[@]}"; do
  lights=$((1 << k))
  scene="$work/scene_$k.gltf"
  # 819.2 cd in total whatever the count, as in bench-bound.sh.
  intensity="$(/usr/bin/python3 -c "print(819.2 / $lights)")"
  echo "== $lights lights" >&2
  "$client" add-lights --count "$lights" --layout random --type point \
    --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity "$intensity" --range 0 -o "$scene" >/dev/null
  gltf_mb="$(du -b "$scene"* | awk '{s += $1} END {printf "%.1f", s / 1048576}')"

  bake_once "$scene" lbvh "lbvh_$k"
  lbvh_build_ms="$(json_field "$work/lbvh_$k.json" build_ms)"
  lbvh_wall="$(wall_s "$work/lbvh_$k.client.time")"
  rm -f "$work/lbvh_$k.lcut"

  tag="agglo_$k"
  bake_once "$scene" agglomerative "$tag"
  j="$work/$tag.json"
  bake_wall="$(wall_s "$work/$tag.client.time")"
  client_peak="$(peak_mb "$work/$tag.client.time")"
  server_peak="$(peak_mb "$work/$tag.server.time")"

  LC_VALIDATION=0 /usr/bin/time -v -o "$work/render_$k.time" "$client" render "$scene" \
    --tree "$work/$tag.lcut" --mode lightcuts --criterion bound --size 256x256 \
    -o "$work/render_$k.png" --stats "$work/render_$k.json" >"$work/render_$k.log" 2>&1 ||
    { cat "$work/render_$k.log"; exit 1; }
  render_wall="$(wall_s "$work/render_$k.time")"
  render_gpu_ms="$(json_field "$work/render_$k.json" render_ms)"
  render_peak="$(peak_mb "$work/render_$k.time")"

  echo "$lights,$gltf_mb,$bake_wall,$(json_field "$j" load_ms),$(json_field "$j" upload_ms),$(json_field "$j" build_ms),$(json_field "$j" download_ms),$(json_field "$j" write_ms),$(json_field "$j" import_ms),$(json_field "$j" total_ms),$client_peak,$server_peak,$lbvh_wall,$lbvh_build_ms,$render_wall,$render_gpu_ms,$render_peak" \
    | tee -a "$out" >&2
  rm -f "$scene"* "$work/$tag.lcut"
done

cat "$out"
/usr/bin/python3 scripts/bench/plot_scale.py "$out" docs/bench/scale.png
