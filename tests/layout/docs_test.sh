#!/usr/bin/env bash
# The docs stay readable and true (scripts/tools/check_docs.py): the checker
# rejects a planted long line and a missing path; the architecture map is short
# with short lines, the benchmarks under 500 lines; every path the README, the docs and the folder READMEs name exists.
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
checker="$repo/scripts/tools/check_docs.py"
planted="$(mktemp -d)"
trap 'rm -rf "$planted"' EXIT
printf 'see `lightcuts/no_such_file.h`\n' > "$planted/missing.md"
printf '%0300d\n' 0 > "$planted/long.md"
for doc in missing long; do
  if /usr/bin/python3 "$checker" --repo "$repo" "$planted/$doc.md" 2>/dev/null; then
    echo "the checker accepted $doc.md" >&2
    exit 1
  fi
done
cd "$repo"
/usr/bin/python3 "$checker" --max-lines 250 docs/ARCHITECTURE.md
/usr/bin/python3 "$checker" --max-lines 500 docs/BENCHMARKS.md
/usr/bin/python3 "$checker" --max-width 0 README.md docs/*.md $(git ls-files '*/README.md' 2>/dev/null || ls */README.md)
