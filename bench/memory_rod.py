#!/usr/bin/python3
"""Memory of the rod case at large sizes: peak resident memory of a
short mpsolid run at each l0, its bytes per particle (bonds included), the
marginal bytes per particle between the sizes (fixed overheads cancel), and
the bytes the data structures should take (src/core/particle_store.hpp,
src/core/bonds.hpp), so that the measurement can be checked against the layout.

  bench/memory_rod.py [--l0 1.264e-4 6.32e-5] [--steps 10] [--threads 2] [--out out/bench]

l0 = 6.32e-5 m gives about 1,000,000 particles. Each run writes only a frame
at its start and its end and checkpoints only at the ends (a 1M-particle
frame is about 70 MB). Peak RSS comes from the kernel's rusage of the child
(ru_maxrss, as /usr/bin/time -v reports it). Writes OUT/memory_rod.md and .json;
the runs go to OUT/memory_runs/ (removed afterwards unless --keep).
"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parents[1]
CASE = REPO / "cases" / "shock_rod.toml"
DT = 1.0e-8
sys.path.insert(0, str(REPO / "tools"))
from source_package import mpsolid_module  # noqa: E402

run_data = mpsolid_module("run_data")   # run.json, read through the package (numpy needed)

# The layout at the time of writing (check against the headers when they change):
# ParticleStore: 19 double arrays (x, y, vx, vy, theta, omega, x0, y0, half_cos,
# half_sin, strain, pressure, fx, fy, torque, inv_mass, inv_inertia, lambda,
# mu), 3 int32 arrays (id, body, material), 1 int8 (kind); BondTable: a uint32
# row offset per particle and, per bond entry (each bond is stored from both
# ends), a uint32 neighbour and 4 doubles (r0x, r0y, strain_coef, spring_coef);
# the run loop's last-good snapshot: the 6 state arrays (x, y, vx, vy, theta,
# omega) as doubles.
LAYOUT = {
    "particle store (19 x 8 + 3 x 4 + 1 bytes)": ("particle", 19 * 8 + 3 * 4 + 1),
    "bond rows (uint32 offset)": ("particle", 4),
    "last-good snapshot (6 x 8 bytes)": ("particle", 6 * 8),
    "bond entries (uint32 + 4 x 8 bytes, 2 per bond)": ("entry", 4 + 4 * 8),
}


def fail(message):
    sys.exit(f"memory_rod.py: {message}")


def mem_total():
    for line in open("/proc/meminfo"):
        if line.startswith("MemTotal:"):
            return int(line.split()[1]) * 1024
    return None


def measure(exe, l0, steps, threads, folder):
    end = steps * DT
    shutil.rmtree(folder, ignore_errors=True)  # the folder is this script's: a fresh run
    cmd = [str(exe), "run", str(CASE), "--out", str(folder), "--threads", str(threads),
           "--set", f"l0={l0!r}", "--set", f"time.end={end!r}",
           "--set", f"output.frame_interval={end!r}", "--set", "output.checkpoint_interval=0"]
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    output = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    seconds = time.monotonic() - start
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        fail(f"mpsolid exited with {code} at l0 = {l0} m:\n{output[-3000:]}\n"
             "(at this size a failure in set-up is most likely memory: see dmesg for the OOM "
             "killer, or the message above)")
    rep = run_data.read_info(folder)
    particles, bonds = rep["particles"], rep["bonds"]
    entries = 2 * bonds
    layout = {name: (particles if per == "particle" else entries) * size
              for name, (per, size) in LAYOUT.items()}
    return {"l0": l0, "particles": particles, "bonds": bonds,
            "bonds_per_particle": entries / particles,
            "peak_rss_bytes": usage.ru_maxrss * 1024,  # Linux: KiB
            "rss_bytes_per_particle": usage.ru_maxrss * 1024 / particles,
            "layout_bytes": layout, "layout_total_bytes": sum(layout.values()),
            "layout_bytes_per_particle": sum(layout.values()) / particles,
            "setup_seconds": rep["phase_seconds"]["setup"], "process_seconds": seconds,
            "bytes_written": rep["bytes_written"] + rep["checkpoint_bytes"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--l0", type=float, nargs="+", default=[1.264e-4, 6.32e-5])
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", type=pathlib.Path, default=REPO / "out" / "bench")
    ap.add_argument("--mpsolid", type=pathlib.Path, default=REPO / "build/release/mpsolid")
    ap.add_argument("--keep", action="store_true", help="keep the runs' outputs")
    args = ap.parse_args()
    if not os.access(args.mpsolid, os.X_OK):
        fail(f"no mpsolid executable at {args.mpsolid}: build it with "
             "`cmake --preset release && cmake --build --preset release`")
    if args.steps < 1:
        fail("--steps must be >= 1")
    runs = args.out / "memory_runs"
    rows = []
    for l0 in sorted(args.l0, reverse=True):
        folder = runs / f"l0_{l0:g}"
        shutil.rmtree(folder, ignore_errors=True)
        print(f"memory_rod: l0 = {l0:g} m ...", flush=True)
        rows.append(measure(args.mpsolid, l0, args.steps, args.threads, folder))
    if not args.keep:
        shutil.rmtree(runs, ignore_errors=True)
    marginal = None
    if len(rows) >= 2:
        a, b = rows[0], rows[-1]
        marginal = (b["peak_rss_bytes"] - a["peak_rss_bytes"]) / (b["particles"] - a["particles"])
    total = mem_total()

    gib = 1024 ** 3
    lines = ["| l0 (m) | particles | bonds | bond entries / particle | peak RSS | "
             "RSS / particle | data structures / particle | set-up (s) |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        lines.append(f"| {r['l0']:g} | {r['particles']:,} | {r['bonds']:,} "
                     f"| {r['bonds_per_particle']:.2f} | {r['peak_rss_bytes'] / gib:.3f} GiB "
                     f"| {r['rss_bytes_per_particle']:.0f} B | {r['layout_bytes_per_particle']:.0f} B "
                     f"| {r['setup_seconds']:.2f} |")
    big = rows[-1]
    lines += ["", f"Data structures at {big['particles']:,} particles (from the layout):", "",
              "| array | bytes | bytes / particle |", "| --- | --- | --- |"]
    for name, size in big["layout_bytes"].items():
        lines.append(f"| {name} | {size / 1e6:.1f} MB | {size / big['particles']:.0f} |")
    lines.append(f"| total | {big['layout_total_bytes'] / 1e6:.1f} MB "
                 f"| {big['layout_bytes_per_particle']:.0f} |")
    lines.append("")
    if marginal is not None:
        lines.append(f"Marginal peak RSS between {rows[0]['particles']:,} and "
                     f"{big['particles']:,} particles: {marginal:.0f} bytes per particle.")
    if total:
        lines.append(f"Machine memory {total / gib:.1f} GiB: the {big['particles']:,}-particle rod "
                     f"peaks at {big['peak_rss_bytes'] / gib:.2f} GiB "
                     f"({100 * big['peak_rss_bytes'] / total:.1f} % of it).")
    lines.append(f"\n{args.steps} steps at {args.threads} threads per run; command: "
                 f"bench/memory_rod.py {' '.join(sys.argv[1:])}\n")
    table = "\n".join(lines)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "memory_rod.md").write_text(table)
    (args.out / "memory_rod.json").write_text(json.dumps(
        {"rows": rows, "marginal_bytes_per_particle": marginal, "mem_total_bytes": total},
        indent=2) + "\n")
    print(table)


if __name__ == "__main__":
    main()
