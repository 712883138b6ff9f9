#!/usr/bin/python3
"""Two threads against one, and against two MPI ranks, on the paper's rod.

  bench/thread_speedup.py [--l0 2e-3 1e-3 5e-4] [--models paper paper_conservative
                          finite_strain] [--reps 3] [--out out/bench]

For every repetition, size and model it runs, back to back and in an order
that rotates between repetitions: mpsolid at 1 thread, at 2 threads
(--fixed-threads: the solver's own speed-up, no governor), at 2 MPI ranks
of 1 thread each (mpirun -np 2), and two 1-thread runs side by side (what
two independent processes get from the machine together: the ceiling of
any parallel run here). Steps: 100,000 at 2 mm, 200 us of simulated time
(20,000 steps) finer. Rates are particle-steps per second of the time loop
(run.json's wall time less set-up, output and checkpoints); the table gives
medians and each speed-up over 1 thread of the same repetition's median.
The 2-thread runs' crossing between threads per step (run.json's
threads_as_ranks) is reported too.

Writes OUT/thread_speedup.md and OUT/thread_speedup.json; the runs go to
OUT/thread_speedup_runs/ (overwritten).
"""
import argparse
import datetime
import json
import os
import pathlib
import platform
import shutil
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from compare_lammps import (REPO, DT, cpu_model, fail, fixed_threads_flag,  # noqa: E402
                            mpsolid_command, mpsolid_result, run, run_data, summary)

MODES = ["1 thread", "2 threads", "2 ranks", "2 processes"]


def steps_at(l0):
    return 100_000 if l0 >= 2e-3 else round(200e-6 / DT)


def run_mode(exe, folder, l0, steps, model, mode, fixed):
    """Loop seconds per run of one mode (two for the side-by-side pair)."""
    shutil.rmtree(folder, ignore_errors=True)
    if mode == "2 processes":
        procs, folders = [], [folder / "a", folder / "b"]
        for f in folders:
            cmd = mpsolid_command(exe, f, l0, steps, 1, model, fixed)
            procs.append(subprocess.Popen([str(c) for c in cmd], stdout=subprocess.DEVNULL,
                                          stderr=subprocess.DEVNULL))
        if any(p.wait() != 0 for p in procs):
            fail(f"a side-by-side run in {folder} failed")
        return [mpsolid_result(f, steps)["seconds"] for f in folders]
    threads = 2 if mode == "2 threads" else 1
    launcher = []
    if mode == "2 ranks":
        root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
        launcher = ["mpirun", *root, "--oversubscribe", "--bind-to", "none", "-np", "2"]
    run([*launcher, *mpsolid_command(exe, folder, l0, steps, threads, model, fixed)],
        env=dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none"))
    return [mpsolid_result(folder, steps)["seconds"]]


def crossing(folder):
    info = run_data.read_info(folder)
    t = info.get("threads_as_ranks")
    return t["crossing_per_step"] if t else None


def markdown(meta, rows):
    lines = [
        "| model | l0 (mm) | particles | steps | 1 thread (M particle-steps/s) "
        "| 2 threads | 2 ranks | 2 processes side by side | lines crossing per step (2 threads) |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        one = r["rates"]["1 thread"]["median"]
        cells = [f"{one / 1e6:.2f}"] + [
            f"{r['rates'][m]['median'] / 1e6:.2f} ({r['rates'][m]['median'] / one:.2f}x)"
            for m in MODES[1:]]
        c = r["crossing"]
        lines.append(f"| {r['model']} | {r['l0'] * 1e3:g} | {r['particles']} | {r['steps']} | "
                     + " | ".join(cells) + f" | {c['cache_lines']:.0f} ({c['bytes']:.0f} B) |")
    lines.append("")
    lines.append(f"{meta['cpu']}, {meta['cores']} cores, {meta['started']}; mpsolid "
                 f"{meta['mpsolid_commit']}; medians of {meta['reps']} interleaved "
                 f"repetitions; `{meta['command']}`")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--l0", type=float, nargs="+", default=[2e-3, 1e-3, 5e-4])
    ap.add_argument("--models", nargs="+",
                    default=["paper", "paper_conservative", "finite_strain"])
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--out", type=pathlib.Path, default=REPO / "out" / "bench")
    ap.add_argument("--mpsolid", type=pathlib.Path, default=REPO / "build/release/mpsolid")
    args = ap.parse_args()
    if not os.access(args.mpsolid, os.X_OK):
        fail(f"no mpsolid executable at {args.mpsolid}")
    if not shutil.which("mpirun"):
        fail("no mpirun for the 2-rank runs")
    fixed = fixed_threads_flag(args.mpsolid)
    runs_dir = args.out / "thread_speedup_runs"
    shutil.rmtree(runs_dir, ignore_errors=True)
    started = datetime.datetime.now().isoformat(timespec="seconds")
    samples, facts = {}, {}
    for rep in range(args.reps):
        for l0 in args.l0:
            steps = steps_at(l0)
            for model in args.models:
                order = MODES[rep % 4:] + MODES[:rep % 4]
                line = []
                for mode in order:
                    folder = runs_dir / f"{model}_{l0 * 1e3:g}mm_{mode.replace(' ', '_')}"
                    seconds = run_mode(args.mpsolid, folder, l0, steps, model, mode, fixed)
                    first = folder / "a" if mode == "2 processes" else folder
                    r = mpsolid_result(first, steps)
                    # The pair's rate is the two processes' together: what the
                    # machine gives two workers that share nothing.
                    rate = sum(r["particles"] * steps / s for s in seconds)
                    samples.setdefault((l0, model, mode), []).append(rate)
                    facts[(l0, model)] = r
                    if mode == "2 threads":
                        facts[(l0, model, "crossing")] = crossing(folder)
                    line.append(f"{mode} {rate / 1e6:.2f}")
                print(f"rep {rep + 1}/{args.reps} {model} l0 {l0 * 1e3:g} mm: "
                      + ", ".join(line) + " M particle-steps/s", flush=True)
    rows = []
    for model in args.models:
        for l0 in args.l0:
            rates = {m: summary(samples[(l0, model, m)]) for m in MODES}
            rows.append({"model": model, "l0": l0, "steps": steps_at(l0),
                         "particles": facts[(l0, model)]["particles"], "rates": rates,
                         "speedup": {m: rates[m]["median"] / rates["1 thread"]["median"]
                                     for m in MODES},
                         "crossing": facts[(l0, model, "crossing")]})
    meta = {"started": started, "finished": datetime.datetime.now().isoformat(timespec="seconds"),
            "host": platform.node(), "cpu": cpu_model(), "cores": os.cpu_count(),
            "mpsolid_commit": next(iter(facts.values()))["git_commit"], "reps": args.reps,
            "command": " ".join([pathlib.Path(sys.argv[0]).name] + sys.argv[1:])}
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "thread_speedup.json").write_text(
        json.dumps({"meta": meta, "rows": rows}, indent=2) + "\n")
    (args.out / "thread_speedup.md").write_text(markdown(meta, rows))
    print(markdown(meta, rows))


if __name__ == "__main__":
    main()
