#!/usr/bin/env bash
# Adds Khronos' validation layer to the device bundle (.gpu/, made by
# ../shared/tools/gpu-bundle.sh, which packs the Vulkan loader but no layer),
# so that scripts/tools/gpu_check.sh's --validation runs really validate on NVIDIA's
# driver: .gpu/validation.tar.xz holds the stripped layer and its manifest
# (library_path beside it); scripts/bench/gpu.sh unpacks it and points
# VK_LAYER_PATH at it. Run after gpu-bundle.sh:
#   bash ../shared/tools/gpu-bundle.sh && bash scripts/tools/gpu_pack_validation.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
[[ -d .gpu ]] || { echo "tools/gpu_pack_validation.sh: no .gpu/ folder: run ../shared/tools/gpu-bundle.sh first" >&2; exit 1; }
manifest=/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json
library=$(ldconfig -p | awk '/libVkLayer_khronos_validation.so/ {print $NF; exit}')
[[ -f "$manifest" && -n "$library" ]] ||
  { echo "tools/gpu_pack_validation.sh: the validation layer is not installed (apt-get install vulkan-validationlayers)" >&2; exit 1; }
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
strip -o "$stage/libVkLayer_khronos_validation.so" "$library"
python3 - "$manifest" "$stage/VkLayer_khronos_validation.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["layer"]["library_path"] = "./libVkLayer_khronos_validation.so"  # relative to the manifest
json.dump(m, open(sys.argv[2], "w"), indent=1)
PY
tar -C "$stage" -cf - . | xz -6 -T0 > .gpu/validation.tar.xz
du -sh .gpu/validation.tar.xz
