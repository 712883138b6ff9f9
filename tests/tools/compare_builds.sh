#!/usr/bin/env bash
# The comparison set: seven short runs that touch every model and body kind
# (paper 20,000 steps, paper_conservative, finite_strain at 55.9 kN,
# the spinning plate, both oscillating plates with the automatic step, the
# held strip), each at 1 and 2 threads, with two builds; then every run of
# the new build against the old one and against itself at the other thread
# count, bit for bit (tests/tools/compare_runs.py: history.csv, every frame,
# the final checkpoint). Use it for a change that must not move a bit, and
# to show how far one that may has moved them.
#   tests/tools/compare_builds.sh OLD_MPSOLID NEW_MPSOLID [WORK_DIR]
# Exits 0 if everything is identical, 1 otherwise (the differences printed);
# datasets only the new build writes (a new output field) are listed, not
# counted as differences.
set -uo pipefail
cd "$(dirname "$0")/../.."
[ $# -ge 2 ] || { echo "usage: tests/tools/compare_builds.sh OLD_MPSOLID NEW_MPSOLID [WORK_DIR]" >&2; exit 2; }
old=$1 new=$2 work=${3:-out/compare_builds}
for exe in "$old" "$new"; do
  [ -x "$exe" ] || { echo "compare_builds: $exe is not an executable" >&2; exit 2; }
done
runs=(
  "paper|cases/shock_rod.toml|time.end=2e-4 output.frame_interval=5e-5"
  "paper_conservative|cases/shock_rod.toml|model=paper_conservative time.end=2e-4 output.frame_interval=5e-5"
  "finite_strain_55kN|cases/shock_rod_55kN_short_wall.toml|time.end=3e-4 output.frame_interval=5e-5"
  "spinning_plate|cases/spinning_plate.toml|time.end=0.02 output.frame_interval=0.005 output.history_interval=0.001"
  "oscillating_plate|cases/oscillating_plate.toml|time.end=0.02 output.frame_interval=0.005"
  "oscillating_plate_linear|cases/oscillating_plate_linear.toml|time.end=0.02 output.frame_interval=0.005"
  "wave_strip|cases/wave_strip.toml|time.end=0.005 output.frame_interval=0.001"
)
run_set() {  # run_set EXE TAG
  local exe=$1 tag=$2 fixed=()
  "$exe" run --help 2>/dev/null | grep -q -- --fixed-threads && fixed=(--fixed-threads)
  for entry in "${runs[@]}"; do
    IFS='|' read -r name case sets <<<"$entry"
    local args=()
    for s in $sets; do args+=(--set "$s"); done
    for t in 1 2; do
      local dir="$work/$tag/$name-t$t"
      rm -rf "$dir"
      "$exe" run "$case" "${args[@]}" --out "$dir" --threads "$t" "${fixed[@]}" >"$dir.log" 2>&1 ||
        { echo "compare_builds: $exe failed on $name at $t thread(s) (see $dir.log)" >&2; exit 1; }
    done
  done
}
mkdir -p "$work/old" "$work/new"
run_set "$old" old
run_set "$new" new
status=0
compare() {  # compare DIR_A DIR_B LABEL
  if out=$(/usr/bin/python3 tests/tools/compare_runs.py "$1" "$2" 2>&1); then
    echo "identical: $3"
  else
    echo "DIFFERENT: $3"; echo "$out" | head -5 | sed 's/^/  /'; status=1
  fi
}
for entry in "${runs[@]}"; do
  name=${entry%%|*}
  for t in 1 2; do compare "$work/old/$name-t$t" "$work/new/$name-t$t" "$name, $t thread(s), old vs new"; done
  compare "$work/new/$name-t1" "$work/new/$name-t2" "$name, new, 1 vs 2 threads"
done
exit $status
