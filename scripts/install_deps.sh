#!/usr/bin/env bash
# Installs every Debian 12 package the project needs, build and test alike.
# Idempotent: apt-get skips what is present. The README and .ci/run both call this.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config git
  # fuzzing (preset "fuzz"): clang with its libFuzzer runtime
  clang libclang-rt-14-dev
  # libraries
  libglm-dev libboost-dev libssl-dev
  libflatbuffers-dev flatbuffers-compiler
  liblemon-dev libtinygltf-dev libtbb-dev libembree-dev
  libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libsimdjson-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # render -o IMAGE.exr, and exrheader for its test
  libopenexr-dev openexr
  # bakes over MPI ranks (lightmass_rank, mpirun in the tests)
  openmpi-bin libopenmpi-dev
  # Vulkan on the CPU (lavapipe), shaders, window
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools spirv-cross libglfw3-dev libimgui-dev
  # headless window tests, plots, test certificates for TLS
  xvfb xauth python3-matplotlib python3-numpy openssl
  # scripts/tools/long_functions.sh (function lengths for review)
  universal-ctags
)

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
