#!/usr/bin/env bash
# Result-channel streaming vs a raw loopback copy, 10^5 and 10^6 records.
# Writes docs/bench/streaming.csv.
set -euo pipefail
cd "$(dirname "$0")/../.."
[ -x build/bin/stream_throughput_bench ] || bash scripts/build.sh default
mkdir -p docs/bench
build/bin/stream_throughput_bench 100000 1000000 | tee docs/bench/streaming.csv
