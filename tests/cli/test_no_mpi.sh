#!/usr/bin/env bash
# The build without MPI (docs/mpi.md): the same objects but a one-rank
# communicator, linked without the MPI library (CMake's mpsolid_no_mpi):
#  - it says so (--version) and does not link libmpi;
#  - it gives the MPI build's one-rank bits (compare_runs.py);
#  - started as one of 2 ranks by a launcher, it refuses with exit 2 and one
#    message, and writes nothing (each rank would run the whole case alone);
#    as the only rank it runs; so under srun's PMIx (its environment
#    imitated);
#  - srun without an MPI plugin (its environment imitated) gets a note from
#    task 0 that each task runs the case alone.
#
#   bash tests/cli/test_no_mpi.sh MPSOLID_NO_MPI MPSOLID MPIEXEC    (from the repository root)
set -u
if [[ $# -ne 3 ]]; then
  echo "usage: bash tests/cli/test_no_mpi.sh MPSOLID_NO_MPI MPSOLID MPIEXEC" >&2
  exit 2
fi
ALONE=$(realpath -- "$1") || { echo "FAIL: no binary at '$1'" >&2; exit 1; }
BIN=$(realpath -- "$2") || { echo "FAIL: no binary at '$2'" >&2; exit 1; }
MPIEXEC=$3
cd "$(dirname -- "${BASH_SOURCE[0]}")/../.." || exit 1
TMP=$(mktemp -d "${TMPDIR:-/tmp}/mpsolid_no_mpi.XXXXXX") || exit 1
trap 'rm -rf -- "$TMP"' EXIT
export OMPI_MCA_btl_vader_single_copy_mechanism=none
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok: $*"; }
RUN=(run cases/shock_rod.toml --set l0=0.001 --set time.end=5e-5 --threads 1)

"$ALONE" --version | grep -q "MPI: not in this build" && ok "--version: MPI: not in this build" ||
  fail "--version does not say the build has no MPI: $("$ALONE" --version | tail -n 1)"
if ldd "$ALONE" | grep -qi "libmpi"; then fail "linked with the MPI library"; else ok "no libmpi linked"; fi

"$BIN" "${RUN[@]}" --out "$TMP/mpi_build" >/dev/null 2>&1 </dev/null || fail "the MPI build's run failed"
if "$ALONE" "${RUN[@]}" --out "$TMP/alone" >/dev/null 2>"$TMP/alone.err" </dev/null; then
  if /usr/bin/python3 tests/tools/compare_runs.py "$TMP/mpi_build" "$TMP/alone" >"$TMP/cmp" 2>&1; then
    ok "the MPI build's bits ($(tail -n 1 "$TMP/cmp"))"
  else
    fail "differs from the MPI build:"
    sed 's/^/    /' "$TMP/cmp" | head -n 8
  fi
else
  fail "the run failed: $(head -c 600 "$TMP/alone.err")"
fi

timeout 120 "$MPIEXEC" -np 2 --oversubscribe --allow-run-as-root "$ALONE" "${RUN[@]}" \
  --out "$TMP/two" </dev/null >"$TMP/two.out" 2>"$TMP/two.err"
rc=$?
[[ $rc -eq 2 ]] && ok "2 ranks: exit 2" || fail "2 ranks: exit $rc (want 2)"
count=$(grep -c "built without MPI" "$TMP/two.err")
[[ $count -eq 1 ]] && ok "2 ranks: one message" ||
  fail "2 ranks: $count messages naming the missing MPI: $(head -c 600 "$TMP/two.err")"
[[ ! -e "$TMP/two" ]] && ok "2 ranks: nothing written" || fail "2 ranks: $TMP/two was written"

timeout 120 "$MPIEXEC" -np 1 --allow-run-as-root "$ALONE" "${RUN[@]}" --out "$TMP/one" \
  </dev/null >/dev/null 2>"$TMP/one.err"
rc=$?
[[ $rc -eq 0 && -s "$TMP/one/history.csv" ]] && ok "1 rank under the launcher: runs" ||
  fail "1 rank under the launcher: exit $rc: $(head -c 600 "$TMP/one.err")"

# srun's environment: PMIx names the rank, the step the task count.
PMIX_RANK=0 SLURM_STEP_NUM_TASKS=2 SLURM_PROCID=0 "$ALONE" "${RUN[@]}" --out "$TMP/srun" \
  </dev/null >/dev/null 2>"$TMP/srun.err"
rc=$?
[[ $rc -eq 2 && ! -e "$TMP/srun" ]] && grep -q "built without MPI" "$TMP/srun.err" &&
  ok "srun's PMIx, 2 tasks: exit 2, the message, nothing written" ||
  fail "srun's PMIx, 2 tasks: exit $rc: $(head -c 600 "$TMP/srun.err")"
for task in 0 1; do
  SLURM_STEP_NUM_TASKS=2 SLURM_PROCID=$task "$BIN" "${RUN[@]}" --out "$TMP/plain$task" \
    </dev/null >/dev/null 2>"$TMP/plain$task.err"
  rc=$?
  notes=$(grep -c "srun started 2 tasks, but not as one MPI job" "$TMP/plain$task.err")
  want=$((task == 0 ? 1 : 0))
  [[ $rc -eq 0 && $notes -eq $want ]] &&
    ok "srun without an MPI plugin, task $task: runs, $notes note(s)" ||
    fail "srun without an MPI plugin, task $task: exit $rc, $notes note(s) (want 0, $want)"
done

if [[ $failures -eq 0 ]]; then
  echo "test_no_mpi: all checks passed"
else
  echo "test_no_mpi: $failures check(s) FAILED"
  exit 1
fi
