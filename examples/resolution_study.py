#!/usr/bin/python3
"""A resolution study of the paper's case with the finite-strain model: the
first peak of the plate at l0 = 2, 1 and 0.5 mm (automatic step), its
observed order of convergence and Richardson-extrapolated value with an
error bar. The same as

  mpsolid study cases/shock_rod.toml --vary l0=0.002,0.001,0.0005 --set model=finite_strain \\
      --set 'time.dt="auto"' --set time.end=0.005 --measure first_peak:plate.x

  examples/resolution_study.py [--l0 0.002 0.001 0.0005] [--end 0.005] [--jobs 1]
"""
import argparse
import os

import mpsolid

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
p.add_argument("--l0", type=float, nargs="+", default=[0.002, 0.001, 0.0005])
p.add_argument("--end", type=float, default=0.005, help="simulated time (s): past the first peak (3.3 ms)")
p.add_argument("--jobs", type=int, default=1)
p.add_argument("--out", default=os.path.join("out", "examples", "resolution_study"))
args = p.parse_args()

result = mpsolid.study(os.path.join(ROOT, "cases", "shock_rod.toml"), vary={"l0": args.l0},
                       sets=["model=finite_strain", 'time.dt="auto"', f"time.end={args.end}"],
                       measures=["first_peak:plate.x"], out=args.out, jobs=args.jobs)
for row in result.rows:
    print(f"l0 = {float(row['l0']) * 1e3:g} mm: peak {row['first_peak(plate.x)'] * 1e3:.4f} mm "
          f"at {row['first_peak(plate.x).t'] * 1e3:.4f} ms, {row['wall_seconds']:.1f} s wall")
for e in result.richardson:
    print(f"{e['measure']}: observed order {e['observed_order']:.2f}, "
          f"extrapolated {e['extrapolated']:.6g} ± {e['error_bar']:.2g}")
print(f"wrote {result.folder}/study.csv and study.png")
