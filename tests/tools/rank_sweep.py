#!/usr/bin/python3
"""Runs every case in cases/, shortened, on one process and under mpirun at
several rank and thread counts, and checks each run has the serial run's
bits (compare_runs.py), what rank 0 held of the particles and how many
slices came back to it (run.json); and that a run stopped half way at the
first rank count resumes at each of the others (and at one rank) to the
serial run's bits.

    /usr/bin/python3 tests/tools/rank_sweep.py build/release/mpsolid mpirun \
        [--ranks 2 3 4] [--threads 1 2] [--steps 100] [--no-resume] [--only NAME ...]
        [--cut auto|slabs|bands|blocks]

Each case runs about `--steps` of its own steps (its dt, given or chosen,
read from the refusal of a too short run), with a frame and a checkpoint
every half of them and a history row every tenth. One line per case;
exits 1 if any run differs from its serial run or ends otherwise. About 22
minutes for the 21 cases at 2, 3 and 4 ranks x 1 and 2 threads with their
resumes on 2 cores: a check by hand (docs/mpi.md); ctest rank_sweep_quick
runs 4 cases at 2 ranks.
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
    """What rank 0 held, the slices moved, and the cut (with its split rigid bodies)."""
    run = json.load(open(os.path.join(folder, "run.json")))
    cut = run.get("cut", {})
    kind = cut.get("kind")
    if cut.get("split_rigid_bodies"):
        kind = f"{kind} (split: {','.join(cut['split_rigid_bodies'])})"
    return (run.get("rank_zero_copy"), sum(r["slice_moves"] for r in run.get("per_rank", [])),
            kind)


def launch(args, ranks, mpsolid, command, env):
    """mpsolid COMMAND under mpirun at `ranks` ranks (on one process at 1)."""
    prefix = [] if ranks == 1 else [args.mpirun, "--allow-run-as-root", "--oversubscribe", "-np",
                                    str(ranks)]
    return subprocess.run([*prefix, mpsolid, *command], capture_output=True, text=True, env=env)


def compare(serial, out):
    """Whether `out` has the serial run's bits, and compare_runs.py's first line."""
    compared = subprocess.run([sys.executable, os.path.join(HERE, "compare_runs.py"), serial, out],
                              capture_output=True, text=True)
    return compared.returncode == 0, (compared.stdout.strip().splitlines() or ["?"])[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mpsolid")
    parser.add_argument("mpirun")
    parser.add_argument("--ranks", type=int, nargs="+", default=[2, 3, 4])
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--steps", type=int, default=100)
    parser.add_argument("--no-resume", action="store_true", help="skip the resumes")
    parser.add_argument("--only", nargs="+", help="case names (default: every case)")
    parser.add_argument("--cut", default="auto", choices=["auto", "slabs", "bands", "blocks"],
                        help="mpsolid's --cut at every rank count")
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
                sets += ["--set", f"{key}={value!r}"]
            serial = os.path.join(scratch, f"{name}_serial")
            one = subprocess.run([mpsolid, "run", case, *sets, "--out", serial, "--threads", "1"],
                                 capture_output=True, text=True, env=env)
            if one.returncode not in (0, 3):
                print(f"{name}: the serial run ended {one.returncode}: {one.stderr.strip()[-300:]}",
                      flush=True)
                failures += 1
                continue
            results = []
            if one.returncode == 0 and not args.no_resume:
                # Half the run at the first rank count, the rest at every
                # other count and at one rank.
                half = os.path.join(scratch, f"{name}_half")
                shutil.rmtree(half, ignore_errors=True)
                first = args.ranks[0]
                ended = launch(args, first, mpsolid,
                               ["run", case, *sets, "--set", f"time.end={n // 2 * dt!r}", "--out",
                                half, "--threads", "1", "--cut", args.cut], env)
                for ranks in [r for r in [1, *args.ranks] if r != first]:
                    label = f"{first}->{ranks}"
                    folder = os.path.join(scratch, f"{name}_{label}")
                    shutil.rmtree(folder, ignore_errors=True)
                    if ended.returncode != 0:
                        failures += 1
                        results.append(f"{label}: the half run ended {ended.returncode}")
                        break
                    shutil.copytree(half, folder)
                    resumed = launch(args, ranks, mpsolid,
                                     ["resume", folder, "--set", f"time.end={n * dt!r}",
                                      "--threads", "1", "--cut", args.cut], env)
                    same, first_difference = compare(serial, folder)
                    same = same and resumed.returncode == 0
                    failures += 0 if same else 1
                    results.append(f"resumed {label}: " + ("same" if same else
                                   f"DIFFERENT (exit {resumed.returncode}: {first_difference})"))
                    shutil.rmtree(folder, ignore_errors=True)
                shutil.rmtree(half, ignore_errors=True)
            for ranks in args.ranks:
                for threads in args.threads:
                    label = f"{ranks}x{threads}"
                    out = os.path.join(scratch, f"{name}_{label}")
                    run = launch(args, ranks, mpsolid,
                                 ["run", case, *sets, "--out", out, "--threads", str(threads),
                                  "--fixed-threads", "--cut", args.cut], env)
                    if run.returncode != one.returncode:
                        failures += 1
                        results.append(f"{label}: ended {run.returncode}, serial {one.returncode}")
                        continue
                    copy, moves, cut = rank_facts(out)
                    same, first_difference = compare(serial, out)
                    # A cut asked for and not given.
                    if args.cut != "auto" and not (cut or "").startswith(args.cut):
                        same, first_difference = False, f"cut {cut}, not {args.cut}"
                    failures += 0 if same else 1
                    results.append(f"{label}: {'same' if same else 'DIFFERENT: ' + first_difference}"
                                   f" copy={copy} moves={moves} cut={cut}")
                    shutil.rmtree(out, ignore_errors=True)
            shutil.rmtree(serial, ignore_errors=True)
            print(f"{name} (dt {dt:.4g} s, exit {one.returncode}): " + "; ".join(results), flush=True)
    print(f"rank_sweep: {len(cases)} cases, {failures} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
