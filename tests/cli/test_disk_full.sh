#!/usr/bin/env bash
# A disk that fills up during a run: the run fails saying "no space left",
# removes its temporary files and keeps its last checkpoint and the outputs it
# records; once space is back, `mpsolid resume` ends bit-identical to a run
# that never failed. Needs a small tmpfs (mount as root): exit 77 (skipped)
# where it cannot mount one.
#
# Over 2 MPI ranks too, where a launcher is given (every rank writes its own
# rows of the frames and checkpoints).
#
#   bash tests/cli/test_disk_full.sh PATH_TO_MPSOLID [MPIEXEC]    (from the repository root)
set -u
BIN=$(realpath -- "$1") || exit 1
MPIEXEC=${2:-}
cd "$(dirname -- "${BASH_SOURCE[0]}")/../.." || exit 1
PY=/usr/bin/python3
TMP=$(mktemp -d "${TMPDIR:-/tmp}/mpsolid_disk.XXXXXX") || exit 1
DISK=$TMP/disk
mkdir -p "$DISK"
if ! mount -t tmpfs -o size=1500k tmpfs "$DISK" 2>/dev/null; then
  echo "test_disk_full: cannot mount a tmpfs here (needs root): skipped"
  rm -rf -- "$TMP"
  exit 77
fi
trap 'umount "$DISK" 2>/dev/null; rm -rf -- "$TMP"' EXIT

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok: $*"; }

# 41 frames of ~90 kB do not fit in 1.5 MB with their published copies.
ARGS=(cases/shock_rod.toml --set time.end=2e-4 --set output.frame_interval=5e-6
  --set output.checkpoint_interval=2e-5)
"$BIN" run "${ARGS[@]}" --out "$TMP/reference" --threads 1 </dev/null >/dev/null 2>&1 ||
  fail "the reference run failed"

# fill_the_disk LABEL THREADS [LAUNCHER...]: the run fills the 1.5 MB disk,
# then resumes once space is back.
fill_the_disk() {
  LABEL=$1 THREADS=$2
  shift 2
  LAUNCH=("$@")
  rm -rf -- "$DISK/run"
  mount -o remount,size=1500k "$DISK" || fail "cannot shrink the tmpfs"
  "${LAUNCH[@]}" "$BIN" run "${ARGS[@]}" --out "$DISK/run" --threads "$THREADS" </dev/null >"$TMP/full.out" 2>"$TMP/full.err"
  rc=$?
  if [[ $rc -eq 1 ]] && grep -qF "no space left on the device holding $DISK/run" "$TMP/full.err" &&
    grep -qF "mpsolid resume $DISK/run" "$TMP/full.err"; then
    ok "$LABEL full: exit 1 saying no space left, naming the folder and how to resume"
  else
    fail "$LABEL full: exit $rc; stderr: $(head -c 600 "$TMP/full.err")"
  fi
  left=$(find "$DISK/run" -name '*.tmp')
  [[ -z "$left" ]] && ok "$LABEL full: no temporary files left" || fail "$LABEL full: temporary files left: $left"
  # Intact: the frames and the history the checkpoint records are the
  # uninterrupted reference run's, bit for bit (what a resume builds on).
  if $PY -c '
import sys, h5py, numpy as np
d, ref = sys.argv[1], sys.argv[2]
with h5py.File(d + "/checkpoint.h5", "r") as c:
    frames, step = int(c.attrs["frames"]), int(c.attrs["step"])
    history_bytes = int(c.attrs["history_bytes"])
assert step > 0 and frames > 1, (step, frames)
with h5py.File(d + "/frames.h5", "r") as f, h5py.File(ref + "/frames.h5", "r") as g:
    mine, theirs = sorted(f["frames"].keys()), sorted(g["frames"].keys())
    assert len(mine) >= frames and mine[:frames] == theirs[:frames], (mine[:frames], theirs[:frames])
    for name in mine[:frames]:
        assert sorted(f["frames"][name].keys()) == sorted(g["frames"][name].keys()), name
        for field in g["frames"][name]:
            a, b = f["frames"][name][field][()], g["frames"][name][field][()]
            assert a.dtype == b.dtype and np.array_equal(a.view(np.uint8), b.view(np.uint8)), (name, field)
with open(d + "/history.csv", "rb") as a, open(ref + "/history.csv", "rb") as b:
    mine, theirs = a.read(), b.read()
assert history_bytes > 0 and len(mine) >= history_bytes, (len(mine), history_bytes)
assert mine[:history_bytes] == theirs[:history_bytes], "history.csv differs from the reference"
print(f"{frames} frames and {history_bytes} bytes of history.csv as the reference, to step {step}")
  ' "$DISK/run" "$TMP/reference" >"$TMP/check.out" 2>"$TMP/check.err"; then
    ok "$LABEL full: the last checkpoint's frames and history are the reference's, bit for bit ($(cat "$TMP/check.out"))"
  else
    fail "$LABEL full: the outputs the checkpoint records are not intact: $(tail -c 600 "$TMP/check.err")"
  fi

  # Space back: the resume ends bit-identical to the reference.
  mount -o remount,size=64m "$DISK" || fail "cannot enlarge the tmpfs"
  "${LAUNCH[@]}" "$BIN" resume "$DISK/run" --threads 1 </dev/null >"$TMP/resume.out" 2>"$TMP/resume.err"
  rc=$?
  if [[ $rc -eq 0 ]] && $PY tests/tools/compare_runs.py "$TMP/reference" "$DISK/run" >"$TMP/cmp.out" 2>&1; then
    ok "$LABEL resume: once space is back the run ends bit-identical to one that never failed"
  else
    fail "$LABEL resume: exit $rc; $(head -c 600 "$TMP/resume.err") $(cat "$TMP/cmp.out")"
  fi
}

fill_the_disk "1 process:" 2 env
# Over MPI ranks every rank writes its own particles' rows of the frames and
# checkpoints: one of them meets the full disk, and the run fails the same way.
if [[ -n "${MPIEXEC:-}" ]]; then
  export OMPI_MCA_btl_vader_single_copy_mechanism=none
  fill_the_disk "2 ranks:" 1 "$MPIEXEC" -np 2 --oversubscribe --allow-run-as-root
fi

echo
if [[ $failures -gt 0 ]]; then
  echo "test_disk_full: $failures check(s) FAILED"
  exit 1
fi
echo "test_disk_full: all checks passed"
