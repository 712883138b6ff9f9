#!/usr/bin/env bash
# The mpsolid executable end to end: exit codes, clear errors, nothing written
# on bad input, the outputs of a short good run, and that the resolved case
# reproduces the run.
#
#   bash tests/cli/test_cli.sh PATH_TO_MPSOLID    (from the repository root)
#
# Prints "ok: ..." per passing check and "FAIL: ..." per failing one; exits
# non-zero if any check failed.
set -u

if [[ $# -ne 1 ]]; then
  echo "usage: bash tests/cli/test_cli.sh PATH_TO_MPSOLID" >&2
  exit 2
fi
BIN=$(realpath -- "$1") || { echo "FAIL: no mpsolid binary at '$1'" >&2; exit 1; }
if [[ ! -x "$BIN" ]]; then
  echo "FAIL: '$BIN' is not an executable" >&2
  exit 1
fi
cd "$(dirname -- "${BASH_SOURCE[0]}")/../.." || exit 1
CASE=cases/shock_rod.toml
[[ -f "$CASE" ]] || { echo "FAIL: $CASE not found (run from the repository root)" >&2; exit 1; }

TMP=$(mktemp -d "${TMPDIR:-/tmp}/mpsolid_cli.XXXXXX") || exit 1
trap 'rm -rf -- "$TMP"' EXIT

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok: $*"; }

# mp LABEL ARGS...: runs mpsolid with ARGS (stdin closed, stderr not a
# terminal, a 5 minute cap); leaves the exit code in $rc and the output in
# $TMP/LABEL.out and $TMP/LABEL.err.
mp() {
  local label=$1
  shift
  timeout 300 "$BIN" "$@" </dev/null >"$TMP/$label.out" 2>"$TMP/$label.err"
  rc=$?
}

show() {  # the output of run LABEL, indented, for failure messages
  echo "    stdout: $(head -c 2000 "$TMP/$1.out")"
  echo "    stderr: $(head -c 2000 "$TMP/$1.err")"
}

# snapshot DIR: every file under DIR with its checksum, sorted.
snapshot() {
  (cd "$1" && find . -mindepth 1 -printf '%y %p\n' | sort && find . -type f -print0 | sort -z |
    xargs -0 -r sha256sum)
}

# A folder that already holds a previous run's history.csv.
SEEDED=$TMP/seeded
mkdir -p "$SEEDED"
printf 't,kinetic_energy\n0,0\n# known content from an earlier run\n' >"$SEEDED/history.csv"
SEEDED_BEFORE=$(snapshot "$SEEDED")

# expect_bad_input LABEL NEEDLE... -- ARGS...: mpsolid ARGS exits 2 with an
# error on stderr containing every NEEDLE, prints nothing on stdout, and
# leaves $SEEDED untouched (ARGS should point --out there).
expect_bad_input() {
  local label=$1
  shift
  local needles=()
  while [[ $# -gt 0 && $1 != -- ]]; do
    needles+=("$1")
    shift
  done
  shift
  mp "$label" "$@"
  local good=1
  if [[ $rc -ne 2 ]]; then
    fail "$label: expected exit code 2, got $rc (mpsolid $*)"
    show "$label"
    good=0
  fi
  if [[ ! -s "$TMP/$label.err" ]]; then
    fail "$label: nothing on stderr"
    good=0
  fi
  local needle
  for needle in "${needles[@]}"; do
    if ! grep -qF -- "$needle" "$TMP/$label.err"; then
      fail "$label: stderr does not contain '$needle'"
      show "$label"
      good=0
    fi
  done
  if [[ -s "$TMP/$label.out" ]]; then
    fail "$label: printed on stdout on bad input: $(head -c 500 "$TMP/$label.out")"
    good=0
  fi
  if [[ "$(snapshot "$SEEDED")" != "$SEEDED_BEFORE" ]]; then
    fail "$label: the --out folder changed on bad input:"
    (cd "$SEEDED" && find . -mindepth 1 | sed 's/^/    /')
    good=0
    # Reset it for the next check.
    rm -rf -- "$SEEDED"
    mkdir -p "$SEEDED"
    printf 't,kinetic_energy\n0,0\n# known content from an earlier run\n' >"$SEEDED/history.csv"
  fi
  # Again with --out naming a folder that does not exist: it is not created.
  local args=() arg absent="$TMP/absent_${label//[^A-Za-z0-9_]/_}"
  for arg in "$@"; do
    [[ $arg == "$SEEDED" ]] && arg=$absent/out
    args+=("$arg")
  done
  if [[ " ${args[*]} " == *" $absent/out "* ]]; then
    mp "$label.absent" "${args[@]}"
    if [[ $rc -ne 2 ]]; then
      fail "$label: with a new --out folder: expected exit code 2, got $rc"
      good=0
    fi
    if [[ -e "$absent" ]]; then
      fail "$label: the --out folder $absent/out was created on bad input"
      good=0
    fi
  fi
  [[ $good -eq 1 ]] && ok "$label: exit 2, clear error, nothing written"
}

# ---- (a) a bad case ----------------------------------------------------------

BAD=$TMP/bad_case.toml
sed 's/^nu = 0\.495/nu = 0.7/' "$CASE" >"$BAD"
if ! grep -q '^nu = 0\.7' "$BAD"; then
  fail "could not make the bad case (no 'nu = 0.495' line in $CASE)"
fi
expect_bad_input bad_nu "mpsolid: error:" "$BAD" "materials.rubber.nu" "(-1, 0.5)" -- \
  run "$BAD" --out "$SEEDED" --threads 2

# The same into a folder that does not exist: it must not be created.
ABSENT=$TMP/absent/out
mp bad_nu_absent run "$BAD" --out "$ABSENT" --threads 2
if [[ $rc -ne 2 ]]; then
  fail "bad_nu_absent: expected exit code 2, got $rc"
  show bad_nu_absent
elif [[ -e "$TMP/absent" ]]; then
  fail "bad_nu_absent: the --out folder (or its parent) was created on bad input"
else
  ok "bad_nu_absent: exit 2, --out folder not created"
fi

# Without --out the default folder out/<name> must not appear either.
(cd "$TMP" && timeout 300 "$BIN" run "$BAD" </dev/null >/dev/null 2>&1)
rc=$?
if [[ $rc -ne 2 ]]; then
  fail "bad_nu_default_out: expected exit code 2, got $rc"
elif [[ -e "$TMP/out" ]]; then
  fail "bad_nu_default_out: the default output folder $TMP/out was created on bad input"
else
  ok "bad_nu_default_out: exit 2, no default output folder"
fi

# Other bad cases, each a one-line change of the shipped case.
bad_variant() {  # bad_variant LABEL SED_EXPR KEY NEEDLE...
  local label=$1 expr=$2
  shift 2
  local file=$TMP/$label.toml
  sed "$expr" "$CASE" >"$file"
  if cmp -s "$file" "$CASE"; then
    fail "$label: the sed edit '$expr' did not change the case"
    return
  fi
  expect_bad_input "$label" "$file" "$@" -- run "$file" --out "$SEEDED" --threads 2
}
bad_variant unknown_key 's/^dt = 1\.0e-8 .*/&\ndtt = 1.0e-8/' "time.dtt" "unknown key"
bad_variant overlap 's/^x = \[-0\.006, 0\.0\]/x = [-0.006, 0.001]/' "bodies.plate" "bodies.rod" \
  "overlap"
bad_variant load_on_wall 's/^body = "plate"/body = "wall"/' "loads.shock.body" "wall"
bad_variant syntax 's/^E = 2\.8e6 .*/E = 2.8e6 Pa/' "syntax error"
bad_variant end_before_dt 's/^end = 0\.010 .*/end = 1e-9/' "time.end" "[dt, inf)"

# A missing case file.
expect_bad_input missing_file "$TMP/no_such_case.toml" -- \
  run "$TMP/no_such_case.toml" --out "$SEEDED"

# A lattice far too fine for this build (l0 = 0.1 pm) is bad input, found
# before anything is written.
expect_bad_input too_fine_l0 "l0" -- \
  run "$CASE" --set l0=1e-13 --set time.end=1e-8 --out "$SEEDED" --threads 2

# ---- (b) bad command lines -----------------------------------------------------

for set in "time.end" "=5" "time..end=1" "time.end="; do
  expect_bad_input "malformed_set[$set]" "--set" "$set" -- \
    run "$CASE" --set "$set" --out "$SEEDED" --threads 2
done
expect_bad_input set_wrong_type "--set" "time.dt=abc" "time.dt" -- \
  run "$CASE" --set time.dt=abc --out "$SEEDED" --threads 2
expect_bad_input set_under_value "--set" "l0.x=1" -- \
  run "$CASE" --set l0.x=1 --out "$SEEDED" --threads 2
expect_bad_input set_unknown_key "--set" "time.dtt" "unknown key" -- \
  run "$CASE" --set time.dtt=1e-8 --out "$SEEDED" --threads 2
expect_bad_input set_model_option "--set" "linear_elastic.hourglass" "[0, inf)" -- \
  run "$CASE" --set model=linear_elastic --set linear_elastic.hourglass=-1 --out "$SEEDED" --threads 2
expect_bad_input unknown_option "--bogus" -- run "$CASE" --bogus --out "$SEEDED"
expect_bad_input unknown_subcommand -- walk "$CASE" --out "$SEEDED"
expect_bad_input no_subcommand --
expect_bad_input no_case_file -- run --out "$SEEDED"
expect_bad_input zero_threads "--threads" -- run "$CASE" --threads 0 --out "$SEEDED"
expect_bad_input bad_threads "--threads" -- run "$CASE" --threads many --out "$SEEDED"

mp help --help
if [[ $rc -ne 0 || ! -s "$TMP/help.out" ]]; then
  fail "help: mpsolid --help should print usage and exit 0 (exit $rc)"
else
  ok "help: exit 0"
fi

# ---- (c) a short good run -------------------------------------------------------

OUT=$TMP/good
HEADER='t,kinetic_energy,strain_energy,external_work,momentum_x,momentum_y,angular_momentum,max_speed,plate.x,plate.y,plate.theta,rod.xmin,rod.xmax,rod.ymin,rod.ymax'
mp good run "$CASE" --set time.end=2e-5 --set output.frame_interval=1e-5 --set output.history_interval=1e-6 --out "$OUT" --threads 2
if [[ $rc -ne 0 ]]; then
  fail "good: expected exit code 0, got $rc"
  show good
else
  ok "good: exit 0"
fi
for f in history.csv frames.h5 frames.xdmf case.resolved.toml run.json checkpoint.h5; do
  if [[ -s "$OUT/$f" ]]; then ok "good: $f written"; else fail "good: $f missing or empty"; fi
done
if [[ -f "$OUT/history.csv" ]]; then
  first=$(head -n 1 "$OUT/history.csv")
  if [[ "$first" == "$HEADER"* ]]; then
    ok "good: history.csv header"
  else
    fail "good: history.csv header is '$first', expected it to begin with '$HEADER'"
  fi
  rows=$(($(wc -l <"$OUT/history.csv") - 1))
  if [[ $rows -eq 21 ]]; then
    ok "good: history.csv has 21 data rows"
  else
    fail "good: history.csv has $rows data rows, expected 21 (t = 0, 1e-6, ..., 2e-5)"
  fi
fi
if [[ -f "$OUT/frames.h5" ]]; then
  if [[ "$(head -c 8 "$OUT/frames.h5" | od -An -tx1 | tr -d ' \n')" == "894844460d0a1a0a" ]]; then
    ok "good: frames.h5 is an HDF5 file"
  else
    fail "good: frames.h5 does not start with the HDF5 signature"
  fi
fi
if [[ -f "$OUT/run.json" ]]; then
  for key in '"steps_per_second"' '"particle_steps_per_second"'; do
    if grep -qF -- "$key" "$OUT/run.json"; then
      ok "good: run.json has $key"
    else
      fail "good: run.json lacks $key"
    fi
  done
  if command -v python3 >/dev/null; then
    if python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$OUT/run.json" 2>/dev/null; then
      ok "good: run.json is valid JSON"
    else
      fail "good: run.json is not valid JSON"
    fi
  fi
fi
leftovers=$(find "$OUT" -name '*.tmp' 2>/dev/null)
if [[ -n "$leftovers" ]]; then
  fail "good: temporary files left behind: $leftovers"
else
  ok "good: no *.tmp files left"
fi
extra=$(cd "$OUT" 2>/dev/null && find . -mindepth 1 | sort |
  grep -vxF -e ./history.csv -e ./frames.h5 -e ./frames.xdmf -e ./case.resolved.toml \
    -e ./run.json -e ./checkpoint.h5)
if [[ -n "$extra" ]]; then
  fail "good: unexpected files in the output folder: $extra"
fi
# stdout: only the closing summary (first line "mpsolid: ...", the rest
# indented); stderr: nothing (no progress line: stderr is not a terminal).
if [[ -s "$TMP/good.err" ]]; then
  fail "good: stderr is not empty (progress or warnings when stderr is not a terminal): $(head -c 500 "$TMP/good.err")"
else
  ok "good: stderr is empty"
fi
if grep -q $'\r' "$TMP/good.out"; then
  fail "good: stdout contains a carriage return (a progress line)"
fi
if [[ "$(head -n 1 "$TMP/good.out")" != "mpsolid: shock_rod "* ]] ||
  tail -n +2 "$TMP/good.out" | grep -qv '^  '; then
  fail "good: stdout is more than the closing summary:"
  sed 's/^/    /' "$TMP/good.out"
else
  ok "good: stdout is just the summary"
fi
if ! grep -q "completed" "$TMP/good.out"; then
  fail "good: the summary does not say the run completed"
fi

# A given dt above the model's stable step: a warning before the first step
# naming the estimate and time.dt = "auto"; the run then stops unstable
# (exit 3) with its last good frame.
"$BIN" run "$CASE" --out "$TMP/too_big_dt" --set time.dt=2e-5 --set time.end=2e-3 \
  >"$TMP/too_big_dt.out" 2>"$TMP/too_big_dt.err" </dev/null
rc=$?
if [[ $rc -eq 3 ]] && grep -q '^mpsolid: warning: .*time.dt = 2e-05 s is above the stable step' \
  "$TMP/too_big_dt.err" && grep -qF 'time.dt = "auto"' "$TMP/too_big_dt.err" &&
  [[ "$(head -n 1 "$TMP/too_big_dt.err")" == "mpsolid: warning: "* ]]; then
  ok "a dt above the stable step: warned before the first step, then stopped (exit 3)"
else
  fail "a dt above the stable step: exit $rc, stderr: $(head -c 600 "$TMP/too_big_dt.err")"
fi

# A gas that goes unphysical (two streams flying apart at 200 km/s at
# CFL 1: the cell between them empties past zero pressure): exit 3, the
# diagnosis names the time, the cell and the quantity, run.json says the
# same, and the last good frame and history row stay.
cat >"$TMP/vacuum.toml" <<'TOML'
name = "vacuum"
model = "finite_strain"
l0 = 0.002
[materials.steel]
E = 220.0e9
nu = 0.3
rho = 7600.0
[bodies.block]
kind = "elastic"
material = "steel"
x = [0.0, 0.01]
y = [0.0, 0.01]
[time]
dt = "auto"
end = 1e-4
[output]
frame_interval = 1e-5
[gas]
cell = 0.001
x = [0.02, 0.22]
y = [0.0, 0.004]
left = "outflow"
right = "outflow"
cfl = 1.0
bodies = []
[gas.initial]
density = 1.2
pressure = 100000.0
velocity = [-100000.0, 0.0]
[gas.regions.right]
x = [0.12, 0.22]
y = [0.0, 0.004]
density = 1.2
pressure = 100000.0
velocity = [100000.0, 0.0]
TOML
mp vacuum run "$TMP/vacuum.toml" --out "$TMP/vacuum" --threads 2
if [[ $rc -eq 3 ]] &&
  grep -q '^mpsolid: unstable: unphysical gas at t = .*the gas went unphysical in cell (99, 0): density .* kg/m^3, pressure -.* Pa' "$TMP/vacuum.err" &&
  grep -q 'last frame of .*frames.h5' "$TMP/vacuum.err" &&
  /usr/bin/python3 - "$TMP/vacuum" <<'PY'
import json, sys, h5py
run = json.load(open(f"{sys.argv[1]}/run.json"))
d = run["diagnosis"]
assert run["outcome"] == "unstable" and d["criterion"] == "unphysical gas", run
assert "cell (99, 0)" in d["where"] and "pressure" in d["where"], d
with h5py.File(f"{sys.argv[1]}/frames.h5") as f:
    last = f["frames"][sorted(f["frames"])[-1]]
    assert last.attrs["step"] == d["last_good_step"], dict(last.attrs)
    p = last["gas_pressure"][()]
    assert (p > 0).all(), "the last frame's gas is the last good one"
rows = open(f"{sys.argv[1]}/history.csv").read().splitlines()
assert len(rows) >= 2 and float(rows[-1].split(",")[0]) == d["last_good_time"], rows[-1]
PY
then
  ok "an unphysical gas: stopped (exit 3) with the cell and the quantity, the last good frame kept"
else
  fail "an unphysical gas: exit $rc"
  show vacuum
fi

# ---- (d) the resolved case reproduces the run -----------------------------------

AGAIN=$TMP/again
if [[ -f "$OUT/case.resolved.toml" ]]; then
  cp "$OUT/case.resolved.toml" "$TMP/resolved.toml"
  mp again run "$TMP/resolved.toml" --out "$AGAIN" --threads 2
  if [[ $rc -ne 0 ]]; then
    fail "resolved: running case.resolved.toml exited $rc"
    show again
  elif cmp -s "$OUT/history.csv" "$AGAIN/history.csv"; then
    ok "resolved: case.resolved.toml gives an identical history.csv"
  else
    fail "resolved: case.resolved.toml gives a different history.csv:"
    diff "$OUT/history.csv" "$AGAIN/history.csv" | head -n 10 | sed 's/^/    /'
  fi
  if [[ -f "$AGAIN/case.resolved.toml" ]] &&
    ! diff -q <(grep -v '^#' "$OUT/case.resolved.toml") \
      <(grep -v '^#' "$AGAIN/case.resolved.toml") >/dev/null; then
    fail "resolved: resolving the resolved case changes it"
  fi
fi

# ---- (e) the command line and the run folder ------------------------------------

mp version --version
if [[ $rc -eq 0 ]] && grep -q '^mpsolid [0-9]' "$TMP/version.out" && grep -q 'git ' "$TMP/version.out" &&
  grep -q 'OpenMP' "$TMP/version.out" && grep -q 'MPI' "$TMP/version.out"; then
  ok "version: --version names the version, commit, compiler, OpenMP and MPI"
else
  fail "version: exit $rc"
  show version
fi

expect_bad_input case_is_folder "is a folder, not a case file" -- run cases --out "$SEEDED"
expect_bad_input end_overflows "time.end" "2^53" "steps" -- \
  run "$CASE" --set time.end=1e11 --out "$SEEDED" --threads 2
sed 's/^l0 = /lo = /' "$CASE" >"$TMP/typo.toml"
expect_bad_input typo_hint "l0 is missing" "'lo'" "a typo for 'l0'" -- \
  run "$TMP/typo.toml" --out "$SEEDED"
# expect_exit LABEL CODE NEEDLE -- ARGS...: mpsolid ARGS exits CODE with NEEDLE on stderr.
expect_exit() {
  local label=$1 code=$2 needle=$3
  shift 4
  mp "$label" "$@"
  if [[ $rc -eq $code ]] && grep -qF -- "$needle" "$TMP/$label.err"; then
    ok "$label: exit $code, '$needle'"
  else
    fail "$label: exit $rc, expected $code with '$needle'"
    show "$label"
  fi
}

# A contact too soft for the impact: the interpenetration check stops the
# run (exit 3), naming the pair that came too close.
expect_exit interpenetration 3 "too close to (not bonded) particle" -- \
  run cases/colliding_blocks.toml --set contact.stiffness=1e4 --out "$TMP/soft_contact" --threads 1

touch "$TMP/a_file"
expect_exit out_is_file 2 "$TMP/a_file: the output folder is a file" -- \
  run "$CASE" --set time.end=1e-7 --out "$TMP/a_file" --threads 1
expect_exit out_uncreatable 2 "$TMP/a_file/sub: cannot create the output folder" -- \
  run "$CASE" --set time.end=1e-7 --out "$TMP/a_file/sub" --threads 1

# Threads: OMP_NUM_THREADS is the default; a bad one is bad input; more
# threads than cores are warned about.
OMP_NUM_THREADS=abc expect_exit omp_bad 2 "OMP_NUM_THREADS = 'abc'" -- \
  run "$CASE" --set time.end=1e-7 --out "$TMP/omp_bad"
OMP_NUM_THREADS=1 mp omp_one run "$CASE" --set time.end=1e-7 --out "$TMP/omp_one"
if [[ $rc -eq 0 ]] && python3 -c 'import json,sys; sys.exit(json.load(open(sys.argv[1]))["threads"] != 1)' \
  "$TMP/omp_one/run.json"; then
  ok "omp_one: OMP_NUM_THREADS=1 runs 1 thread"
else
  fail "omp_one: exit $rc or run.json threads != 1"
  show omp_one
fi
# Waiting threads and the team sizes used are in run.json; --fixed-threads
# keeps the requested size (the governor may use fewer where they are faster).
mp fixed_threads run "$CASE" --set time.end=2e-5 --out "$TMP/fixed_threads" --threads 2 --fixed-threads
if [[ $rc -eq 0 ]] && python3 - "$TMP/fixed_threads/run.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
ok = (r["threads"] == 2 and list(r["team_size_seconds"]) == ["2"] and r["team_size_changes"] == 0
      and 0 <= r["thread_wait_share"] <= 1 and r["thread_wait_seconds"] >= 0
      and "thread_wait_share" in r["segments"][-1])
sys.exit(0 if ok else 1)
PY
then
  ok "fixed_threads: run.json has the wait and the team size, 2 threads throughout"
else
  fail "fixed_threads: exit $rc or run.json lacks the wait or the team sizes"
  show fixed_threads
fi
cores=$(nproc)
expect_exit oversubscribed 0 "warning: $((cores + 1)) threads" -- \
  run "$CASE" --set time.end=1e-7 --out "$TMP/oversubscribed" --threads $((cores + 1))

# Output times that are not whole steps are rounded with a note, kept in run.json.
mp notes run "$CASE" --set time.end=2.5e-7 --set output.frame_interval=1.05e-7 --out "$TMP/notes" \
  --threads 1
if [[ $rc -eq 0 ]] && grep -qF "note: output.frame_interval = 1.05e-07 s is 10.5 steps" "$TMP/notes.err" &&
  python3 -c 'import json,sys; sys.exit(not any("frame_interval" in n for n in json.load(open(sys.argv[1]))["notes"]))' \
    "$TMP/notes/run.json"; then
  ok "notes: a frame interval off the step grid is rounded with a note (stderr and run.json)"
else
  fail "notes: exit $rc, or no note"
  show notes
fi

# A case too large for the machine's memory is refused before set-up, with
# the estimate and what is available (l0 chosen for twice the available memory).
avail=$(awk '/^MemAvailable:/ {print $2 * 1024}' /proc/meminfo)
l0=$(awk -v a="$avail" 'BEGIN { l = sqrt(0.00452 * 1650 / (2 * a)); if (l < 4.5e-6) l = 4.5e-6; printf "%.3g", l }')
expect_bad_input memory "need about" "GiB" "available" "larger l0" -- \
  run "$CASE" --set "l0=$l0" --out "$SEEDED" --threads 1

# Two runs into one folder: the second (and a resume) is refused naming the
# owner, and the first completes with readable results.
LOCKED=$TMP/locked
timeout 300 "$BIN" run "$CASE" --set time.end=4e-4 --out "$LOCKED" --threads 1 \
  </dev/null >"$TMP/first.out" 2>"$TMP/first.err" &
first=$!
for _ in $(seq 100); do [[ -s "$LOCKED/.owner" ]] && break; sleep 0.05; done
mp second run "$CASE" --set time.end=1e-7 --out "$LOCKED" --threads 1
second_rc=$rc
mp second_resume resume "$LOCKED"
resume_rc=$rc
wait $first
first_rc=$?
if [[ $second_rc -eq 2 ]] && grep -qE "in use by another mpsolid run \(pid [0-9]+ on host $(hostname)" "$TMP/second.err" &&
  [[ $resume_rc -eq 2 ]] && grep -qF "in use by another mpsolid run" "$TMP/second_resume.err"; then
  ok "locked: a second run and a resume into a busy folder exit 2 naming the owner's pid and host"
else
  fail "locked: second run exit $second_rc, resume exit $resume_rc"
  show second
  show second_resume
fi
if [[ $first_rc -eq 0 ]] && [[ ! -e "$LOCKED/.owner" ]] &&
  python3 -c 'import json,sys; sys.exit(json.load(open(sys.argv[1]))["outcome"] != "completed")' \
    "$LOCKED/run.json" &&
  [[ $(wc -l <"$LOCKED/history.csv") -eq 42 ]] && ! grep -qaP '\x00' "$LOCKED/history.csv" &&
  /usr/bin/python3 -c 'import h5py,sys; f=h5py.File(sys.argv[1]); sys.exit(len(f["frames"]) != 2)' \
    "$LOCKED/frames.h5" 2>/dev/null; then
  ok "locked: the first run completed with intact results and released the folder"
else
  fail "locked: the first run's results are not intact (exit $first_rc)"
  cat "$TMP/first.err" | head -5
fi

# A run into a folder with an earlier run's results is refused (naming them)
# unless --force, which replaces them.
mp seeded_no_force run "$CASE" --set time.end=2e-5 --set output.frame_interval=1e-5 --set output.history_interval=1e-6 --out "$SEEDED" \
  --threads 2
if [[ $rc -eq 2 ]] && grep -qF "holds the results of an earlier run (history.csv)" \
  "$TMP/seeded_no_force.err" && grep -qF -- "--force" "$TMP/seeded_no_force.err" &&
  [[ "$(snapshot "$SEEDED")" == "$SEEDED_BEFORE" ]]; then
  ok "seeded_no_force: exit 2 naming the earlier results and --force; the folder untouched"
else
  fail "seeded_no_force: exit $rc, or the folder changed"
  show seeded_no_force
fi
# ... before the set-up: a case whose set-up would fail (a finite_strain rod
# one particle thick) is refused for the folder, not for the set-up.
mp seeded_before_setup run "$CASE" --set model=finite_strain --set 'bodies.rod.y=[-0.001,0.001]' \
  --out "$SEEDED" --threads 1
if [[ $rc -eq 2 ]] && grep -qF "holds the results of an earlier run" "$TMP/seeded_before_setup.err" &&
  ! grep -qF "deformation gradient" "$TMP/seeded_before_setup.err" &&
  [[ "$(snapshot "$SEEDED")" == "$SEEDED_BEFORE" ]]; then
  ok "seeded_before_setup: refused for the earlier results before the set-up ran"
else
  fail "seeded_before_setup: exit $rc, not refused for the earlier results first"
  show seeded_before_setup
fi
expect_exit repeat_no_force 2 "run.json: case shock_rod, model paper, completed at step 2000" -- \
  run "$CASE" --set time.end=2e-5 --set output.frame_interval=1e-5 \
  --set output.history_interval=1e-6 --out "$OUT" --threads 2

# --set in the folder name: runs of one case with other overrides do not collide.
(cd "$TMP" && timeout 300 "$BIN" run "$OLDPWD/$CASE" --set time.end=1e-7 --threads 1 \
  </dev/null >/dev/null 2>&1 &&
  timeout 300 "$BIN" run "$OLDPWD/$CASE" --set time.end=2e-7 --threads 1 </dev/null >/dev/null 2>&1)
folders=$(cd "$TMP/out" 2>/dev/null && ls -d shock_rod-* 2>/dev/null | wc -l)
if [[ $folders -eq 2 ]] && /usr/bin/python3 -c '
import glob, json, sys
sets = sorted(tuple(json.load(open(f))["overrides"]) for f in glob.glob(sys.argv[1] + "/out/shock_rod-*/run.json"))
sys.exit(sets != [("time.end=1e-7",), ("time.end=2e-7",)])' "$TMP"; then
  ok "default_out: other --set values go to other folders, the overrides in run.json"
else
  fail "default_out: expected 2 folders out/shock_rod-HASH with their overrides, got $folders"
fi

# --set before the case file: each --set takes one value.
mp set_first run --set time.end=1e-7 "$CASE" --threads 1 --out "$TMP/set_first"
[[ $rc -eq 0 ]] && ok "set_first: --set before the case file" ||
  { fail "set_first: exit $rc"; show set_first; }

# A good run into the seeded folder with --force replaces the old history.csv.
mp good_seeded run "$CASE" --set time.end=2e-5 --set output.frame_interval=1e-5 --set output.history_interval=1e-6 --out "$SEEDED" \
  --threads 2 --force
if [[ $rc -ne 0 ]]; then
  fail "good_seeded: exit $rc"
  show good_seeded
elif ! cmp -s "$SEEDED/history.csv" "$OUT/history.csv"; then
  fail "good_seeded: history.csv in a folder with an old one is not the new run's"
else
  ok "good_seeded: an old history.csv is replaced"
fi

echo
if [[ $failures -gt 0 ]]; then
  echo "test_cli: $failures check(s) FAILED"
  exit 1
fi
echo "test_cli: all checks passed"
