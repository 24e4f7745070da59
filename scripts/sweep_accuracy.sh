#!/usr/bin/env bash
# Accuracy/time sweep of the Lightcuts renderer (issue #5, docs/ACCURACY.md).
# Runs editor_client (which spawns lightmass_server) over generated rooms and the
# shared scenes, then writes CSV files and figures:
#   OUT/bench/accuracy_renders.csv, accuracy_bakes.csv, accuracy_runinfo.csv
#   OUT/images/accuracy_*.png
# Usage: bash scripts/sweep_accuracy.sh [--quick|--full] [--build-dir DIR] [--out-dir OUT]
#                                       [--only pareto,lights,pairing,shared,figure] [--keep-work]
#                                       [--plots-only]
#   --quick  1-2 minutes on 2 cores; OUT defaults to a new temporary directory
#   --full   (default) 12-14 minutes; OUT defaults to docs/ (docs/bench, docs/images)
#   --build-dir defaults to build; editor_client and lightmass_server are built there
#   when missing. --only reruns some groups and keeps the other groups' rows;
#   --plots-only redraws the figures from the CSV files without running anything.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
mode=full
build_dir="$repo/build"
out_dir=""
extra=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) mode=quick ;;
    --full) mode=full ;;
    --build-dir) build_dir="$2"; shift ;;
    --out-dir) out_dir="$2"; shift ;;
    --only) extra+=(--only "$2"); shift ;;
    --keep-work) extra+=(--keep-work) ;;
    --plots-only) extra+=(--plots-only) ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "sweep-accuracy: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
if [[ -z "$out_dir" ]]; then
  if [[ "$mode" == quick ]]; then
    out_dir="$(mktemp -d -t sweep-quick-XXXXXX)"
  else
    out_dir="$repo/docs"
  fi
fi

if [[ ! -x "$build_dir/bin/editor_client" || ! -x "$build_dir/bin/lightmass_server" ]]; then
  if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
    cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  fi
  cmake --build "$build_dir" --target editor_client lightmass_server -j "$(nproc)"
fi

# Debian's interpreter: the python3 on PATH may lack numpy and matplotlib.
exec /usr/bin/python3 "$repo/scripts/lib/sweep_accuracy.py" "--$mode" --build-dir "$build_dir" \
  --out-dir "$out_dir" "${extra[@]}"
