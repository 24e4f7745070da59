#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, runs every test.
#   scripts/test.sh          default build (RelWithDebInfo), full suite
#   scripts/test.sh --asan   AddressSanitizer + UBSan build, full suite
# Both then build the fuzz preset and run each libFuzzer target for a fixed
# 20,000 executions from its seeds (CTest entries fuzz.*; scripts/fuzz.sh runs them long).
set -euo pipefail
cd "$(dirname "$0")/.."
preset=default
if [ "${1:-}" = "--asan" ]; then preset=asan; fi

bash scripts/install_deps.sh
bash scripts/build.sh "$preset"
# Vulkan validation layers are enabled for every test (tests/CMakeLists.txt).
ctest --preset "$preset" -j 2 --timeout 600

cmake --preset fuzz >/dev/null
cmake --build build-fuzz -j 2
ctest --preset fuzz -j 2 --timeout 600
