#!/usr/bin/python3
"""The rod's deformed outline from a frame (no contact: the outline is the
boundary particles' current positions, joined in their reference order), its
area against the reference, and its lateral bulge.

  examples/deformed_outline.py RUN_FOLDER [--time 0.004] [--body rod]
"""
import argparse
import math
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import mpsolid  # noqa: E402


def boundary_loop(x0, y0, l0):
    """Indices of the particles on the boundary of a lattice body (fewer than
    4 lattice neighbours at l0), ordered around it by angle about the
    centroid of the reference configuration (a convex body such as the rod)."""
    key = {(round(a / l0 * 2), round(b / l0 * 2)): k for k, (a, b) in enumerate(zip(x0, y0))}
    edge = [k for k, (a, b) in enumerate(zip(x0, y0))
            if any((round(a / l0 * 2) + 2 * dx, round(b / l0 * 2) + 2 * dy) not in key
                   for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)))]
    cx, cy = x0.mean(), y0.mean()
    return sorted(edge, key=lambda k: math.atan2(y0[k] - cy, x0[k] - cx))


def polygon_area(x, y):
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
p.add_argument("run", help="a run folder (mpsolid run's --out)")
p.add_argument("--time", type=float, default=None, help="the frame nearest this time (default the last)")
p.add_argument("--body", default="rod")
args = p.parse_args()

run = mpsolid.open_run(args.run)
frames = run.frames
first = frames[0]
frame = frames[-1] if args.time is None else frames.at_time(args.time)
body = frames.body_names.index(args.body)
mine = first.body == body
ref = first.position[mine]
now = frame.position[frame.body == body]  # frames are in id order: the same particles, same order
loop = boundary_loop(ref[:, 0], ref[:, 1], run.case["l0"])
outline = now[loop]
area0 = polygon_area(ref[loop, 0], ref[loop, 1])
area = polygon_area(outline[:, 0], outline[:, 1])
height0 = np.ptp(ref[:, 1])
print(f"{args.body} at t = {frame.time * 1e3:.3f} ms: {len(loop)} boundary particles; outline area "
      f"{area * 1e6:.2f} mm^2 ({(area / area0 - 1) * 100:+.3f} % of the reference); height "
      f"{np.ptp(outline[:, 1]) * 1e3:.3f} mm (reference {height0 * 1e3:.3f} mm); "
      f"x from {outline[:, 0].min() * 1e3:.3f} to {outline[:, 0].max() * 1e3:.3f} mm")
closed = np.vstack([outline, outline[:1]])
ref_closed = np.vstack([ref[loop], ref[loop][:1]])
plt.plot(ref_closed[:, 0] * 1e3, ref_closed[:, 1] * 1e3, "k--", lw=0.8, label="reference")
plt.plot(closed[:, 0] * 1e3, closed[:, 1] * 1e3, "-", label=f"t = {frame.time * 1e3:.2f} ms")
plt.axis("equal")
plt.xlabel("x (mm)")
plt.ylabel("y (mm)")
plt.legend()
png = os.path.join(args.run, "outline.png")
plt.savefig(png, dpi=100)
print(f"wrote {png}")
