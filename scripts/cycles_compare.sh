#!/usr/bin/env bash
# Our renders of a glTF scene against Blender's Cycles (docs/ACCURACY.md, "Against an
# independent path tracer"): direct light, and with --indirect the bounced part alone
# (all bounces minus direct) for VPL and radiosity at their defaults.
#
#   scripts/cycles_compare.sh SCENE.gltf --camera ex,ey,ez,tx,ty,tz,fovy [--size 64x64]
#       [--indirect] [--samples N] [--bounces B] [--out DIR] [--build DIR]
#
# Needs Debian's blender (apt-get install blender) and a build (scripts/build.sh). Writes
# DIR/{cycles,ours}_*.pfm, the comparisons' PNGs, and prints one line per comparison.
set -euo pipefail

usage() { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit "${1:-2}"; }
root=$(cd "$(dirname "$0")/.." && pwd)
scene="" camera="" size=64x64 indirect=0 samples=4096 bounces=16 out="" build="$root/build"
while [ $# -gt 0 ]; do
    case "$1" in
        --camera) camera=$2; shift 2 ;;
        --size) size=$2; shift 2 ;;
        --indirect) indirect=1; shift ;;
        --samples) samples=$2; shift 2 ;;
        --bounces) bounces=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --build) build=$2; shift 2 ;;
        -h|--help) usage 0 ;;
        -*) echo "cycles_compare: unknown option $1" >&2; usage ;;
        *) scene=$1; shift ;;
    esac
done
[ -n "$scene" ] && [ -n "$camera" ] || usage
command -v blender > /dev/null || { echo "cycles_compare: needs blender (apt-get install blender)" >&2; exit 1; }
client="$build/bin/editor_client"
[ -x "$client" ] || { echo "cycles_compare: no $client: build first (scripts/build.sh)" >&2; exit 1; }
out=${out:-$(mktemp -d -t cycles_compare.XXXXXX)}
mkdir -p "$out"

cycles() {  # OUT.pfm BOUNCES SAMPLES
    blender -b --factory-startup -P "$root/scripts/tools/cycles_reference.py" -- "$scene" -o "$1" \
        --size "$size" --camera "$camera" --bounces "$2" --samples "$3" > "$out/blender.log" 2>&1 ||
        { tail -20 "$out/blender.log" >&2; exit 1; }
}
ours() {  # OUT.pfm MODE INDIRECT
    "$client" render "$scene" --spawn-server --mode "$2" --indirect "$3" --size "$size" --camera "$camera" \
        -o "$out/ours.png" --float "$1" > "$out/render.log" 2>&1 || { cat "$out/render.log" >&2; exit 1; }
}
compare() { /usr/bin/python3 "$root/scripts/tools/cycles_compare.py" "$@"; }

cycles "$out/cycles_direct.pfm" 0 "$samples"
ours "$out/ours_direct.pfm" reference off
compare "$out/ours_direct.pfm" "$out/cycles_direct.pfm" --png "$out/direct" --label "direct, reference:"
ours "$out/ours_direct_lightcuts.pfm" lightcuts off
compare "$out/ours_direct_lightcuts.pfm" "$out/cycles_direct.pfm" --label "direct, lightcuts:"
if [ "$indirect" = 1 ]; then
    cycles "$out/cycles_all.pfm" "$bounces" "$samples"
    for method in vpl radiosity; do
        ours "$out/ours_$method.pfm" reference "$method"
        compare "$out/ours_$method.pfm" "$out/cycles_all.pfm" --minus-ours "$out/ours_direct.pfm" \
            --minus-cycles "$out/cycles_direct.pfm" --png "$out/$method" \
            --label "indirect ($method, $bounces Cycles bounces), reference:"
    done
fi
echo "cycles_compare: images in $out"
