#!/usr/bin/env bash
# Area-light benchmark (issue 15): sampling plus tree build for 10^4, 10^5 and
# 10^6 area lights (tests/benchmarks/area_light_bench, one case per process),
# then the emissive Cornell box (make-scene cornell-emissive, every light from
# its ceiling panel) rendered in lightcuts at E = 0.02 and 0.005 against the
# reference. Writes docs/bench/area_lights_build.csv,
# docs/bench/area_lights_cornell.csv and docs/images/area_lights.png.
# Usage: scripts/bench/area_lights.sh [build-dir]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
cmake --build "$build_dir" --target area_light_bench lightmass_server editor_client -j "$(nproc)"
bin="$build_dir/bin"
mkdir -p docs/bench docs/images
tmp="$(mktemp -d)"
trap 'kill "$server_pid" 2>/dev/null || true; rm -rf "$tmp"' EXIT
server_pid=

for name in $("$bin/area_light_bench" --benchmark_list_tests); do
  echo "running $name" >&2
  "$bin/area_light_bench" --benchmark_filter="^${name}\$" --benchmark_format=json \
    > "$tmp/$(echo "$name" | tr '/:' '__').json"
done
python3 - "$tmp" docs/bench/area_lights_build.csv <<'PY'
import csv, glob, json, sys
rows = []
for path in sorted(glob.glob(sys.argv[1] + "/*.json")):
    for b in json.load(open(path))["benchmarks"]:
        if b.get("error_occurred"):
            sys.exit("benchmark %s failed: %s" % (b["name"], b.get("error_message")))
        rows.append([b["name"].split("/")[0], int(b["samples"]), int(b["triangles"]),
                     "%.2f" % b["sample_ms"], "%.2f" % b["build_ms"]])
rows.sort(key=lambda r: (r[0], r[1]))
with open(sys.argv[2], "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["builder", "samples", "emissive_triangles", "sample_ms", "build_ms"])
    w.writerows(rows)
print("wrote", sys.argv[2])
PY

"$bin/lightmass_server" --listen 127.0.0.1:0 --port-file "$tmp/port" --threads 2 > "$tmp/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 1 100); do [ -s "$tmp/port" ] && break; sleep 0.1; done
"$bin/editor_client" make-scene cornell-emissive -o "$tmp/cornell.gltf"
"$bin/editor_client" bake "$tmp/cornell.gltf" --server "127.0.0.1:$(cat "$tmp/port")" \
    --builder agglomerative -o "$tmp/cornell.lcut" > /dev/null
"$bin/editor_client" render "$tmp/cornell.gltf" --tree "$tmp/cornell.lcut" --size 256x256 \
    --reconstruction off --sweep-error 0.02,0.005 --sweep-csv docs/bench/area_lights_cornell.csv -o "$tmp/cornell.png"

# Debian's interpreter has matplotlib (SPEC §10: the python3 on PATH may not).
/usr/bin/python3 - docs/bench/area_lights_build.csv docs/images/area_lights.png <<'PY'
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
rows = list(csv.DictReader(open(sys.argv[1])))
fig, ax = plt.subplots(figsize=(6, 4))
for builder in sorted({r["builder"] for r in rows}):
    mine = [r for r in rows if r["builder"] == builder]
    n = [int(r["samples"]) for r in mine]
    ax.loglog(n, [float(r["build_ms"]) for r in mine], "o-", label=builder + " build")
    if builder == "agglomerative":
        ax.loglog(n, [float(r["sample_ms"]) for r in mine], "s--", label="sampling")
ax.set_xlabel("area lights (oriented point lights)")
ax.set_ylabel("ms")
ax.set_title("Area lights from 8,192 emissive triangles")
ax.grid(True, which="both", alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=100)
print("wrote", sys.argv[2])
PY
cat docs/bench/area_lights_cornell.csv
