#!/usr/bin/env bash
# The comparison set: short runs that touch every model, body kind and
# feature (paper 20,000 steps, paper_conservative, finite_strain at
# 55.9 kN, the spinning plate, both oscillating plates with the automatic
# step, the held strip; a ring under internal pressure, colliding blocks
# in contact, a holed plate pulled by driven grips, the Giordano panel in
# its gas), each at 1 and 2 threads, with two builds; then every run of the
# new build against the old one and against itself at the other thread
# count, bit for bit (tests/tools/compare_runs.py: history.csv, every frame,
# the final checkpoint). Each build also runs the paper's case stopped
# halfway and resumed, and, where mpirun and an MPI build are there, at 2
# ranks: both against its straight run. Use it for a change that must not
# move a bit, and to show how far one that may has moved them.
#   tests/tools/compare_builds.sh OLD_MPSOLID NEW_MPSOLID [WORK_DIR]
# Exits 0 if everything is identical, 1 otherwise (the differences printed);
# datasets only the new build writes (a new output field) are listed, not
# counted as differences, and a case the old build refuses as bad input
# (exit 2: a feature it does not have) is listed as not compared.
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
  "ring_pressure|cases/ring_pressure.toml|time.end=2e-4 output.frame_interval=5e-5"
  "colliding_blocks|cases/colliding_blocks.toml|time.end=2e-4 output.frame_interval=5e-5"
  "holed_plate_grips|cases/holed_plate_grips.toml|time.end=2e-4 output.frame_interval=5e-5"
  "giordano_gas|cases/giordano_panel.toml|gas.cell=0.001 gas.shock.x=-0.002 time.end=5e-5 output.frame_interval=1e-5"
)
MPIEXEC=${MPIEXEC:-$(command -v mpirun || true)}
run_set() {  # run_set EXE TAG
  local exe=$1 tag=$2 fixed=()
  "$exe" run --help 2>/dev/null | grep -q -- --fixed-threads && fixed=(--fixed-threads)
  for entry in "${runs[@]}"; do
    IFS='|' read -r name case sets <<<"$entry"
    local args=()
    for s in $sets; do args+=(--set "$s"); done
    for t in 1 2; do
      local dir="$work/$tag/$name-t$t" rc=0
      rm -rf "$dir"
      "$exe" run "$case" "${args[@]}" --out "$dir" --threads "$t" "${fixed[@]}" >"$dir.log" 2>&1 || rc=$?
      if [[ $rc -eq 2 && $tag == old ]]; then
        touch "$dir.refused"  # a case this build does not know
      elif [[ $rc -ne 0 ]]; then
        echo "compare_builds: $exe failed on $name at $t thread(s) (see $dir.log)" >&2
        exit 1
      fi
    done
  done
  # The paper's case stopped halfway and resumed; and at 2 ranks.
  local dir="$work/$tag/paper-resumed"
  rm -rf "$dir"
  "$exe" run cases/shock_rod.toml --set time.end=1e-4 --set output.frame_interval=5e-5 \
    --out "$dir" --threads 2 "${fixed[@]}" >"$dir.log" 2>&1 &&
    "$exe" resume "$dir" --set time.end=2e-4 --threads 1 "${fixed[@]}" >>"$dir.log" 2>&1 ||
    { echo "compare_builds: $exe failed to run and resume the paper's case (see $dir.log)" >&2; exit 1; }
  dir="$work/$tag/paper-ranks2"
  rm -rf "$dir"
  if [[ -n $MPIEXEC ]] && "$exe" --version 2>/dev/null | grep -q "MPI: Open MPI"; then
    "$MPIEXEC" -np 2 --oversubscribe --allow-run-as-root "$exe" run cases/shock_rod.toml \
      --set time.end=2e-4 --set output.frame_interval=5e-5 --out "$dir" --threads 1 >"$dir.log" 2>&1 ||
      { echo "compare_builds: $exe failed at 2 ranks (see $dir.log)" >&2; exit 1; }
  fi
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
  for t in 1 2; do
    if [[ -e "$work/old/$name-t$t.refused" ]]; then
      echo "not compared: $name, $t thread(s): the old build refuses the case (see $work/old/$name-t$t.log)"
    else
      compare "$work/old/$name-t$t" "$work/new/$name-t$t" "$name, $t thread(s), old vs new"
    fi
  done
  compare "$work/new/$name-t1" "$work/new/$name-t2" "$name, new, 1 vs 2 threads"
done
for tag in old new; do
  compare "$work/$tag/paper-t1" "$work/$tag/paper-resumed" "paper, $tag, straight vs stopped halfway and resumed"
  if [[ -d "$work/$tag/paper-ranks2" ]]; then
    compare "$work/$tag/paper-t1" "$work/$tag/paper-ranks2" "paper, $tag, 1 thread vs 2 ranks"
  else
    echo "not compared: paper at 2 ranks, $tag (no mpirun or no MPI in the build)"
  fi
done
exit $status
