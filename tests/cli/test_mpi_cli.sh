#!/usr/bin/env bash
# The executable under mpirun (docs/mpi.md), where MPI is installed:
#  - the rod (paper model) at 2 and 3 ranks, and 2 ranks x 2 threads, gives
#    the serial run's bits: history.csv, every frame, the final checkpoint
#    (compare_runs.py);
#  - a checkpoint written at 2 ranks resumes at 1 and at 3 ranks to the
#    same bits, every rank reading its own rows (a damaged row is refused);
#  - contact (the colliding blocks) at 2 and 3 ranks (and on bands at 3),
#    and a 2-rank checkpoint written mid-collision resumed at 1 and 3 ranks
#    (and at 3 on bands), give the
#    serial bits, and the ranks' estimate of the stable step is the serial
#    one (and warns of a given dt above it the same way);
#  - a too soft contact stops a 2-rank run as it stops one rank (exit 3),
#    and so does an inverted bond (the same diagnosis and outputs);
#  - the finite-strain model at 2 ranks gives the serial bits too, and so
#    does the rod in space (its frames' surface marks from each rank's
#    bonds), resumed at 3 ranks;
#  - a blast-wave load at 2 ranks, and resumed at 3 mid-wave, too;
#  - a pressure load at 2 and 3 ranks, and resumed at 3, too, rank 0
#    holding no copy and no slice moving;
#  - the gas coupled to a panel at 2 and 3 ranks, and resumed at 3 ranks
#    during the shock's reflection, gives the serial bits, and so does the
#    rod in the gas at 3 ranks, rank 0 holding no copy, no slice moving;
#  - a square plate at 4 ranks, cut in blocks, gives the serial bits;
#  - a rigid rail along a strip, split between ranks by the cut (bands or
#    slabs), gives the serial bits at 2 and 3 ranks and resumed across rank
#    counts, run.json naming it split;
#  - SIGTERM to the launcher stops a 2-rank run with a checkpoint that
#    resumes to the serial bits;
#  - a bad case gets exit 2, one message (rank 0's) and nothing written;
#    bad input only a follower's part shows ends the job the same way;
#  - run.json records the ranks and, per rank, its particles, its passes'
#    times, and its halo time and bytes, and what rank 0 held: no copy of
#    the particles for the rod (every rank sets its own part up), its
#    resume and its compressed frames, and contact and its resume (rank 0
#    keeps a copy of the candidates only), a whole one for a checkpoint of
#    format 3 resumed at 2 ranks (the same bits as its resume on one rank);
#  - the particles stay on their ranks: no slice comes back to rank 0 for a
#    check, a history row, a frame or a checkpoint (run.json's slice_moves):
#    each rank writes its own particles' rows of the frames and checkpoints,
#    and sends a compressed frame's to rank 0 chunk by chunk of ids (a
#    frame of 200,338 particles in 4 chunks at 3 ranks: the serial bits).
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
export OMPI_MCA_btl_vader_single_copy_mechanism=none
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ok() { echo "ok: $*"; }
CASE=cases/shock_rod.toml
# 20,000 steps at l0 = 1 mm (the load on from the start), a frame and a
# checkpoint every 5,000.
SETS=(--set l0=0.001 --set output.frame_interval=5e-5 --set output.checkpoint_interval=5e-5)
mpi() {  # mpi RANKS LABEL ARGS...: mpsolid ARGS under the launcher; exit code in $rc
  local ranks=$1 label=$2
  shift 2
  timeout 300 "$MPIEXEC" -np "$ranks" --oversubscribe --allow-run-as-root "$BIN" "$@" \
    </dev/null >"$TMP/$label.out" 2>"$TMP/$label.err"
  rc=$?
}
same() {  # same LABEL DIR [SERIAL]: DIR has the serial run's bits (SERIAL: $TMP/serial)
  if /usr/bin/python3 tests/tools/compare_runs.py "${3:-$TMP/serial}" "$2" >"$TMP/$1.compare" 2>&1; then
    ok "$1: the serial run's bits ($(tail -n 1 "$TMP/$1.compare"))"
  else
    fail "$1 differs from the serial run:"
    sed 's/^/    /' "$TMP/$1.compare" | head -n 8
  fi
}

no_slice_moved() {  # no_slice_moved LABEL DIR: none came back to rank 0 (run.json)
  local moves
  moves=$(/usr/bin/python3 -c '
import json, sys
print(sum(x["slice_moves"] for x in json.load(open(sys.argv[1]))["per_rank"]))' "$2/run.json")
  [[ $moves == 0 ]] && ok "$1: no slice moved" || fail "$1: $moves slice moves"
}

copy_is() {  # copy_is LABEL DIR WANT: what rank 0 held of the particles (run.json)
  local got
  got=$(/usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["rank_zero_copy"])' \
    "$2/run.json" 2>&1)
  [[ $got == "$3" ]] && ok "$1: rank 0 held $3 of the particles" ||
    fail "$1: run.json's rank_zero_copy is $got (want $3)"
}

# no_copy_at RANKS LABEL NAME SERIAL ARGS...: `run ARGS` at RANKS ranks into
# $TMP/NAME has the serial run's bits, rank 0 holding no copy and no slice
# moving.
no_copy_at() {
  local ranks=$1 label=$2 name=$3 serial=$4
  shift 4
  mpi "$ranks" "$name" run "$@" --out "$TMP/$name"
  [[ $rc -eq 0 ]] && same "$label" "$TMP/$name" "$serial" || fail "$label: exit $rc"
  copy_is "$label" "$TMP/$name" none
  no_slice_moved "$label" "$TMP/$name"
}

# at_2_and_3 LABEL NAME SERIAL ARGS...: `run ARGS` on one thread serially
# into SERIAL, then at 2 and 3 ranks into $TMP/NAME2, $TMP/NAME3
# (no_copy_at).
at_2_and_3() {
  local label=$1 name=$2 serial=$3
  shift 3
  "$BIN" run "$@" --out "$serial" --threads 1 >/dev/null 2>&1 </dev/null ||
    fail "$label: the serial run failed"
  for ranks in 2 3; do
    no_copy_at "$ranks" "$label at $ranks ranks" "$name$ranks" "$serial" "$@" --threads 1
  done
}

"$BIN" run "$CASE" "${SETS[@]}" --set time.end=2e-4 --out "$TMP/serial" --threads 1 \
  >/dev/null 2>&1 </dev/null || { fail "the serial run failed"; exit 1; }

for ranks in 2 3; do
  mpi "$ranks" "ranks$ranks" run "$CASE" "${SETS[@]}" --set time.end=2e-4 --out "$TMP/ranks$ranks"
  if [[ $rc -ne 0 ]]; then
    fail "$ranks ranks: exit $rc"
    sed 's/^/    /' "$TMP/ranks$ranks.err" | head -n 8
    continue
  fi
  same "$ranks ranks" "$TMP/ranks$ranks"
  copy_is "$ranks ranks" "$TMP/ranks$ranks" none
  recorded=$(/usr/bin/python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))
rows = r.get("per_rank", [])
ok = (len(rows) == r["ranks"] and sum(x["owned_particles"] for x in rows) == r["particles"]
      and all(x["halo_bytes_sent"] > 0 and x["halo_seconds"] >= 0 and x["strain_seconds"] > 0
              and x["forces_seconds"] > 0 and x["ghosts"] > 0 for x in rows))
print(r["ranks"], "with an entry per rank" if ok else "WITHOUT a whole entry per rank")' \
    "$TMP/ranks$ranks/run.json")
  [[ $recorded == "$ranks with an entry per rank" ]] &&
    ok "$ranks ranks: run.json says ranks = $recorded" ||
    fail "$ranks ranks: run.json says ranks = $recorded"
done

# The rod cut both ways at 3 ranks (--cut): the serial bits either way,
# run.json's cut names it, and the bands (across the rod's length) hold
# fewer ghosts than the slabs (along it). A cut of another name is bad
# input.
for cut in slabs bands; do
  mpi 3 "cut_$cut" run "$CASE" "${SETS[@]}" --set time.end=2e-4 --cut "$cut" \
    --out "$TMP/cut_$cut"
  [[ $rc -eq 0 ]] && same "3 ranks, --cut $cut" "$TMP/cut_$cut" || fail "--cut $cut: exit $rc"
done
cuts=$(/usr/bin/python3 -c '
import json, sys
runs = [json.load(open(p)) for p in sys.argv[1:]]
ghosts = [sum(x["ghosts"] for x in r["per_rank"]) for r in runs]
print(runs[0]["cut"]["kind"], "|", runs[1]["cut"]["kind"], "|", ghosts[1] < ghosts[0])' \
  "$TMP/cut_slabs/run.json" "$TMP/cut_bands/run.json" 2>&1)
[[ $cuts == "slabs | bands along x | True" ]] &&
  ok "--cut: run.json names each cut, and the bands hold fewer ghosts" ||
  fail "--cut: run.json's cuts and fewer ghosts for bands: $cuts"
mpi 2 cut_bad run "$CASE" "${SETS[@]}" --cut diagonal --out "$TMP/cut_bad"
[[ $rc -eq 2 && ! -e "$TMP/cut_bad" ]] && grep -q "diagonal not in {auto,slabs,bands,blocks}" \
  "$TMP/cut_bad.err" && ok "--cut diagonal: exit 2, the allowed values named, nothing written" ||
  fail "--cut diagonal: exit $rc"

# A square plate spinning at 4 ranks: the cut chosen is blocks (quarters),
# with the serial bits.
PLATE_SETS=(--set time.end=2e-3 --set output.frame_interval=1e-3 --set output.checkpoint_interval=1e-3
  --set output.history_interval=2e-4)
"$BIN" run cases/spinning_plate.toml "${PLATE_SETS[@]}" --out "$TMP/plate_serial" --threads 1 \
  >/dev/null 2>&1 </dev/null || fail "the serial spinning plate failed"
mpi 4 plate4 run cases/spinning_plate.toml "${PLATE_SETS[@]}" --out "$TMP/plate4"
[[ $rc -eq 0 ]] && same "the spinning plate at 4 ranks" "$TMP/plate4" "$TMP/plate_serial" ||
  fail "the spinning plate at 4 ranks: exit $rc"
/usr/bin/python3 -c 'import json, sys; sys.exit(json.load(open(sys.argv[1]))["cut"]["kind"] != "blocks")' \
  "$TMP/plate4/run.json" && ok "the spinning plate at 4 ranks: cut in blocks" ||
  fail "the spinning plate at 4 ranks: not cut in blocks"

# A rigid rail along a strip, a quarter of the particles (more than a tenth
# of a rank's share): the cut splits it between ranks (bands at 2 and 3,
# slabs at 4 when asked), each rank holding some of it projects it with the
# others; the serial bits, run.json naming it split, and a checkpoint
# written at 3 ranks resumes at 2 to the same bits.
RAIL=tests/support/strip_on_a_rail.toml
at_2_and_3 "a rail split between ranks" rail "$TMP/rail_serial" "$RAIL"
mpi 4 rail_slabs run "$RAIL" --cut slabs --out "$TMP/rail_slabs"
[[ $rc -eq 0 ]] && same "the rail on slabs at 4 ranks" "$TMP/rail_slabs" "$TMP/rail_serial" ||
  fail "the rail on slabs: exit $rc"
split=$(/usr/bin/python3 -c '
import json, sys
print(" | ".join(",".join(json.load(open(p))["cut"]["split_rigid_bodies"]) for p in sys.argv[1:]))' \
  "$TMP/rail2/run.json" "$TMP/rail3/run.json" "$TMP/rail_slabs/run.json" 2>&1)
[[ $split == "rail | rail | rail" ]] && ok "the rail: run.json names it split at 2, 3 ranks and on slabs at 4" ||
  fail "the rail: run.json's split rigid bodies: $split"
mpi 3 rail_half run "$RAIL" --set time.end=0.002 --out "$TMP/rail_half"
mpi 2 rail_resume resume "$TMP/rail_half" --set time.end=0.004
[[ $rc -eq 0 ]] && same "the rail at 3 ranks, resumed at 2" "$TMP/rail_half" "$TMP/rail_serial" ||
  fail "the rail resumed at 2 ranks: exit $rc"

# A 2-rank run NAME with SETTINGS against the serial run in $TMP/sparse_serial:
# the same outputs, and each rank's slice moved to rank 0 MOVES times
# (run.json's slice_moves, each move a whole slice of 48 bytes per
# particle): the checks and the 4 history rows read the ranks' shares, the
# frames and checkpoints are written by every rank.
slices_move_at_the_reads() {
  local name=$1 what=$2 want=$3
  shift 3
  mpi 2 "$name" run "$CASE" "${SETS[@]}" "$@" --out "$TMP/$name"
  if [[ $rc -ne 0 ]]; then
    fail "2 ranks, $what: exit $rc"
    return
  fi
  same "2 ranks, $what" "$TMP/$name" "$TMP/sparse_serial"
  local moves
  moves=$(/usr/bin/python3 -c '
import json, sys
rows = json.load(open(sys.argv[1]))["per_rank"]
print(" ".join(str(x["slice_moves"]) for x in rows),
      all(x["slice_bytes"] >= x["slice_moves"] * 48 * x["owned_particles"] for x in rows))' \
    "$TMP/$name/run.json")
  [[ $moves == "$want $want True" ]] &&
    ok "2 ranks, $what: each rank's slice moved $want times" ||
    fail "2 ranks, $what: slice moves per rank and bytes: $moves (want $want $want True)"
}

# The particles stay on their ranks between batches: with checks and history
# rows every 2,500 steps, the batches (2,000 steps, then 500) send no slice
# out again, and bring them back only for the frame and the checkpoints.
SPARSE=(--set output.history_interval=2.5e-5 --set time.end=1e-4)
"$BIN" run "$CASE" "${SETS[@]}" "${SPARSE[@]}" --set stability.check_interval=2500 \
  --out "$TMP/sparse_serial" --threads 1 >/dev/null 2>&1 </dev/null ||
  fail "the serial run with sparse checks failed"
slices_move_at_the_reads sparse "sparse checks" 0 "${SPARSE[@]}" \
  --set stability.check_interval=2500
# A check and a history row read each rank's share of their figures and the
# last good state stays on the ranks: with a check every 100 steps (100
# checks), still no move, and the serial outputs.
slices_move_at_the_reads frequent "a check every 100 steps" 0 "${SPARSE[@]}" \
  --set stability.check_interval=100
# Compressed frames are written by rank 0 from the ranks' rows sent chunk
# by chunk of ids: no slice moves, rank 0 holds no copy, and the frames
# hold the same numbers.
slices_move_at_the_reads compressed "compressed frames" 0 "${SPARSE[@]}" \
  --set output.compression=4
copy_is "compressed frames" "$TMP/compressed" none
# 200,338 particles: 4 chunks of 65,536 ids, the ranks' ranges across them.
BIG=(--set l0=1.5e-4 --set time.end=2e-8 --set time.dt=1e-8 --set output.frame_interval=1e-8
  --set output.compression=1)
"$BIN" run "$CASE" "${BIG[@]}" --out "$TMP/chunks_serial" --threads 1 >/dev/null 2>&1 </dev/null ||
  fail "the serial run of 200,338 particles failed"
mpi 3 chunks run "$CASE" "${BIG[@]}" --out "$TMP/chunks"
[[ $rc -eq 0 ]] && same "compressed frames in 4 chunks at 3 ranks" "$TMP/chunks" \
  "$TMP/chunks_serial" || fail "compressed frames in 4 chunks at 3 ranks: exit $rc"

# Ranks x threads: 2 x 2.
mpi 2 threads2 run "$CASE" "${SETS[@]}" --set time.end=2e-4 --out "$TMP/threads2" --threads 2
[[ $rc -eq 0 ]] && same "2 ranks x 2 threads" "$TMP/threads2" || fail "2 ranks x 2 threads: exit $rc"

# A varying load (a blast wave: its factor, last centroid and work travel
# with the plate's rank) at 2 ranks, and resumed at 3 mid-wave.
BLAST=(--set 'loads.shock.history="friedlander"' --set loads.shock.duration=6e-5
  --set loads.shock.decay=1.5)
"$BIN" run "$CASE" "${SETS[@]}" "${BLAST[@]}" --set time.end=1e-4 --out "$TMP/blast_serial" \
  --threads 1 >/dev/null 2>&1 </dev/null || fail "the serial blast-wave run failed"
mpi 2 blast run "$CASE" "${SETS[@]}" "${BLAST[@]}" --set time.end=1e-4 --out "$TMP/blast"
[[ $rc -eq 0 ]] && same "2 ranks, blast wave" "$TMP/blast" "$TMP/blast_serial" ||
  fail "2 ranks, blast wave: exit $rc"
mpi 2 blast_half run "$CASE" "${SETS[@]}" "${BLAST[@]}" --set time.end=5e-5 --out "$TMP/blast_half"
mpi 3 blast_resume resume "$TMP/blast_half" --set time.end=1e-4
[[ $rc -eq 0 ]] && same "blast wave at 2 ranks, resumed at 3" "$TMP/blast_half" "$TMP/blast_serial" ||
  fail "blast wave resumed at 3 ranks: exit $rc"

# A pressure load on the plate (every rank holds each node, positioning
# those it hosts; a check's work from the nodes' positions the ranks send)
# at 2 and 3 ranks and resumed at 3: rank 0 holds no copy, no slice moves.
P_CASE=cases/shock_rod_pressure.toml
P_SETS=(--set output.frame_interval=5e-5 --set output.checkpoint_interval=1e-4
  --set output.history_interval=1e-5)
at_2_and_3 pressure pressure "$TMP/p_serial" "$P_CASE" "${P_SETS[@]}" --set time.end=2e-4
mpi 2 p_half run "$P_CASE" "${P_SETS[@]}" --set time.end=1e-4 --out "$TMP/p_half"
mpi 3 p_resume resume "$TMP/p_half" --set time.end=2e-4
[[ $rc -eq 0 ]] && same "pressure at 2 ranks, resumed at 3" "$TMP/p_half" "$TMP/p_serial" ||
  fail "pressure resumed at 3 ranks: exit $rc"
copy_is "pressure at 2 ranks, resumed at 3" "$TMP/p_half" none

# Half the run at 2 ranks, the rest at 1 and at 3 (each rank reading its own
# rows of the checkpoint, rank 0 holding no copy).
mpi 2 half run "$CASE" "${SETS[@]}" --set time.end=1e-4 --out "$TMP/half"
cp -r "$TMP/half" "$TMP/half3"
cp -r "$TMP/half" "$TMP/damaged"
"$BIN" resume "$TMP/half" --set time.end=2e-4 --threads 1 >/dev/null 2>"$TMP/resume1.err" </dev/null &&
  same "2 ranks, resumed at 1" "$TMP/half" || fail "resume at 1 rank failed: $(cat "$TMP/resume1.err")"
mpi 3 resume3 resume "$TMP/half3" --set time.end=2e-4
[[ $rc -eq 0 ]] && same "2 ranks, resumed at 3" "$TMP/half3" || fail "resume at 3 ranks: exit $rc"
copy_is "a resume at 3 ranks" "$TMP/half3" none
# A changed byte in a particle row only the last rank reads is found by the
# ranks' hashes: refused with exit 2, the folder as it was.
/usr/bin/python3 - "$TMP/damaged/checkpoint.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    ds = f["particles/x"]
    at = ds.id.get_offset() + 8 * (ds.shape[0] - 1) + 3  # the last id's x
with open(sys.argv[1], "r+b") as f:
    f.seek(at)
    b = f.read(1)
    f.seek(at)
    f.write(bytes([b[0] ^ 0x10]))
PY
before=$(md5sum "$TMP/damaged/"* | md5sum)
mpi 3 damaged resume "$TMP/damaged" --set time.end=2e-4
if [[ $rc -eq 2 ]] && grep -q "damaged checkpoint" "$TMP/damaged.err" &&
  [[ $(md5sum "$TMP/damaged/"* | md5sum) == "$before" ]]; then
  ok "a damaged particle row: refused at 3 ranks (exit 2), the folder as it was"
else
  fail "a damaged particle row at 3 ranks: exit $rc: $(head -c 400 "$TMP/damaged.err")"
fi

# A batch system's SIGTERM to the launcher (which forwards it to every
# rank) stops the run with a checkpoint and releases every rank; the run
# resumed (at 1 rank: other counts are tested above) gives the serial bits.
"$MPIEXEC" -np 2 --oversubscribe --allow-run-as-root "$BIN" run "$CASE" "${SETS[@]}" \
  --set time.end=2e-4 --out "$TMP/term" </dev/null >"$TMP/term.out" 2>"$TMP/term.err" &
launcher=$!
# Soon after the first checkpoint, well before the end.
for _ in $(seq 1000); do [[ -f "$TMP/term/checkpoint.h5" ]] && break; sleep 0.01; done
sleep 0.05
kill -TERM "$launcher"
waited=0
while kill -0 "$launcher" 2>/dev/null && [[ $waited -lt 120 ]]; do sleep 0.5; waited=$((waited + 1)); done
if kill -0 "$launcher" 2>/dev/null; then
  kill -KILL "$launcher"
  fail "SIGTERM at 2 ranks: the job still ran a minute after the signal"
else
  wait "$launcher"
  stopped=$(/usr/bin/python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))
print(r["outcome"], r["final_step"] > 0)' "$TMP/term/run.json" 2>&1)
  if [[ $stopped == "completed True" ]]; then
    echo "note: the 2-rank run ended before SIGTERM arrived; nothing to check"
  elif [[ $stopped == "stopped by SIGTERM True" ]]; then
    ok "SIGTERM at 2 ranks: stopped with a checkpoint, every rank ended"
    "$BIN" resume "$TMP/term" --threads 1 >/dev/null 2>"$TMP/term_resume.err" </dev/null &&
      same "SIGTERM at 2 ranks, resumed" "$TMP/term" ||
      fail "SIGTERM at 2 ranks, resumed: $(head -c 600 "$TMP/term_resume.err")"
  else
    fail "SIGTERM at 2 ranks: run.json says $stopped (want: stopped by SIGTERM)"
    sed 's/^/    /' "$TMP/term.err" | head -n 8
  fi
fi

# Contact: the colliding blocks (finite_strain) at l0 = 0.5 mm (seven
# chunks: every rank owns some) through the collision at 2 and 3 ranks, and
# a 2-rank checkpoint written mid-collision resumed at 1 and at 3 ranks.
# Rank 0 keeps no copy of the particles (only of the contact candidates,
# whose positions each check brings), and no slice moves.
C_CASE=cases/colliding_blocks.toml
C_SETS=(--set l0=0.0005 --set output.frame_interval=3e-4 --set output.checkpoint_interval=3e-4
  --set output.history_interval=1e-5)
at_2_and_3 contact contact "$TMP/c_serial" "$C_CASE" "${C_SETS[@]}" --set time.end=2.4e-3
# time.dt = "auto" is estimated on every rank's part, contact's bound
# included: the serial estimate's bits (run.json).
for ranks in 2 3; do
  /usr/bin/python3 -c '
import json, sys
a, b = (json.load(open(f))["stable_step"] for f in sys.argv[1:])
sys.exit(0 if (a["omega_max"], a["iterations"]) == (b["omega_max"], b["iterations"]) else 1)' \
    "$TMP/c_serial/run.json" "$TMP/contact$ranks/run.json" 2>/dev/null &&
    ok "contact at $ranks ranks: the serial stable-step estimate, bit for bit" ||
    fail "contact at $ranks ranks: run.json's stable_step differs from the serial run's"
done
# A given dt above the limit: the same warning from the ranks' estimate.
"$BIN" run "$CASE" --set time.dt=2e-5 --set time.end=2e-5 --out "$TMP/warn_serial" --threads 1 \
  </dev/null >/dev/null 2>"$TMP/warn_serial.err"
mpi 2 warn2 run "$CASE" --set time.dt=2e-5 --set time.end=2e-5 --out "$TMP/warn2"
if grep -q "is above the stable step" "$TMP/warn_serial.err" &&
  diff <(grep "warning:" "$TMP/warn_serial.err") <(grep "warning:" "$TMP/warn2.err") >/dev/null; then
  ok "a dt above the limit at 2 ranks: the serial run's warning"
else
  fail "a dt above the limit at 2 ranks: the warning differs or is missing"
  sed 's/^/    /' "$TMP/warn2.err" | head -n 4
fi
mpi 2 c_half run "$C_CASE" "${C_SETS[@]}" --set time.end=1.2e-3 --out "$TMP/c_half"
cp -r "$TMP/c_half" "$TMP/c_half3"
cp -r "$TMP/c_half" "$TMP/c_half_bands"
"$BIN" resume "$TMP/c_half" --set time.end=2.4e-3 --threads 1 >/dev/null 2>&1 </dev/null &&
  same "contact, 2 ranks resumed at 1" "$TMP/c_half" "$TMP/c_serial" ||
  fail "contact: resume at 1 rank failed"
mpi 3 c_resume3 resume "$TMP/c_half3" --set time.end=2.4e-3
[[ $rc -eq 0 ]] && same "contact, 2 ranks resumed at 3" "$TMP/c_half3" "$TMP/c_serial" ||
  fail "contact: resume at 3 ranks: exit $rc"
copy_is "contact, 2 ranks resumed at 3" "$TMP/c_half3" none
# Contact on bands at 3 ranks (each rank's candidates are runs of the
# candidate order, the ranks' interleaved), and the 2-rank checkpoint
# resumed at 3 on bands: the serial bits, rank 0's contact figures too.
mpi 3 c_bands run "$C_CASE" "${C_SETS[@]}" --set time.end=2.4e-3 --cut bands --out "$TMP/c_bands"
[[ $rc -eq 0 ]] && same "contact on bands at 3 ranks" "$TMP/c_bands" "$TMP/c_serial" ||
  fail "contact on bands at 3 ranks: exit $rc"
/usr/bin/python3 -c 'import json, sys; sys.exit(json.load(open(sys.argv[1]))["cut"]["kind"] != "bands along x")' \
  "$TMP/c_bands/run.json" &&
  ok "contact on bands: run.json names the bands" || fail "contact on bands: not cut in bands"
mpi 3 c_resume_bands resume "$TMP/c_half_bands" --set time.end=2.4e-3 --cut bands
[[ $rc -eq 0 ]] && same "contact, 2 ranks resumed at 3 on bands" "$TMP/c_half_bands" "$TMP/c_serial" ||
  fail "contact: resume at 3 ranks on bands: exit $rc"
touched=$(/usr/bin/python3 -c '
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("in contact" if max(float(r["contact_energy"]) for r in rows) > 0 else "never touched")' \
  "$TMP/c_serial/history.csv")
[[ $touched == "in contact" ]] && ok "contact: the blocks collide" || fail "contact: $touched"

# A contact too soft for the impact at 2 ranks: the interpenetration check
# stops the run with the one-rank run's exit code and names the pair.
mpi 2 soft run "$C_CASE" --set contact.stiffness=1e4 --out "$TMP/soft"
[[ $rc -eq 3 ]] && grep -q "too close to (not bonded) particle 640" "$TMP/soft.err" &&
  ok "interpenetration at 2 ranks: exit 3, the pair named" ||
  { fail "interpenetration at 2 ranks: exit $rc"; sed 's/^/    /' "$TMP/soft.err" | head -n 4; }

# A blow-up at 2 ranks (the paper model at 55.9 kN inverts a bond near
# 0.69 ms): the one-rank run's exit code, diagnosis and outputs. Over ranks
# rank 0 holds no model: the ranks' strain passes give its integrity check.
BU_SETS=(--set model=paper --set l0=0.002 --set time.end=1.2e-3)
"$BIN" run cases/shock_rod_55kN_short_wall.toml "${BU_SETS[@]}" --out "$TMP/bu_serial" \
  --threads 1 >/dev/null 2>"$TMP/bu_serial.err" </dev/null
serial_rc=$?
mpi 2 bu2 run cases/shock_rod_55kN_short_wall.toml "${BU_SETS[@]}" --out "$TMP/bu2"
if [[ $serial_rc -eq 3 && $rc -eq 3 ]] &&
  diff <(grep "unstable:" "$TMP/bu_serial.err") <(grep "unstable:" "$TMP/bu2.err") >/dev/null; then
  same "a blow-up at 2 ranks: exit 3, the same diagnosis and" "$TMP/bu2" "$TMP/bu_serial"
else
  fail "a blow-up at 2 ranks: exit $rc (serial $serial_rc), or another diagnosis:"
  grep -h "unstable:" "$TMP/bu_serial.err" "$TMP/bu2.err" | cut -c1-200 | sed 's/^/    /'
fi

# The finite-strain model (three halos a step) at 2 ranks: the 55.9 kN rod.
FS_SETS=(--set l0=0.002 --set time.end=2e-4 --set output.frame_interval=5e-5)
"$BIN" run cases/shock_rod_55kN_short_wall.toml "${FS_SETS[@]}" --out "$TMP/fs_serial" --threads 1 \
  >/dev/null 2>&1 </dev/null || fail "the finite_strain serial run failed"
mpi 2 fs2 run cases/shock_rod_55kN_short_wall.toml "${FS_SETS[@]}" --out "$TMP/fs2"
if [[ $rc -eq 0 ]] && /usr/bin/python3 tests/tools/compare_runs.py "$TMP/fs_serial" "$TMP/fs2" \
  >"$TMP/fs2.compare" 2>&1; then
  ok "finite_strain at 2 ranks: the serial run's bits ($(tail -n 1 "$TMP/fs2.compare"))"
else
  fail "finite_strain at 2 ranks (exit $rc) differs from the serial run:"
  sed 's/^/    /' "$TMP/fs2.compare" "$TMP/fs2.err" | head -n 8
fi

# The rod in space (finite_strain, 24,300 particles) at 2 ranks: the serial
# bits, its frames (the surface marks from each rank's bonds) and
# checkpoints written by every rank, no slice moved; resumed at 3 ranks.
S3_SETS=(--set output.frame_interval=5e-5 --set output.history_interval=1e-5
  --set output.checkpoint_interval=5e-5)
"$BIN" run cases/shock_rod_3d.toml "${S3_SETS[@]}" --set time.end=1e-4 --out "$TMP/s3_serial" \
  --threads 1 >/dev/null 2>&1 </dev/null || fail "the serial run in space failed"
mpi 2 space2 run cases/shock_rod_3d.toml "${S3_SETS[@]}" --set time.end=5e-5 --out "$TMP/space2"
[[ $rc -eq 0 ]] || fail "the rod in space at 2 ranks: exit $rc"
no_slice_moved "the rod in space at 2 ranks" "$TMP/space2"
mpi 3 space3 resume "$TMP/space2" --set time.end=1e-4
[[ $rc -eq 0 ]] && same "the rod in space, 2 ranks resumed at 3" "$TMP/space2" "$TMP/s3_serial" ||
  fail "the rod in space, 2 ranks resumed at 3: exit $rc"

# A bad case: exit 2, one message (rank 0's) naming the key and its range,
# nothing written, and no rank left waiting.
mpi 2 bad run "$CASE" --set time.end=1e-6 --set contact.distance=3 --out "$TMP/bad"
[[ $rc -eq 2 ]] && ok "a bad case at 2 ranks: exit 2" || fail "a bad case at 2 ranks: exit $rc"
messages=$(grep -c "contact.distance.*0.5" "$TMP/bad.err")
[[ $messages -eq 1 ]] && ok "a bad case at 2 ranks: one message" ||
  { fail "a bad case at 2 ranks: $messages messages:"; sed 's/^/    /' "$TMP/bad.err"; }
[[ ! -e "$TMP/bad" ]] && ok "a bad case at 2 ranks: nothing written" ||
  fail "a bad case at 2 ranks: $TMP/bad was created"

# Bad input only a follower sees: a body one row thick that its own part
# holds (finite_strain's A^-1 is undefined there; rank 0 builds no model).
# The follower ends the job: exit 2, the one-rank run's message, nothing
# written.
sed 's/^model = "paper"/model = "finite_strain"/' "$CASE" >"$TMP/thin.toml"
printf '\n[bodies.thin]\nkind = "elastic"\nmaterial = "rubber"\nx = [0.2, 0.3]\ny = [0.0, 0.002]\n' \
  >>"$TMP/thin.toml"
mpi 2 thin run "$TMP/thin.toml" --set time.end=1e-6 --out "$TMP/thin"
if [[ $rc -eq 2 ]] && grep -q "has no neighbours off one line" "$TMP/thin.err" &&
  [[ ! -e "$TMP/thin" ]]; then
  ok "bad input on a follower: exit 2, its message, nothing written"
else
  fail "bad input on a follower: exit $rc"
  sed 's/^/    /' "$TMP/thin.err" | head -n 4
fi

# The gas (the Giordano panel, coarse, the shock started 2 mm from the panel
# so the panel is struck and bends within the run): 2 and 3 ranks, and a
# 2-rank checkpoint written during the shock's reflection resumed at 3
# ranks, give the serial bits (gas fields in every frame included), rank 0
# holding no copy and no slice moving (the gas's windows read the nodes
# each rank hosts).
GAS=(cases/giordano_panel.toml --set gas.cell=0.001 --set gas.shock.x=-0.002
  --set output.frame_interval=1e-5 --set output.checkpoint_interval=1e-5)
at_2_and_3 gas gas "$TMP/gas_serial" "${GAS[@]}" --set time.end=4e-5
mpi 2 gas_half run "${GAS[@]}" --set time.end=2e-5 --out "$TMP/gas_half" --threads 1
mpi 3 gas_resume resume "$TMP/gas_half" --set time.end=4e-5 --threads 1
[[ $rc -eq 0 ]] && same "gas at 2 ranks, resumed at 3 in the reflection" "$TMP/gas_half" \
  "$TMP/gas_serial" || fail "gas resumed at 3 ranks: exit $rc"
copy_is "gas at 2 ranks, resumed at 3" "$TMP/gas_half" none
# A checkpoint whose rows cannot be read in place (format 3, the regression
# data's: the rod at l0 = 4 mm after 1,000 steps) resumed at 2 ranks: rank
# 0 restores it whole and sends each rank its part (a whole copy), with the
# bits of its resume on one rank. Its run folder is the same run's outputs
# by this build, their run id made the checkpoint's.
"$BIN" run "$CASE" --set l0=0.004 --set time.end=1e-5 --out "$TMP/f3_one" --threads 1 \
  >/dev/null 2>&1 </dev/null || fail "the run for the format-3 checkpoint failed"
cp tests/regression/data/shock_rod_checkpoint_format3.h5 "$TMP/f3_one/checkpoint.h5"
/usr/bin/python3 -c '
import sys, h5py
run_id = h5py.File(sys.argv[1] + "/checkpoint.h5", "r").attrs["run_id"]
with h5py.File(sys.argv[1] + "/frames.h5", "r+") as frames:
    frames.attrs["run_id"] = run_id' "$TMP/f3_one"
cp -r "$TMP/f3_one" "$TMP/f3_two"
"$BIN" resume "$TMP/f3_one" --set time.end=2e-5 --threads 1 >/dev/null 2>&1 </dev/null ||
  fail "the format-3 checkpoint resumed on one rank failed"
mpi 2 f3_two resume "$TMP/f3_two" --set time.end=2e-5 --threads 1
[[ $rc -eq 0 ]] && same "a format-3 checkpoint resumed at 2 ranks" "$TMP/f3_two" "$TMP/f3_one" ||
  fail "a format-3 checkpoint resumed at 2 ranks: exit $rc"
copy_is "a format-3 checkpoint resumed at 2 ranks" "$TMP/f3_two" whole

# The rod struck through the gas: a rigid plate and a wall among the
# outlines (the wall's nodes hosted by the rank that owns it).
ROD_GAS=(cases/shock_rod_gas.toml --set time.end=1e-4 --set output.frame_interval=5e-5)
"$BIN" run "${ROD_GAS[@]}" --out "$TMP/rod_gas_serial" --threads 1 >/dev/null 2>&1 </dev/null ||
  fail "the serial run of the rod in the gas failed"
no_copy_at 3 "the rod in the gas at 3 ranks" rod_gas3 "$TMP/rod_gas_serial" "${ROD_GAS[@]}" \
  --threads 1

if [[ $failures -gt 0 ]]; then
  echo "test_mpi_cli: $failures check(s) FAILED"
  exit 1
fi
echo "test_mpi_cli: all checks passed"
