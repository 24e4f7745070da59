#!/usr/bin/env bash
# The size checker (scripts/tools/check_sizes.py) names a planted long file and a
# planted crowded folder, and the repository has neither: no production file
# over 700 lines, no production folder with more than 25 concepts at its top level.
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
checker="$repo/scripts/tools/check_sizes.py"
planted="$(mktemp -d)"
trap 'rm -rf "$planted"' EXIT
mkdir -p "$planted/long/lightcuts" "$planted/crowded/protocol/sub"
seq 701 > "$planted/long/lightcuts/long.cpp"
for i in $(seq 25); do touch "$planted/crowded/protocol/c$i.h" "$planted/crowded/protocol/c$i.cpp"; done
for case in long:lightcuts/long.cpp crowded:protocol/; do
  if messages="$(/usr/bin/python3 "$checker" "$planted/${case%%:*}" 2>&1)"; then
    echo "the checker accepted the planted ${case%%:*} case" >&2
    exit 1
  fi
  grep -q "${case#*:}" <<< "$messages" || { echo "the checker did not name ${case#*:}: $messages" >&2; exit 1; }
done
# A header and its source count once: 25 pairs and no subfolder pass.
rmdir "$planted/crowded/protocol/sub"
/usr/bin/python3 "$checker" "$planted/crowded" > /dev/null
/usr/bin/python3 "$checker" "$repo"
