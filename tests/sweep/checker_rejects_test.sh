#!/usr/bin/env bash
# scripts/tools/check_sweep.py accepts a real quick-sweep output (fixtures/good_*) and
# rejects each broken variant, naming the check that caught it:
#   bad_nan_renders.csv       a NaN error value                  -> [finite]
#   bad_monotone_renders.csv  E=0.005 worse than E=0.02          -> [monotone-error]
#   bad_columns_renders.csv   the ssim column missing            -> [columns]
#   bad_pairing_bakes.csv     exact pairing dearer than approx.  -> [pairing-exact]
# Usage: bash tests/sweep/checker_rejects_test.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
checker="$here/../../scripts/tools/check_sweep.py"
fixtures="$here/fixtures"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
failures=0

# case NAME RENDERS BAKES EXPECTED  (EXPECTED: "ok" or the name of the check that must fail)
case_() {
  local name=$1 renders=$2 bakes=$3 expected=$4 out rc
  mkdir -p "$tmp/$name/bench"
  cp "$fixtures/$renders" "$tmp/$name/bench/accuracy_renders.csv"
  cp "$fixtures/$bakes" "$tmp/$name/bench/accuracy_bakes.csv"
  set +e
  out="$(/usr/bin/python3 "$checker" "$tmp/$name" --skip-images 2>&1)"
  rc=$?
  set -e
  if [[ "$expected" == ok ]]; then
    if [[ $rc -ne 0 ]]; then
      echo "FAIL $name: the checker rejected a good sweep:"; echo "$out"; failures=$((failures + 1))
    else
      echo "pass $name: accepted ($out)"
    fi
  elif [[ $rc -ne 1 ]]; then
    echo "FAIL $name: exit $rc, expected 1:"; echo "$out"; failures=$((failures + 1))
  elif ! grep -qF "FAILED [$expected]" <<<"$out"; then
    echo "FAIL $name: rejected, but not by [$expected]:"; echo "$out"; failures=$((failures + 1))
  else
    echo "pass $name: rejected by [$expected]"
  fi
}

case_ good good_renders.csv good_bakes.csv ok
case_ nan bad_nan_renders.csv good_bakes.csv finite
case_ monotone bad_monotone_renders.csv good_bakes.csv monotone-error
case_ columns bad_columns_renders.csv good_bakes.csv columns
case_ pairing good_renders.csv bad_pairing_bakes.csv pairing-exact

# Without the images the full check (no --skip-images) must fail by [images].
mkdir -p "$tmp/noimages/bench"
cp "$fixtures/good_renders.csv" "$tmp/noimages/bench/accuracy_renders.csv"
cp "$fixtures/good_bakes.csv" "$tmp/noimages/bench/accuracy_bakes.csv"
out="$(/usr/bin/python3 "$checker" "$tmp/noimages" 2>&1 || true)"
if grep -qF "FAILED [images]" <<<"$out"; then
  echo "pass noimages: rejected by [images]"
else
  echo "FAIL noimages: missing figures not reported"; failures=$((failures + 1))
fi

if [[ $failures -ne 0 ]]; then echo "checker_rejects_test: $failures case(s) failed"; exit 1; fi
echo "checker_rejects_test: all cases passed"
