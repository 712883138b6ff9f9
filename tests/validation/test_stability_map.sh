#!/usr/bin/env bash
# A small subset of the stability map (tools/stability_map.py): at 55.9 kN,
# l0 = 2 mm, 10 ns, over 1 ms, the paper model is stopped by an inverted
# bond before 0.75 ms and the finite-strain model is stable.
set -euo pipefail
bin=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$root/tools/stability_map.py" --binary "$bin" --work "$work/runs" \
  --docs "$work/docs" --l0 2 --models paper finite_strain --forces 55.9 --end 0.001 \
  --dt-paper-only --jobs 2 > "$work/stdout"
table=$work/docs/stability_map.md
fail() { echo "test_stability_map: $*"; cat "$table"; exit 1; }
[ -s "$work/docs/images/stability_map.png" ] || fail "no picture"
grep -E '^\| paper \| 2 \| 10 ns \| 0\.(6[0-9]|7[0-4])[0-9]* ms, inverted bond \|$' "$table" >/dev/null ||
  fail "paper model at 55.9 kN should fail by an inverted bond between 0.6 and 0.75 ms"
grep -E '^\| finite_strain \| 2 \| 10 ns \| stable \|$' "$table" >/dev/null ||
  fail "finite_strain at 55.9 kN should be stable"
echo "test_stability_map: ok"
