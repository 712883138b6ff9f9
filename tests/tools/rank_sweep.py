#!/usr/bin/python3
"""Runs every case in cases/, shortened, on one process and under mpirun at
several rank and thread counts, and checks each run has the serial run's
bits (compare_runs.py), what rank 0 held of the particles and how many
slices came back to it (run.json).

    /usr/bin/python3 tests/tools/rank_sweep.py build/release/mpsolid mpirun \
        [--ranks 2 3 4] [--threads 1 2] [--steps 100] [--only NAME ...]

Each case runs about `--steps` of its own steps (its dt, given or chosen,
read from the refusal of a too short run), with a frame and a checkpoint
every half of them and a history row every tenth. One line per case;
exits 1 if any run differs from its serial run or ends otherwise. About 25
minutes for the 21 cases at 2, 3 and 4 ranks x 1 and 2 threads on 2 cores:
a check by hand, not a CI test (docs/mpi.md).
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def case_dt(mpsolid, case, scratch, env):
    """The case's step, from the refusal of a run shorter than it."""
    err = subprocess.run([mpsolid, "run", case, "--set", "time.end=1e-15", "--out", scratch,
                          "--threads", "1"], capture_output=True, text=True, env=env).stderr
    found = re.search(r"\[([0-9.e+-]+), inf\)", err) or re.search(r"chose \(([0-9.e+-]+) s", err)
    if not found:
        raise RuntimeError(f"no step in: {err.strip()[:300]}")
    return float(found.group(1))


def rank_facts(folder):
    run = json.load(open(os.path.join(folder, "run.json")))
    return run.get("rank_zero_copy"), sum(r["slice_moves"] for r in run.get("per_rank", []))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mpsolid")
    parser.add_argument("mpirun")
    parser.add_argument("--ranks", type=int, nargs="+", default=[2, 3, 4])
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--steps", type=int, default=100)
    parser.add_argument("--only", nargs="+", help="case names (default: every case)")
    args = parser.parse_args()
    mpsolid = os.path.abspath(args.mpsolid)
    env = dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none")
    cases = sorted(glob.glob(os.path.join(ROOT, "cases", "*.toml")))
    if args.only:
        cases = [c for c in cases if os.path.basename(c)[:-5] in args.only]
    failures = 0
    with tempfile.TemporaryDirectory() as scratch:
        for case in cases:
            name = os.path.basename(case)[:-5]
            try:
                dt = case_dt(mpsolid, case, os.path.join(scratch, "probe"), env)
            except RuntimeError as e:
                print(f"{name}: {e}", flush=True)
                failures += 1
                continue
            n = args.steps
            sets = []
            for key, value in (("time.end", n * dt), ("output.frame_interval", n // 2 * dt),
                               ("output.checkpoint_interval", n // 2 * dt),
                               ("output.history_interval", n // 10 * dt)):
                sets += ["--set", f"{key}={value:.6g}"]
            serial = os.path.join(scratch, f"{name}_serial")
            one = subprocess.run([mpsolid, "run", case, *sets, "--out", serial, "--threads", "1"],
                                 capture_output=True, text=True, env=env)
            if one.returncode not in (0, 3):
                print(f"{name}: the serial run ended {one.returncode}: {one.stderr.strip()[-300:]}",
                      flush=True)
                failures += 1
                continue
            results = []
            for ranks in args.ranks:
                for threads in args.threads:
                    label = f"{ranks}x{threads}"
                    out = os.path.join(scratch, f"{name}_{label}")
                    run = subprocess.run(
                        [args.mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks),
                         mpsolid, "run", case, *sets, "--out", out, "--threads", str(threads),
                         "--fixed-threads"], capture_output=True, text=True, env=env)
                    if run.returncode != one.returncode:
                        failures += 1
                        results.append(f"{label}: ended {run.returncode}, serial {one.returncode}")
                        continue
                    compared = subprocess.run([sys.executable, os.path.join(HERE, "compare_runs.py"),
                                               serial, out], capture_output=True, text=True)
                    copy, moves = rank_facts(out)
                    same = compared.returncode == 0
                    failures += 0 if same else 1
                    results.append(f"{label}: {'same' if same else 'DIFFERENT'} copy={copy} "
                                   f"moves={moves}")
                    shutil.rmtree(out, ignore_errors=True)
            shutil.rmtree(serial, ignore_errors=True)
            print(f"{name} (dt {dt:.4g} s, exit {one.returncode}): " + "; ".join(results), flush=True)
    print(f"rank_sweep: {len(cases)} cases, {failures} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
