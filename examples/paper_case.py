#!/usr/bin/python3
"""Run the paper's case (cases/shock_rod.toml) and plot the plate's
displacement against time, with the first peak marked.

  examples/paper_case.py [--end 0.01] [--out out/examples/paper_case] [--threads N]
"""
import argparse
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import mpsolid  # noqa: E402
from mpsolid.analysis import first_peak  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
p.add_argument("--end", type=float, default=None, help="simulated time (s; default the case's 10 ms)")
p.add_argument("--out", default=os.path.join("out", "examples", "paper_case"))
p.add_argument("--threads", type=int, default=None)
args = p.parse_args()

case = mpsolid.Case.load(os.path.join(ROOT, "cases", "shock_rod.toml"))
if args.end:
    case.set("time.end", args.end)
code = mpsolid.run(case, out=args.out, threads=args.threads, force=True)
if code != 0:
    raise SystemExit(f"the run ended with exit code {code} (see {args.out}/run.json)")

run = mpsolid.open_run(args.out)
h = run.history
t_ms, x_mm = h["t"] * 1e3, h["plate.x"] * 1e3
plt.plot(t_ms, x_mm, label=f"{run.info['model']}, l0 = {run.case['l0'] * 1e3:g} mm")
try:
    peak, when = first_peak(list(h["t"]), list(h["plate.x"]))
    plt.plot([when * 1e3], [peak * 1e3], "o", label=f"first peak {peak * 1e3:.3f} mm at {when * 1e3:.3f} ms")
    print(f"first peak of the plate: {peak * 1e3:.4f} mm at {when * 1e3:.4f} ms")
except ValueError:
    print("no first peak yet: run longer (--end)")
plt.xlabel("t (ms)")
plt.ylabel("plate displacement (mm)")
plt.legend()
png = os.path.join(args.out, "plate.png")
plt.savefig(png, dpi=100)
print(f"wrote {png}")
