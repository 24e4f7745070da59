#!/usr/bin/env bash
# The include-cycle checker finds a planted cycle between two folders, and the
# repository itself has none (scripts/tools/check_include_cycles.py).
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
checker="$repo/scripts/tools/check_include_cycles.py"
planted="$(mktemp -d)"
trap 'rm -rf "$planted"' EXIT
mkdir -p "$planted/lightcuts/a" "$planted/lightcuts/b"
echo '#include "lightcuts/b/y.h"' > "$planted/lightcuts/a/x.h"
echo '#include "lightcuts/a/x.h"' > "$planted/lightcuts/b/y.h"
if /usr/bin/python3 "$checker" "$planted" 2>/dev/null; then
  echo "the checker missed a planted cycle lightcuts/a <-> lightcuts/b" >&2
  exit 1
fi
/usr/bin/python3 "$checker" "$repo"
