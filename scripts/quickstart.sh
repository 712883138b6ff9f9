#!/usr/bin/env bash
# One command from a fresh clone: install what is missing, build (Release),
# then either run the paper's case or the whole test suite.
#   scripts/quickstart.sh paper   # cases/shock_rod.toml -> out/shock_rod/ (+ pictures)
#   scripts/quickstart.sh test    # ctest, every label
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-}
case "$what" in
  paper | test) ;;
  *) echo "usage: scripts/quickstart.sh paper|test" >&2; exit 2 ;;
esac
scripts/install_deps.sh
jobs=$(nproc)
cmake --preset release
cmake --build --preset release -j "$jobs"
if [ "$what" = paper ]; then
  # --force: running the quick start again replaces the previous results.
  ./build/release/mpsolid run cases/shock_rod.toml --out out/shock_rod --force
  # The pictures: out/shock_rod/frames.png and history.png (Debian's python3).
  /usr/bin/python3 tools/plot.py out/shock_rod
else
  ctest --preset release -j "$jobs"
fi
