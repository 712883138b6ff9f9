#!/usr/bin/python3
"""Compare the bond models on the paper's case: plate displacement of each
(one run folder per model) and their first peaks, side by side.

  examples/compare_models.py [--end 0.005] [--load 11200] [--out out/examples/compare_models]
"""
import argparse
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import mpsolid  # noqa: E402
from mpsolid.analysis import first_peak  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = ["paper", "paper_conservative", "finite_strain"]

p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
p.add_argument("--end", type=float, default=0.005, help="simulated time (s)")
p.add_argument("--load", type=float, default=None, help="step force (N per metre; default the case's)")
p.add_argument("--out", default=os.path.join("out", "examples", "compare_models"))
p.add_argument("--threads", type=int, default=None)
args = p.parse_args()

for model in MODELS:
    case = mpsolid.Case.load(os.path.join(ROOT, "cases", "shock_rod.toml"))
    case.set("model", model)
    case.set("time.end", args.end)
    if args.load is not None:
        case.set("loads.shock.force", [args.load, 0.0])
    folder = os.path.join(args.out, model)
    code = mpsolid.run(case, out=folder, threads=args.threads, force=True)
    run = mpsolid.open_run(folder)
    h = run.history
    plt.plot(h["t"] * 1e3, h["plate.x"] * 1e3, label=model)
    try:
        peak, when = first_peak(list(h["t"]), list(h["plate.x"]))
        text = f"first peak {peak * 1e3:.4f} mm at {when * 1e3:.4f} ms"
    except ValueError:
        text = "no peak before the end"
    print(f"{model:20s} {run.outcome:10s} {text}, {run.info['wall_seconds']:.1f} s wall"
          + ("" if code == 0 else f" (exit {code})"))
plt.xlabel("t (ms)")
plt.ylabel("plate displacement (mm)")
plt.legend()
png = os.path.join(args.out, "models.png")
plt.savefig(png, dpi=100)
print(f"wrote {png}")
