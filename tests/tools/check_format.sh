#!/usr/bin/env bash
# check_format.sh CLANG_FORMAT: every tracked C++ file must be formatted as
# .clang-format says; prints the offending lines and fails otherwise.
set -euo pipefail
clang_format=${1:-clang-format}
if ! command -v "$clang_format" > /dev/null; then
  echo "check_format: $clang_format not found (scripts/install_deps.sh installs clang-format)" >&2
  exit 1
fi
cd "$(dirname "$0")/../.."
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
if [ ${#files[@]} -eq 0 ]; then
  echo "check_format: no C++ files found (not a git checkout?)" >&2
  exit 1
fi
"$clang_format" --dry-run -Werror "${files[@]}"
echo "check_format: ${#files[@]} files formatted"
