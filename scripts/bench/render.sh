#!/usr/bin/env bash
# Reference-mode GPU throughput: builds tests/benchmarks/render_throughput_bench,
# runs it (the renderer's lighting pass and a minimal light-loop kernel, 512x512,
# 1,024 and 16,384 point lights, in one process on one device) and writes
# docs/bench/render_throughput.csv:
#   kernel, lights, pixels, wall_ms, evals_per_s, fraction_of_minimal, lighting_gpu_ms
# wall_ms is submit-to-completion on the CPU clock (for the renderer: the whole
# frame, G-buffer and tone mapping included, so its rate is a lower bound);
# fraction_of_minimal is the renderer's rate over the minimal kernel's at the
# same light count (the target is >= 0.5). lighting_gpu_ms is the renderer's
# lighting pass by GPU timestamps; the minimal kernel's timestamps are left out
# because lavapipe takes them lazily after a renderer frame (see the bench).
# Usage: scripts/bench/render.sh [build-dir]   (default: build, the default preset)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build_dir" --target render_throughput_bench -j "$(nproc)"
out=docs/bench/render_throughput.csv
mkdir -p docs/bench
tmp="$(mktemp)"
trap 'rm -f "$tmp"' EXIT

# Validation would slow the GPU work down; the benchmark measures the renderer alone.
LC_VALIDATION=0 "$build_dir/bin/render_throughput_bench" --benchmark_out="$tmp" \
  --benchmark_out_format=json

python3 - "$tmp" "$out" <<'PY'
import csv, json, sys
src, out = sys.argv[1], sys.argv[2]
with open(src) as f:
    report = json.load(f)
rows, minimal = [], {}
for b in report["benchmarks"]:
    if b.get("error_occurred"):
        sys.exit("benchmark %s failed: %s" % (b["name"], b.get("error_message")))
    kernel = "minimal_light_loop" if b["name"].startswith("BM_MinimalLightLoop") else "reference_lighting_pass"
    lights = int(b["lights"])
    if kernel == "minimal_light_loop":
        minimal[lights] = b["evals_per_s"]
    gpu = "%.1f" % b["lighting_ms"] if kernel == "reference_lighting_pass" else ""
    rows.append([kernel, lights, int(b["pixels"]), b["wall_ms"], b["evals_per_s"], gpu])
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["kernel", "lights", "pixels", "wall_ms", "evals_per_s", "fraction_of_minimal",
                "lighting_gpu_ms"])
    for kernel, lights, pixels, wall, rate, gpu in rows:
        w.writerow([kernel, lights, pixels, "%.1f" % wall, "%.4g" % rate,
                    "%.3f" % (rate / minimal[lights]) if lights in minimal else "", gpu])
print("wrote", out, "on", report["context"].get("host_name", "?"))
PY
cat "$out"
