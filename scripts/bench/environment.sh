#!/usr/bin/env bash
# Environment sampling plus tree build (tests/benchmarks/environment_sampling_bench):
# a Preetham sun and sky and a 2048 x 1024 HDR map as 10^4, 10^5 and 10^6
# directional lights; writes docs/bench/environment_sampling.csv:
#   source, lights, builder, sample_ms, build_ms, nodes
# Usage: scripts/bench/environment.sh [build-dir] [largest light count]
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${1:-build}"
cmake --build "$build_dir" --target environment_sampling_bench -j "$(nproc)"
mkdir -p docs/bench
"$build_dir/bin/environment_sampling_bench" "${2:-1000000}" | tee docs/bench/environment_sampling.csv
/usr/bin/python3 scripts/bench/plot_environment_bench.py docs/bench/environment_sampling.csv
