#!/bin/bash
# Lists the production functions longer than a limit (default 80 lines), longest
# first, as "LINES NAME FILE:LINE", from Universal Ctags' end lines over the
# tracked sources outside tests/. Usage: scripts/tools/long_functions.sh [LIMIT]
set -euo pipefail
limit=${1:-80}
cd "$(dirname "$0")/../.."
command -v ctags >/dev/null || { echo "tools/long_functions.sh: needs universal-ctags" >&2; exit 1; }
git ls-files '*.cpp' '*.h' ':!tests/' ':!cmake/' |
  xargs ctags --kinds-C++=f --fields=+ne -x --_xformat='%n	%e	%N	%F' |
  awk -F'\t' -v limit="$limit" '{ lines = $2 - $1 + 1; if (lines > limit) printf "%d %s %s:%d\n", lines, $3, $4, $1 }' |
  sort -rn
