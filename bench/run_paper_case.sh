#!/usr/bin/env bash
# The end-to-end benchmark: the paper's case, cases/shock_rod.toml
# (1,130 particles, 1,000,000 steps of 10 ns), at each thread count given
# (default 1 2). Builds Release first if needed. Reports wall time, steps/s and
# particle-steps/s per thread count (from each run's run.json) and checks that
# history.csv is byte-identical between the thread counts (mpsolid promises
# the same bits at any thread count).
#   bench/run_paper_case.sh [THREADS...]
# Runs go to out/bench/paper_case/tN/; the table to out/bench/paper_case.md
# and .json. PAPER_END=T (seconds) shortens the runs, to try the script.
# Each full run takes 25-60 s on a 2-vCPU VM (docs/performance.md).
set -euo pipefail
cd "$(dirname "$0")/.."
threads=("$@")
[ ${#threads[@]} -gt 0 ] || threads=(1 2)
for t in "${threads[@]}"; do
  [[ "$t" =~ ^[1-9][0-9]*$ ]] || { echo "run_paper_case: thread count '$t' is not a positive integer" >&2; exit 2; }
done

# Build Release if needed (a no-op when up to date).
if [ ! -f build/release/CMakeCache.txt ]; then
  cmake --preset release >/dev/null || { echo "run_paper_case: cmake --preset release failed" >&2; exit 1; }
fi
cmake --build --preset release --target mpsolid -j "$(nproc)" >/dev/null \
  || { echo "run_paper_case: building mpsolid failed (cmake --build --preset release)" >&2; exit 1; }
exe=build/release/mpsolid

out=out/bench/paper_case
mkdir -p "$out"
extra=()
[ -z "${PAPER_END:-}" ] || extra=(--set "time.end=$PAPER_END")
for t in "${threads[@]}"; do
  echo "run_paper_case: cases/shock_rod.toml at $t thread(s) -> $out/t$t" >&2
  rc=0
  "$exe" run cases/shock_rod.toml --out "$out/t$t" --threads "$t" --fixed-threads --force "${extra[@]}" || rc=$?
  if [ "$rc" -ne 0 ]; then
    echo "run_paper_case: mpsolid exited with $rc at $t thread(s) (see $out/t$t/run.json)" >&2
    exit 1
  fi
done

# The table, and the bit-identity of history.csv against the first thread count.
/usr/bin/python3 - "$out" "${threads[@]}" <<'EOF'
import hashlib, json, pathlib, sys
out, threads = pathlib.Path(sys.argv[1]), sys.argv[2:]
rows, ref = [], None
for t in threads:
    rep = json.loads((out / f"t{t}" / "run.json").read_text())
    history = (out / f"t{t}" / "history.csv").read_bytes()
    ref = history if ref is None else ref
    rows.append({"threads": int(t), "particles": rep["particles"], "steps": rep["steps"],
                 "wall_seconds": rep["wall_seconds"], "steps_per_second": rep["steps_per_second"],
                 "particle_steps_per_second": rep["particle_steps_per_second"],
                 "git_commit": rep["git_commit"],
                 "history_sha256": hashlib.sha256(history).hexdigest(),
                 "history_identical_to_first": history == ref})
lines = ["| threads | particles | steps | wall (s) | steps/s | particle-steps/s | speed-up | history.csv |",
         "| --- | --- | --- | --- | --- | --- | --- | --- |"]
for r in rows:
    lines.append(f"| {r['threads']} | {r['particles']:,} | {r['steps']:,} | {r['wall_seconds']:.1f} "
                 f"| {r['steps_per_second']:,.0f} | {r['particle_steps_per_second'] / 1e6:.2f} M "
                 f"| {rows[0]['wall_seconds'] / r['wall_seconds']:.2f}x "
                 f"| {'identical' if r['history_identical_to_first'] else 'DIFFERS'} |")
lines.append(f"\nmpsolid {rows[0]['git_commit']}, cases/shock_rod.toml; wall time from run.json "
             "(set-up, outputs and checkpoints included); speed-up and history.csv against "
             f"{rows[0]['threads']} thread(s). Command: bench/run_paper_case.sh {' '.join(threads)}\n")
table = "\n".join(lines)
(out.parent / "paper_case.md").write_text(table)
(out.parent / "paper_case.json").write_text(json.dumps(rows, indent=2) + "\n")
print(table)
if not all(r["history_identical_to_first"] for r in rows):
    sys.exit("run_paper_case: history.csv DIFFERS between thread counts")
EOF
