#!/usr/bin/env bash
# Before/after benchmark for a refactoring: runs the same cases with two builds'
# binaries in ONE run, alternating before and after in each round so that the
# machine's noise falls on both alike, and writes docs/bench/before_after.csv:
#   case, build, round, metric, value
# Cases: tree builds (tree_build_bench: agglomerative 65,536, optimal-pair
# 4,096, lbvh 65,536), the result stream (stream_throughput_bench), reference
# throughput (render_throughput_bench, 512x512, 16,384 lights), a bake end to end (spawned
# server), and the furnished room (shadow rays, glossy) with 4,096 lights at
# 128x128 in every lighting mode: reference, bound walk, bound heap, radius.
# Usage: scripts/bench/before_after.sh BEFORE_BIN_DIR AFTER_BIN_DIR [rounds]
set -euo pipefail
cd "$(dirname "$0")/../.."
before="$(realpath "$1")"
after="$(realpath "$2")"
rounds="${3:-2}"
out=docs/bench/before_after.csv
mkdir -p docs/bench
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export LC_VALIDATION=0  # the benchmark measures the programs, not the validation layers

# One scene for every render case, made by the "before" build so that both
# builds render the same bytes.
"$before/editor_client" make-scene furnished-room -o "$work/room.gltf" >/dev/null
"$before/editor_client" add-lights "$work/room.gltf" --count 4096 --layout random --type point \
  --box -4.7,0.3,-4.7,4.7,2.7,4.7 --intensity 0.2 --range 0 --seed 7 -o "$work/lit.gltf" >/dev/null
# Each build bakes its own copy of the tree: a dump carries its build's schema hash,
# and a build refuses another schema's dump (the trees' payloads are the same).
for build in before after; do
  bin=$before
  [[ $build == after ]] && bin=$after
  "$bin/editor_client" bake "$work/lit.gltf" --spawn-server --builder agglomerative \
    -o "$work/lit.$build.lcut" >/dev/null
done

row() { echo "$1,$2,$3,$4,$5" >>"$work/rows.csv"; }

bench_json() {  # case build round binary filter
  local json="$work/b.json"
  "$4" --benchmark_filter="$5" --benchmark_out="$json" --benchmark_out_format=json >/dev/null 2>&1
  python3 - "$json" "$1" "$2" "$3" >>"$work/rows.csv" <<'PY'
import json, sys
path, case, build, rnd = sys.argv[1:5]
for b in json.load(open(path))["benchmarks"]:
    name = b["name"].replace(",", ";")
    print(f"{case}:{name},{build},{rnd},real_ms,{b['real_time'] * {'ns': 1e-6, 'us': 1e-3, 'ms': 1.0, 's': 1e3}[b['time_unit']]:.3f}")
    for key in ("bytes_per_second", "evals_per_s", "lighting_gpu_ms"):
        if key in b:
            print(f"{case}:{name},{build},{rnd},{key},{b[key]:.6g}")
PY
}

render_case() {  # case build round binary extra-args...
  local case=$1 build=$2 rnd=$3 bin=$4
  shift 4
  "$bin/editor_client" render "$work/lit.gltf" --tree "$work/lit.$build.lcut" --size 128x128 \
    --exposure 0.03 -o "$work/$case.$build.png" --stats "$work/s.json" "$@" >/dev/null 2>&1
  python3 - "$work/s.json" "$case" "$build" "$rnd" >>"$work/rows.csv" <<'PY'
import json, sys
stats, case, build, rnd = json.load(open(sys.argv[1])), *sys.argv[2:5]
for key in ("lighting_ms", "gbuffer_ms", "avg_cut", "shadow_rays"):
    if key in stats:
        print(f"{case},{build},{rnd},{key},{stats[key]}")
PY
}

for rnd in $(seq 1 "$rounds"); do
  for build in before after; do
    bin=$before
    [[ $build == after ]] && bin=$after
    echo "round $rnd: $build" >&2
    bench_json tree_build "$build" "$rnd" "$bin/tree_build_bench" \
      '^(agglomerative/65536|optimal_pair_exact/4096|lbvh/65536)/'
    "$bin/stream_throughput_bench" 1000000 >"$work/stream.csv"
    python3 - "$work/stream.csv" "$build" "$rnd" >>"$work/rows.csv" <<'PY'
import csv, sys
path, build, rnd = sys.argv[1:4]
for r in csv.DictReader(open(path)):
    for key in ("protocol_ms", "protocol_mb_s", "raw_mb_s", "peak_rss_mb"):
        print(f"stream:{r['records']},{build},{rnd},{key},{r[key]}")
PY
    bench_json reference_throughput "$build" "$rnd" "$bin/render_throughput_bench" 'ReferenceLightingPass/16384'
    start=$(date +%s.%N)
    "$bin/editor_client" bake "$work/lit.gltf" --spawn-server --builder agglomerative \
      -o "$work/again.lcut" >/dev/null
    row bake_end_to_end "$build" "$rnd" wall_ms "$(python3 -c "import time; print(round((time.time() - $start) * 1e3, 1))")"
    render_case reference "$build" "$rnd" "$bin" --mode reference
    render_case bound_walk "$build" "$rnd" "$bin" --mode lightcuts --criterion bound --bound-search walk --reconstruction 0  # the cut per pixel, as builds before s18 made it
    render_case bound_heap "$build" "$rnd" "$bin" --mode lightcuts --criterion bound --bound-search heap
    render_case radius "$build" "$rnd" "$bin" --mode lightcuts --criterion radius
  done
done
{
  echo "case,build,round,metric,value"
  cat "$work/rows.csv"
} >"$out"
# Median of the rounds, before against after.
python3 - "$out" <<'PY'
import csv, statistics, sys
from collections import defaultdict
values = defaultdict(list)
for r in csv.DictReader(open(sys.argv[1])):
    values[(r["case"], r["metric"], r["build"])].append(float(r["value"]))
print(f"{'case':58} {'metric':16} {'before':>12} {'after':>12} {'after/before':>12}")
for (case, metric) in sorted({(c, m) for c, m, _ in values}):
    b = statistics.median(values.get((case, metric, "before"), [float("nan")]))
    a = statistics.median(values.get((case, metric, "after"), [float("nan")]))
    ratio = a / b if b else float("nan")
    print(f"{case:58} {metric:16} {b:12.4g} {a:12.4g} {ratio:12.3f}")
PY
