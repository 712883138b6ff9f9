#!/usr/bin/env bash
# The executable under mpirun (docs/mpi.md), where MPI is installed:
#  - more than one rank is refused on every rank with exit 2 and one message,
#    before anything is read or written;
#  - one rank under mpirun gives the same bits as a plain run.
#
#   bash tests/cli/test_mpi_cli.sh PATH_TO_MPSOLID MPIEXEC    (from the repository root)
set -u
if [[ $# -ne 2 ]]; then
  echo "usage: bash tests/cli/test_mpi_cli.sh PATH_TO_MPSOLID MPIEXEC" >&2
  exit 2
fi
BIN=$(realpath -- "$1") || { echo "FAIL: no mpsolid binary at '$1'" >&2; exit 1; }
MPIEXEC=$2
cd "$(dirname -- "${BASH_SOURCE[0]}")/../.." || exit 1
TMP=$(mktemp -d "${TMPDIR:-/tmp}/mpsolid_mpi_cli.XXXXXX") || exit 1
trap 'rm -rf -- "$TMP"' EXIT
export OMP_NUM_THREADS=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok: $*"; }
CASE=cases/shock_rod.toml
SHORT=(--set time.end=2e-5 --set output.frame_interval=1e-5)

"$MPIEXEC" -np 2 --oversubscribe --allow-run-as-root "$BIN" run "$CASE" "${SHORT[@]}" \
  --out "$TMP/two" >"$TMP/two.out" 2>"$TMP/two.err" </dev/null
rc=$?
[[ $rc -eq 2 ]] && ok "2 ranks: exit 2" || fail "2 ranks: exit $rc, expected 2"
messages=$(grep -c "started as 2 MPI ranks.*docs/mpi.md" "$TMP/two.err")
[[ $messages -eq 1 ]] && ok "2 ranks: one message, naming docs/mpi.md" ||
  { fail "2 ranks: $messages messages on stderr, expected 1:"; sed 's/^/    /' "$TMP/two.err"; }
[[ ! -e "$TMP/two" ]] && ok "2 ranks: nothing written" || fail "2 ranks: $TMP/two was created"

"$BIN" run "$CASE" "${SHORT[@]}" --out "$TMP/plain" --threads 1 >/dev/null 2>&1 </dev/null ||
  fail "the plain run failed"
"$MPIEXEC" -np 1 --allow-run-as-root "$BIN" run "$CASE" "${SHORT[@]}" --out "$TMP/one" \
  --threads 1 >"$TMP/one.out" 2>"$TMP/one.err" </dev/null
rc=$?
if [[ $rc -ne 0 ]]; then
  fail "1 rank under mpirun: exit $rc"
  sed 's/^/    /' "$TMP/one.err"
elif /usr/bin/python3 tests/tools/compare_runs.py "$TMP/plain" "$TMP/one" >"$TMP/compare" 2>&1; then
  ok "1 rank under mpirun: the plain run's bits ($(tail -n 1 "$TMP/compare"))"
else
  fail "1 rank under mpirun differs from the plain run:"
  sed 's/^/    /' "$TMP/compare"
fi

if [[ $failures -gt 0 ]]; then
  echo "test_mpi_cli: $failures check(s) FAILED"
  exit 1
fi
echo "test_mpi_cli: all checks passed"
