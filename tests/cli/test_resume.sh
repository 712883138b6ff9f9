#!/usr/bin/env bash
# Checkpoints and resume, end to end:
#  - a run stopped by SIGINT or SIGTERM exits 4 with published outputs and a
#    checkpoint, and `mpsolid resume` finishes it to the same bits as an
#    uninterrupted run, also at another thread count;
#  - a run killed (SIGKILL) at random moments, resumed after each kill, ends
#    with the same history.csv, frames and final state as an uninterrupted
#    run, bit for bit (tests/tools/compare_runs.py); one killed after its last
#    checkpoint but before run.json is finished by a resume of no steps;
#  - a resume can go past the old end: run to T, resume to 2T = run to 2T;
#    also with contact, stopped mid-collision (cases/colliding_blocks.toml),
#    and in space (cases/spinning_cube.toml, a quaternion per particle; a
#    rigid sphere of cases/colliding_spheres.toml mid-collision);
#  - a missing, damaged or foreign checkpoint, or a --set that changes the
#    case, is refused with exit 2 and a clear message, leaving the folder as
#    it was.
#
#   bash tests/cli/test_resume.sh PATH_TO_MPSOLID    (from the repository root)
set -u

if [[ $# -ne 1 ]]; then
  echo "usage: bash tests/cli/test_resume.sh PATH_TO_MPSOLID" >&2
  exit 2
fi
BIN=$(realpath -- "$1") || { echo "FAIL: no mpsolid binary at '$1'" >&2; exit 1; }
cd "$(dirname -- "${BASH_SOURCE[0]}")/../.." || exit 1
PY=/usr/bin/python3
# Other tests run beside this one on few cores: threads that wait should sleep.
export OMP_WAIT_POLICY=PASSIVE
COMPARE=tests/tools/compare_runs.py
CASE=cases/shock_rod.toml
TMP=$(mktemp -d "${TMPDIR:-/tmp}/mpsolid_resume.XXXXXX") || exit 1
trap 'rm -rf -- "$TMP"' EXIT

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok: $*"; }

# 6,000 steps, a frame and a checkpoint every 300 steps.
SHORT=(--set time.end=6e-5 --set output.frame_interval=3e-6 --set output.checkpoint_interval=3e-6)

# mp LABEL ARGS...: mpsolid ARGS in the foreground; exit code in $rc.
mp() {
  local label=$1
  shift
  timeout 300 "$BIN" "$@" </dev/null >"$TMP/$label.out" 2>"$TMP/$label.err"
  rc=$?
}
show() {
  echo "    stdout: $(head -c 1500 "$TMP/$1.out")"
  echo "    stderr: $(head -c 1500 "$TMP/$1.err")"
}
same_as_reference() {  # same_as_reference LABEL DIR
  if $PY "$COMPARE" "$REF" "$2" >"$TMP/$1.compare" 2>&1; then
    ok "$1: identical to the uninterrupted run ($(tail -n 1 "$TMP/$1.compare"))"
  else
    fail "$1: differs from the uninterrupted run:"
    sed 's/^/    /' "$TMP/$1.compare" | head -n 12
  fi
}
# resumed_as_reference LABEL WHAT REF DIR: after `mp LABEL_extend resume DIR`
# ($rc), DIR ends as the uninterrupted run REF, bit for bit.
resumed_as_reference() {
  local label=$1 what=$2 ref=$3 dir=$4
  if [[ $rc -ne 0 ]]; then
    fail "$label: resume exited $rc"
    show "${label}_extend"
  elif $PY "$COMPARE" "$ref" "$dir" >"$TMP/$label.compare" 2>&1; then
    ok "$label: $what: identical ($(tail -n 1 "$TMP/$label.compare"))"
  else
    fail "$label: the resumed run differs from the uninterrupted one:"
    sed 's/^/    /' "$TMP/$label.compare" | head -n 12
  fi
}
snapshot() {
  (cd "$1" && find . -type f -print0 | sort -z | xargs -0 -r sha256sum)
}

# ---- the reference: uninterrupted -----------------------------------------------

REF=$TMP/reference
mp reference run "$CASE" "${SHORT[@]}" --out "$REF" --threads 1
if [[ $rc -ne 0 ]]; then
  fail "reference run exited $rc"
  show reference
  exit 1
fi
for f in frames.xdmf checkpoint.h5; do
  [[ -s "$REF/$f" ]] && ok "reference: $f written" || fail "reference: $f missing"
done

# ---- stop signals ------------------------------------------------------------------

for signal in INT TERM; do
  dir=$TMP/stopped_$signal
  "$BIN" run "$CASE" "${SHORT[@]}" --out "$dir" --threads 1 </dev/null >"$TMP/stop_$signal.out" \
    2>"$TMP/stop_$signal.err" &
  pid=$!
  # Signal soon after the first checkpoint (step 300): the whole run takes
  # about 0.4 s on one thread of a 2-vCPU VM.
  for _ in $(seq 500); do [[ -f "$dir/checkpoint.h5" ]] && break; sleep 0.01; done
  sleep 0.05
  kill -"$signal" "$pid"
  wait "$pid"
  rc=$?
  if [[ $rc -eq 0 ]]; then
    echo "note: the run ended before SIG$signal arrived; nothing to check"
    continue
  fi
  if [[ $rc -ne 4 ]]; then
    fail "SIG$signal: expected exit code 4, got $rc"
    show "stop_$signal"
    continue
  fi
  ok "SIG$signal: exit 4"
  grep -q "stopped by SIG$signal" "$TMP/stop_$signal.out" && ok "SIG$signal: summary printed" ||
    fail "SIG$signal: no closing summary naming the signal on stdout"
  grep -q "mpsolid resume" "$TMP/stop_$signal.err" && ok "SIG$signal: says how to resume" ||
    fail "SIG$signal: stderr does not say how to resume"
  leftovers=$(find "$dir" -name '*.tmp')
  [[ -z "$leftovers" ]] && ok "SIG$signal: no staging files left" ||
    fail "SIG$signal: staging files left: $leftovers"
  if $PY -c '
import sys, csv, h5py, json
d = sys.argv[1]
rows = list(csv.reader(open(d + "/history.csv")))
with h5py.File(d + "/frames.h5", "r") as f:
    assert len(f["frames"]) == len(rows) - 1, (len(f["frames"]), len(rows))
assert json.load(open(d + "/run.json"))["outcome"].startswith("stopped")
' "$dir" 2>"$TMP/stop_$signal.py"; then
    ok "SIG$signal: history.csv, frames.h5 (as many frames as rows) and run.json readable"
  else
    fail "SIG$signal: published outputs not readable or inconsistent: $(cat "$TMP/stop_$signal.py")"
  fi
  mp "resume_$signal" resume "$dir" --threads 2
  if [[ $rc -ne 0 ]]; then
    fail "SIG$signal: resume exited $rc"
    show "resume_$signal"
  else
    same_as_reference "SIG$signal then resume at 2 threads" "$dir"
    segments=$($PY -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["segments"]))' \
      "$dir/run.json")
    [[ $segments -eq 2 ]] && ok "SIG$signal: run.json lists 2 segments" ||
      fail "SIG$signal: run.json lists $segments segments, expected 2"
  fi
done

# ---- kills at random moments ---------------------------------------------------

KILLED=$TMP/killed
seed=${MPSOLID_TEST_SEED:-$RANDOM}
RANDOM=$seed
echo "kill moments from seed $seed (MPSOLID_TEST_SEED=$seed reproduces them)"
kills=0
attempt=0
done_ok=0
# completed DIR: run.json records the run completed (a kill can come after it
# is written, while the summary prints).
completed() {
  $PY -c 'import json,sys; sys.exit(json.load(open(sys.argv[1]))["outcome"] != "completed")' \
    "$1/run.json" 2>/dev/null
}
while [[ $attempt -lt 12 ]]; do
  attempt=$((attempt + 1))
  threads=$((RANDOM % 2 + 1))
  if completed "$KILLED"; then
    done_ok=1
    echo "  killed after run.json recorded the run completed"
    break
  fi
  if [[ -f "$KILLED/checkpoint.h5" ]]; then
    cmd=(resume "$KILLED" --threads "$threads")
  else
    # --force: a kill before the first checkpoint can leave published outputs.
    cmd=(run "$CASE" "${SHORT[@]}" --out "$KILLED" --threads "$threads" --force)
  fi
  if [[ $kills -ge 6 ]]; then  # enough: let it finish
    mp final "${cmd[@]}"
    [[ $rc -eq 0 ]] && done_ok=1 || { fail "final ${cmd[0]} exited $rc"; show final; }
    break
  fi
  delay=$(printf '0.%02d' $((RANDOM % 28 + 3)))
  "$BIN" "${cmd[@]}" </dev/null >"$TMP/kill.out" 2>"$TMP/kill.err" &
  pid=$!
  sleep "$delay"
  kill -KILL "$pid" 2>/dev/null
  { wait "$pid"; } 2>/dev/null
  rc=$?
  if [[ $rc -eq 0 ]]; then
    done_ok=1
    echo "  ${cmd[0]} finished before the kill at ${delay} s"
    break
  elif [[ $rc -eq 137 ]]; then
    kills=$((kills + 1))
    echo "  killed ${cmd[0]} (--threads $threads) after ${delay} s"
  else
    fail "${cmd[*]} exited $rc (not killed)"
    cat "$TMP/kill.err"
    break
  fi
done
if [[ $done_ok -eq 1 ]]; then
  ok "killed $kills times and resumed each time"
  same_as_reference "killed and resumed" "$KILLED"
  leftovers=$(find "$KILLED" -name '*.tmp')
  [[ -z "$leftovers" ]] && ok "killed and resumed: no temporary files left" ||
    fail "killed and resumed: temporary files left: $leftovers"
else
  fail "the killed run never completed"
fi

# ---- killed after the last checkpoint, before run.json ---------------------------

FINISH=$TMP/finish
cp -r "$REF" "$FINISH" && rm "$FINISH/run.json"
mp finish resume "$FINISH"
if [[ $rc -eq 0 ]] && completed "$FINISH" && grep -q "finishing it" "$TMP/finish.err"; then
  ok "killed before run.json: resume finishes it (exit 0, run.json completed)"
  same_as_reference "killed before run.json" "$FINISH"
else
  fail "killed before run.json: resume exited $rc or run.json does not record completion"
  show finish
fi
mp finish_again resume "$FINISH"
[[ $rc -eq 2 ]] && grep -q "already reached its end" "$TMP/finish_again.err" &&
  ok "finished: a second resume is refused (already reached its end)" ||
  { fail "finished: a second resume exited $rc"; show finish_again; }

# ---- going past the old end ------------------------------------------------------

HALF=$TMP/half
mp half run "$CASE" --set time.end=3e-5 --set output.frame_interval=3e-6 \
  --set output.checkpoint_interval=3e-6 --out "$HALF" --threads 2
mp extend resume "$HALF" --set time.end=6e-5 --threads 1
if [[ $rc -ne 0 ]]; then
  fail "resume --set time.end=6e-5 exited $rc"
  show extend
else
  same_as_reference "run to T, resume to 2T" "$HALF"
fi

# ---- contact: resumed through many Verlet-list rebuilds ------------------------

# The blocks collide between 1 and 2 ms; the list is rebuilt every ~12 steps.
# (The default history interval follows time.end: it is set here.)
CONTACT=cases/colliding_blocks.toml
CSETS=(--set output.history_interval=5e-5)
CREF=$TMP/contact_reference
mp contact_reference run "$CONTACT" "${CSETS[@]}" --set time.end=3e-3 --out "$CREF" --threads 1
CHALF=$TMP/contact_half
mp contact_half run "$CONTACT" "${CSETS[@]}" --set time.end=1.5e-3 --out "$CHALF" --threads 2
mp contact_extend resume "$CHALF" --set time.end=3e-3 --threads 1
resumed_as_reference contact "stopped mid-collision at 2 threads, resumed at 1" "$CREF" "$CHALF"

# ---- in space: a spinning cube with a quaternion per particle -------------------

# The paper model turns each particle's quaternion; gravity, a ramped force
# and a ramped pressure on its top push the cube, damped until 0.03 s: stopped at 2 threads, resumed
# at 1, it ends as the uninterrupted run.
SPACE=cases/spinning_cube.toml
SSETS=(--set l0=0.008 --set 'model="paper"' --set output.frame_interval=0.01
  --set output.history_interval=0.002 --set 'loads.g.type="acceleration"'
  --set 'loads.g.body="cube"' --set 'loads.g.acceleration=[1.0, 2.0, -9.81]'
  --set 'loads.push.body="cube"' --set 'loads.push.force=[0.5, 0.0, 1.0]'
  --set 'loads.push.history="ramp"' --set loads.push.rise_time=0.03
  --set damping.coefficient=5.0 --set damping.end=0.03 --set 'loads.blast.type="pressure"'
  --set 'loads.blast.body="cube"' --set loads.blast.pressure=2e3
  --set 'loads.blast.half_space={ point = [0.0, 0.0, 0.02], normal = [0.0, 0.3, 1.0] }'
  --set 'loads.blast.history="ramp"' --set loads.blast.rise_time=0.03)
SREF=$TMP/space_reference
mp space_reference run "$SPACE" "${SSETS[@]}" --set time.end=0.04 --out "$SREF" --threads 1
SHALF=$TMP/space_half
mp space_half run "$SPACE" "${SSETS[@]}" --set time.end=0.02 --out "$SHALF" --threads 2
mp space_extend resume "$SHALF" --set time.end=0.04 --threads 1
resumed_as_reference space "stopped at 2 threads, resumed at 1" "$SREF" "$SHALF"

# A rigid body in space: the struck sphere made rigid, stopped mid-collision
# at 2 threads and resumed at 1, keeps its pose, quaternion and angular
# momentum to the bit.
RSETS=(--set 'bodies.b.kind="rigid"' --set 'model="paper"' --set output.frame_interval=5e-4
  --set output.history_interval=5e-5)
RREF=$TMP/rigid_space_reference
mp rigid_space_reference run cases/colliding_spheres.toml "${RSETS[@]}" --set time.end=2e-3 --out "$RREF" --threads 1
RHALF=$TMP/rigid_space_half
mp rigid_space_half run cases/colliding_spheres.toml "${RSETS[@]}" --set time.end=1e-3 --out "$RHALF" --threads 2
mp rigid_space_extend resume "$RHALF" --set time.end=2e-3 --threads 1
resumed_as_reference rigid_space "a rigid sphere stopped mid-collision at 2 threads, resumed at 1" "$RREF" "$RHALF"

# ---- refusals ---------------------------------------------------------------------

# expect_refused LABEL DIR NEEDLE -- ARGS...: exit 2, NEEDLE on stderr, DIR unchanged.
expect_refused() {
  local label=$1 dir=$2 needle=$3
  shift 4
  local before
  before=$(snapshot "$dir")
  mp "$label" "$@"
  if [[ $rc -ne 2 ]]; then
    fail "$label: expected exit code 2, got $rc"
    show "$label"
  elif ! grep -qF -- "$needle" "$TMP/$label.err"; then
    fail "$label: stderr does not contain '$needle'"
    show "$label"
  elif [[ "$(snapshot "$dir")" != "$before" ]]; then
    fail "$label: the folder changed"
  else
    ok "$label: refused (exit 2): $(head -c 300 "$TMP/$label.err")"
  fi
}

mkdir -p "$TMP/empty"
expect_refused no_checkpoint "$TMP/empty" "no checkpoint" -- resume "$TMP/empty"
expect_refused already_done "$REF" "already reached" -- resume "$REF"
expect_refused set_physics "$REF" "keeps its case" -- resume "$REF" --set l0=0.001
expect_refused end_before "$REF" "before the checkpoint" -- resume "$REF" --set time.end=3e-5

TRUNC=$TMP/truncated
cp -r "$REF" "$TRUNC"
truncate -s $(($(stat -c %s "$TRUNC/checkpoint.h5") / 2)) "$TRUNC/checkpoint.h5"
expect_refused truncated "$TRUNC" "damaged" -- resume "$TRUNC" --set time.end=2e-4

FLIPPED=$TMP/flipped
cp -r "$REF" "$FLIPPED"
$PY - "$FLIPPED/checkpoint.h5" <<'PYEOF'
import sys, h5py
path = sys.argv[1]
with h5py.File(path, "r") as f:
    offset = f["particles/vx"].id.get_offset() + 1001  # a byte inside the velocities
with open(path, "r+b") as f:
    f.seek(offset)
    byte = f.read(1)
    f.seek(offset)
    f.write(bytes([byte[0] ^ 0x10]))
PYEOF
expect_refused flipped_byte "$FLIPPED" "damaged" -- resume "$FLIPPED" --set time.end=2e-4

NOTH5=$TMP/not_hdf5
cp -r "$REF" "$NOTH5"
echo "not a checkpoint" >"$NOTH5/checkpoint.h5"
expect_refused not_hdf5 "$NOTH5" "not an HDF5 file" -- resume "$NOTH5" --set time.end=2e-4

# A checkpoint of another case (another force: same lattice, same bonds) in
# this run's folder.
OTHER=$TMP/other
mp other run "$CASE" --set time.end=2e-5 --set loads.shock.force=[5000.0,0.0] --out "$OTHER" \
  --threads 1
FOREIGN=$TMP/foreign
cp -r "$REF" "$FOREIGN"
cp "$OTHER/checkpoint.h5" "$FOREIGN/checkpoint.h5"
expect_refused foreign_case "$FOREIGN" "different run or case" -- resume "$FOREIGN" --set time.end=2e-4

# A checkpoint of another lattice.
COARSE=$TMP/coarse
mp coarse run "$CASE" --set time.end=2e-5 --set l0=0.004 --out "$COARSE" --threads 1
LATTICE=$TMP/lattice
cp -r "$REF" "$LATTICE"
cp "$COARSE/checkpoint.h5" "$LATTICE/checkpoint.h5"
expect_refused foreign_lattice "$LATTICE" "different run or case" -- resume "$LATTICE" --set time.end=2e-4

echo
if [[ $failures -gt 0 ]]; then
  echo "test_resume: $failures check(s) FAILED"
  exit 1
fi
echo "test_resume: all checks passed"
