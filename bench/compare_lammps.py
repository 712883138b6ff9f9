#!/usr/bin/python3
"""Peer comparison: mpsolid's full models against LAMMPS on a
plain harmonic bond network with the same particles and bonds
(bench/lammps/make_input.py), measured in the same run.

  bench/compare_lammps.py [--l0 2e-3 1e-3 5e-4 2.5e-4] [--threads 1 2] [--reps 5]
                          [--models paper paper_conservative finite_strain]
                          [--work 2.5e7] [--out out/bench] [--install-lammps]
                          [--case cases/shock_rod.toml]

The case is the paper's rod (cases/shock_rod.toml) or, in space, its 3D form
(--case cases/shock_rod_3d.toml: 32 bonds per interior particle); both codes
step it at dt = 1e-8 s.

For every repetition, size and thread count it runs mpsolid and LAMMPS back
to back (their order alternates between repetitions), so that the machine's
load (2 shared cores) hits both alike; it reports particle-steps per second
of the time loop (particles x steps / loop seconds) as median, min and max,
and the ratio mpsolid / LAMMPS. Loop seconds: LAMMPS's "Loop time"; for
mpsolid run.json's wall_seconds minus its setup, output and checkpoint
phases (the neighbours phase is inside setup). Both runs do the same number
of steps (--work particle-steps, at least 200 steps) at the case's dt.

Writes OUT/lammps_comparison.md and OUT/lammps_comparison.json; the runs'
files go to OUT/lammps_runs/ (overwritten).

LAMMPS is Debian's `lammps` package (apt-get install lammps). It is only a
benchmark dependency, so scripts/install_deps.sh does not install it: this
script fails with the command to run, or installs it with --install-lammps.
Threads for LAMMPS: OpenMP (-sf omp -pk omp N) when its build has the
OPENMP package, else MPI ranks (mpirun -np N); Debian 12's build has no
OPENMP package, so 2 "threads" are 2 MPI ranks there. The table says which.
"""
import argparse
import datetime
import json
import os
import pathlib
import platform
import re
import shutil
import statistics
import subprocess
import sys

REPO = pathlib.Path(__file__).resolve().parents[1]
CASE = REPO / "cases" / "shock_rod.toml"
DT = 1.0e-8  # both codes' dt (checked against run.json)
sys.path.insert(0, str(REPO / "tools"))
from source_package import mpsolid_module  # noqa: E402

run_data = mpsolid_module("run_data")   # run.json, read through the package (numpy needed)


def fail(message):
    sys.exit(f"compare_lammps.py: {message}")


def run(cmd, **kw):
    """Runs a command; on failure prints its output and stops."""
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if r.returncode != 0:
        fail(f"command failed (exit {r.returncode}): {' '.join(map(str, cmd))}\n"
             f"{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r


def ensure_lammps(install):
    if shutil.which("lmp"):
        return
    if not install:
        fail("LAMMPS (lmp) is not installed. It is an optional benchmark dependency: install "
             "Debian's package with `apt-get update && apt-get install -y lammps` (as root), "
             "or rerun with --install-lammps")
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    print("compare_lammps: installing Debian's lammps package", flush=True)
    run(sudo + ["apt-get", "update", "-qq"], env=env)
    run(sudo + ["apt-get", "install", "-y", "-qq", "lammps"], env=env)
    if not shutil.which("lmp"):
        fail("apt-get installed lammps but there is no `lmp` on PATH")


def lammps_info():
    """LAMMPS version line and whether its build has the OPENMP package."""
    text = run(["lmp", "-h"]).stdout
    version = text.splitlines()[1].strip() if len(text.splitlines()) > 1 else "unknown"
    m = re.search(r"Installed packages:\s*\n(.*?)\n\s*\n", text, re.S)
    packages = m.group(1).split() if m else []
    return version, ("OPENMP" in packages or "USER-OMP" in packages)


def lammps_command(threads, openmp):
    base = ["lmp", "-nocite", "-screen", "none", "-log", "log.lammps", "-in", "in.rod"]
    if threads == 1:
        return base
    if openmp:
        return base + ["-sf", "omp", "-pk", "omp", str(threads)]
    if not shutil.which("mpirun"):
        fail(f"LAMMPS has no OPENMP package and there is no mpirun for {threads} ranks")
    root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    return ["mpirun", *root, "-np", str(threads), *base]


def run_lammps(folder, threads, openmp):
    run(lammps_command(threads, openmp), cwd=folder)
    log = (folder / "log.lammps").read_text()
    m = re.search(r"Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", log)
    if not m:
        fail(f"no 'Loop time' line in {folder / 'log.lammps'}")
    seconds, steps, atoms = float(m.group(1)), int(m.group(3)), int(m.group(4))
    bonds = re.findall(r"^\s*\d+\s+\d+\s+(\d+)\s+\S+\s*$", log, re.M)  # thermo: step atoms bonds ke
    return {"seconds": seconds, "steps": steps, "particles": atoms,
            "bonds": int(bonds[-1]) if bonds else None}


def fixed_threads_flag(exe):
    """--fixed-threads where the build has it (a scaling measurement must not
    let a busy moment change the team size); older builds keep it anyway."""
    return ["--fixed-threads"] if "--fixed-threads" in run([exe, "run", "--help"]).stdout else []


def mpsolid_command(exe, folder, l0, steps, threads, model, fixed, case=CASE):
    """The run of `steps` steps of the case at l0 with `model` (no frames
    between, checkpoints only at the ends)."""
    end = steps * DT
    return [exe, "run", case, "--out", folder, "--threads", threads, *fixed,
            "--set", f"l0={l0!r}", "--set", f"time.dt={DT!r}",
            "--set", f"model={model}",
            "--set", f"time.end={end!r}",
            "--set", f"output.frame_interval={end!r}", "--set", f"output.history_interval={end!r}",
            "--set", "output.checkpoint_interval=0"]


def mpsolid_result(folder, steps):
    """What a finished run's run.json says: its time-loop seconds (wall less
    set-up, output and checkpoints), steps, particles, bonds and commit."""
    rep = run_data.read_info(folder)
    if rep["outcome"] != "completed" or rep["steps"] != steps or rep["dt"] != DT:
        fail(f"{folder / 'run.json'}: outcome {rep['outcome']}, {rep['steps']} steps, "
             f"dt {rep['dt']}; expected completed, {steps}, {DT}")
    ph = rep["phase_seconds"]
    missing = [k for k in ("setup", "output", "checkpoint") if k not in ph]
    if missing:
        fail(f"{folder / 'run.json'} has no phase_seconds {missing}: update this script")
    seconds = rep["wall_seconds"] - ph["setup"] - ph["output"] - ph["checkpoint"]
    return {"seconds": seconds, "steps": steps, "particles": rep["particles"],
            "bonds": rep["bonds"], "git_commit": rep["git_commit"]}


def run_mpsolid(exe, folder, l0, steps, threads, model, fixed, launcher=(), case=CASE):
    shutil.rmtree(folder, ignore_errors=True)  # the folder is this script's: a fresh run
    run([*launcher, *mpsolid_command(exe, folder, l0, steps, threads, model, fixed, case)])
    return mpsolid_result(folder, steps)


def summary(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values),
            "samples": values}


def fmt_rate(s):
    return f"{s['median'] / 1e6:.2f} ({s['min'] / 1e6:.2f}-{s['max'] / 1e6:.2f})"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--l0", type=float, nargs="+", default=[2e-3, 1e-3, 5e-4, 2.5e-4],
                    help="lattice spacings (m)")
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--models", nargs="+", default=["paper"],
                    help="mpsolid models, each against the same LAMMPS runs (default paper)")
    ap.add_argument("--reps", type=int, default=5, help="repetitions (default 5)")
    ap.add_argument("--work", type=float, default=2.5e7,
                    help="particle-steps per run (default 2.5e7: a few seconds)")
    ap.add_argument("--out", type=pathlib.Path, default=REPO / "out" / "bench")
    ap.add_argument("--mpsolid", type=pathlib.Path, default=REPO / "build/release/mpsolid")
    ap.add_argument("--case", type=pathlib.Path, default=CASE,
                    help="the rod in the plane (default) or in space (cases/shock_rod_3d.toml)")
    ap.add_argument("--install-lammps", action="store_true",
                    help="apt-get install lammps if lmp is missing")
    args = ap.parse_args()
    if args.reps < 1 or args.work <= 0 or min(args.threads) < 1:
        fail("--reps, --work and --threads must be positive")
    if not os.access(args.mpsolid, os.X_OK):
        fail(f"no mpsolid executable at {args.mpsolid}: build it with "
             "`cmake --preset release && cmake --build --preset release`")
    ensure_lammps(args.install_lammps)
    fixed = fixed_threads_flag(args.mpsolid)
    lmp_version, openmp = lammps_info()
    parallel = "OpenMP (-sf omp -pk omp N)" if openmp else "MPI ranks (mpirun -np N)"

    runs_dir = args.out / "lammps_runs"
    shutil.rmtree(runs_dir, ignore_errors=True)
    sizes = []
    for l0 in args.l0:
        folder = runs_dir / f"lammps_l0_{l0 * 1e3:g}mm"
        # The particle count sets the steps; the generator knows it.
        generate = [sys.executable, REPO / "bench/lammps/make_input.py", "--out", folder,
                    "--case", args.case, "--l0", repr(l0), "--dt", repr(DT)]
        probe = json.loads(run([*generate, "--steps", "0"]).stdout)
        steps = max(200, round(args.work / probe["atoms"]))
        info = json.loads(run([*generate, "--steps", str(steps)]).stdout)
        sizes.append({"l0": l0, "steps": steps, "folder": folder, "info": info})

    started = datetime.datetime.now().isoformat(timespec="seconds")
    load_before = os.getloadavg()
    samples = {}  # (l0, threads, code) -> list of rates
    paired = {}  # (l0, threads) -> list of mpsolid/LAMMPS ratios, back to back
    facts = {}
    for rep in range(args.reps):
        for size in sizes:
            for threads in args.threads:
                codes = ["lammps"] + args.models
                order = codes if rep % 2 == 1 else codes[1:] + codes[:1]
                rates = {}
                for code in order:
                    if code == "lammps":
                        r = run_lammps(size["folder"], threads, openmp)
                    else:
                        folder = (runs_dir /
                                  f"mpsolid_{code}_l0_{size['l0'] * 1e3:g}mm_t{threads}")
                        r = run_mpsolid(args.mpsolid, folder, size["l0"], size["steps"], threads,
                                        code, fixed, case=args.case)
                    if r["particles"] != size["info"]["atoms"]:
                        fail(f"{code} ran {r['particles']} particles, expected "
                             f"{size['info']['atoms']}")
                    if r["bonds"] is not None and r["bonds"] != size["info"]["bonds"]:
                        fail(f"{code} has {r['bonds']} bonds, expected {size['info']['bonds']}")
                    rates[code] = r["particles"] * r["steps"] / r["seconds"]
                    samples.setdefault((size["l0"], threads, code), []).append(rates[code])
                    facts.setdefault("mpsolid" if code != "lammps" else code, r)
                for model in args.models:
                    paired.setdefault((size["l0"], threads, model), []).append(
                        rates[model] / rates["lammps"])
                print(f"rep {rep + 1}/{args.reps} l0 {size['l0'] * 1e3:g} mm, {threads} "
                      f"thread(s): " + ", ".join(f"{c} {rates[c] / 1e6:.2f}" for c in codes)
                      + " M particle-steps/s", flush=True)

    rows = []
    for model in args.models:
        for size in sizes:
            for threads in args.threads:
                ms = summary(samples[(size["l0"], threads, model)])
                lm = summary(samples[(size["l0"], threads, "lammps")])
                rows.append({"model": model, "l0": size["l0"],
                             "particles": size["info"]["atoms"], "bonds": size["info"]["bonds"],
                             "steps": size["steps"], "threads": threads, "mpsolid": ms,
                             "lammps": lm, "ratio": ms["median"] / lm["median"],
                             "paired_ratios": summary(paired[(size["l0"], threads, model)])})
    for row in rows:  # speed-up over 1 thread, per code
        one = next((r for r in rows if r["model"] == row["model"] and r["l0"] == row["l0"]
                    and r["threads"] == 1), None)
        if one:
            row["speedup"] = {c: row[c]["median"] / one[c]["median"] for c in ("mpsolid", "lammps")}

    meta = {
        "started": started,
        "finished": datetime.datetime.now().isoformat(timespec="seconds"),
        "host": platform.node(), "cpu": cpu_model(), "cores": os.cpu_count(),
        "load_average_before": load_before, "load_average_after": os.getloadavg(),
        "mpsolid_commit": facts["mpsolid"]["git_commit"], "lammps_version": lmp_version,
        "lammps_parallel": parallel, "reps": args.reps, "work": args.work,
        "command": " ".join([pathlib.Path(sys.argv[0]).name] + sys.argv[1:]),
    }
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "lammps_comparison.json").write_text(
        json.dumps({"meta": meta, "rows": rows}, indent=2) + "\n")
    (args.out / "lammps_comparison.md").write_text(markdown(meta, rows))
    print(markdown(meta, rows))
    print(f"compare_lammps: wrote {args.out / 'lammps_comparison.md'} and .json")


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def markdown(meta, rows):
    out = [
        "| model | l0 (mm) | particles | bonds | steps | threads | mpsolid (M particle-steps/s) "
        "| LAMMPS (M particle-steps/s) | mpsolid / LAMMPS | paired ratios (min-max) "
        "| speed-up 1 -> N: mpsolid, LAMMPS |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        speed = r.get("speedup")
        speed_text = (f"{speed['mpsolid']:.2f}x, {speed['lammps']:.2f}x"
                      if speed and r["threads"] != 1 else "")
        pr = r["paired_ratios"]
        out.append(
            f"| {r['model']} | {r['l0'] * 1e3:g} | {r['particles']:,} | {r['bonds']:,} | {r['steps']:,} "
            f"| {r['threads']} | {fmt_rate(r['mpsolid'])} | {fmt_rate(r['lammps'])} "
            f"| **{r['ratio']:.2f}** | {pr['min']:.2f}-{pr['max']:.2f} | {speed_text} |")
    out += [
        "",
        f"Medians (min-max) of {meta['reps']} repetitions, interleaved in one run "
        f"({meta['started']} to {meta['finished']}); {meta['cpu']}, {meta['cores']} cores, "
        f"load average {meta['load_average_before'][0]:.2f} before and "
        f"{meta['load_average_after'][0]:.2f} after. mpsolid {meta['mpsolid_commit']} "
        f"(Release); LAMMPS {meta['lammps_version']}, N threads = "
        f"{meta['lammps_parallel']}. Paired ratios: mpsolid / LAMMPS of the two runs made "
        "back to back in each repetition. Command: `bench/" + meta["command"] + "`.",
        "",
    ]
    return "\n".join(out)


if __name__ == "__main__":
    main()
