#!/usr/bin/env bash
# Runs the quick accuracy sweep (scripts/sweep_accuracy.sh --quick, 1-2 minutes
# on 2 cores) into a temporary directory and checks its output with
# scripts/tools/check_sweep.py: columns, finite values, ranges, monotone error against
# the error ratio, sublinear cut growth, figures present.
# Usage: bash tests/sweep/sweep_quick_test.sh BUILD_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$here/../.."
build_dir="${1:?usage: sweep_quick_test.sh BUILD_DIR}"
out="$(mktemp -d -t sweep-quick-test-XXXXXX)"
trap 'rm -rf "$out"' EXIT
bash "$repo/scripts/sweep_accuracy.sh" --quick --build-dir "$build_dir" --out-dir "$out"
/usr/bin/python3 "$repo/scripts/tools/check_sweep.py" "$out"
