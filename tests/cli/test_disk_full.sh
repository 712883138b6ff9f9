#!/usr/bin/env bash
# A disk that fills up during a run: the run fails saying "no space left",
# removes its temporary files and keeps its last checkpoint and the outputs it
# records; once space is back, `mpsolid resume` ends bit-identical to a run
# that never failed. Needs a small tmpfs (mount as root): exit 77 (skipped)
# where it cannot mount one.
#
#   bash tests/cli/test_disk_full.sh PATH_TO_MPSOLID    (from the repository root)
set -u
BIN=$(realpath -- "$1") || exit 1
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

"$BIN" run "${ARGS[@]}" --out "$DISK/run" --threads 2 </dev/null >"$TMP/full.out" 2>"$TMP/full.err"
rc=$?
if [[ $rc -eq 1 ]] && grep -qF "no space left on the device holding $DISK/run" "$TMP/full.err" &&
  grep -qF "mpsolid resume $DISK/run" "$TMP/full.err"; then
  ok "full: exit 1 saying no space left, naming the folder and how to resume"
else
  fail "full: exit $rc; stderr: $(head -c 600 "$TMP/full.err")"
fi
left=$(find "$DISK/run" -name '*.tmp')
[[ -z "$left" ]] && ok "full: no temporary files left" || fail "full: temporary files left: $left"
if $PY -c '
import sys, csv, h5py
d = sys.argv[1]
with h5py.File(d + "/checkpoint.h5", "r") as c:
    frames, step = int(c.attrs["frames"]), int(c.attrs["step"])
with h5py.File(d + "/frames.h5", "r") as f:
    assert len(f["frames"]) >= frames, (len(f["frames"]), frames)
rows = list(csv.reader(open(d + "/history.csv")))
assert len(rows) - 1 >= frames and step > 0
' "$DISK/run" 2>"$TMP/check.err"; then
  ok "full: the last checkpoint and the outputs it records are intact and readable"
else
  fail "full: checkpoint or outputs not readable: $(cat "$TMP/check.err")"
fi

# Space back: the resume ends bit-identical to the reference.
mount -o remount,size=64m "$DISK" || fail "cannot enlarge the tmpfs"
"$BIN" resume "$DISK/run" --threads 1 </dev/null >"$TMP/resume.out" 2>"$TMP/resume.err"
rc=$?
if [[ $rc -eq 0 ]] && $PY tests/tools/compare_runs.py "$TMP/reference" "$DISK/run" >"$TMP/cmp.out" 2>&1; then
  ok "resume: once space is back the run ends bit-identical to one that never failed"
else
  fail "resume: exit $rc; $(head -c 600 "$TMP/resume.err") $(cat "$TMP/cmp.out")"
fi

echo
if [[ $failures -gt 0 ]]; then
  echo "test_disk_full: $failures check(s) FAILED"
  exit 1
fi
echo "test_disk_full: all checks passed"
