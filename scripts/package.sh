#!/usr/bin/env bash
# Builds the Debian package: build/lightcuts_VERSION_ARCH.deb (CPack, cmake/LightcutsPackaging.cmake),
# with the programs, the MPI rank program, the service and the docs, and its dependencies declared.
# Install it with `sudo apt install ./build/lightcuts_*.deb` (docs/OPERATING.md).
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(lightmass_server editor_client)
cmake --preset default > /dev/null
# lightmass_rank is a target only where CMake found MPI.
ninja -C build -t query lightmass_rank > /dev/null 2>&1 && targets+=(lightmass_rank)
bash scripts/build.sh default "${targets[@]}"
(cd build && cpack -G DEB)
ls -l build/lightcuts_*.deb
