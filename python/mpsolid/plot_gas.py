"""Pictures of a run's gas (a case with [gas]): numerical schlieren and the
probes' pressures.

schlieren.png: at chosen times, the gas's density gradient magnitude in grey
(dark where the density changes fast, as a shadowgraph shows shocks), with
the bodies' particles drawn over it in dark red, one panel per time, in mm
at equal aspect. The grey is Quirk's exponential scale, exp(-k |grad rho| /
max |grad rho|) with k = 15, the maximum taken over every panel so the
panels compare.

gas_probes.png: each probe's pressure against time in ms, with measured
points (a CSV of t in ms and p in kPa, a header row allowed) drawn over it.

displacement.png: a history.csv column's change since t = 0 (a body's
extent: `panel.xmax`, the tip of a panel bending to +x) in mm against time
in ms, with measured points (t in ms, mm) drawn over it.

The figures are made without pyplot (an interactive session's backend is
left alone); not imported by `import mpsolid`.
"""
import os

import numpy as np
from matplotlib.figure import Figure

from .plot import read_reference, save_png
from .run_data import open_run

SCHLIEREN_K = 15.0


def density_gradient(frame, cell):
    """|grad rho| on the gas's grid (central differences, one-sided at the
    edges and next to bodies; 0 inside a body)."""
    rho = frame.gas("density")
    solid = frame.gas("solid").astype(bool)
    gy, gx = np.gradient(np.where(solid, np.nan, rho), cell)
    g = np.hypot(gx, gy)
    return np.where(np.isfinite(g), g, 0.0)


def schlieren(folder, times_ms=None, out=None, columns=2, dpi=150):
    """schlieren.png of the run in `folder` at `times_ms` (default: six
    frames evenly spread); returns the path written."""
    run = open_run(folder)
    frames = run.frames
    if frames.gas_grid is None:
        raise ValueError(f"{folder}: the run has no gas")
    grid = frames.gas_grid
    if times_ms is None:
        picks = np.unique(np.linspace(0, len(frames) - 1, min(6, len(frames))).round().astype(int))
        chosen = [frames[int(k)] for k in picks]
    else:
        chosen = [frames.at_time(t * 1e-3) for t in times_ms]
    gradients = [density_gradient(f, grid["cell"]) for f in chosen]
    top = max(float(g.max()) for g in gradients) or 1.0
    x0, y0, h = grid["x0"], grid["y0"], grid["cell"]
    extent = [1e3 * x0, 1e3 * (x0 + grid["nx"] * h), 1e3 * y0, 1e3 * (y0 + grid["ny"] * h)]
    rows = (len(chosen) + columns - 1) // columns
    width = 7.0 * columns
    aspect = (extent[3] - extent[2]) / (extent[1] - extent[0])
    fig = Figure(figsize=(width, rows * (7.0 * aspect + 0.6) + 0.4))
    axes = np.array(fig.subplots(rows, columns, squeeze=False))
    for k, ax in enumerate(axes.flat):
        if k >= len(chosen):
            ax.axis("off")
            continue
        frame = chosen[k]
        shade = np.exp(-SCHLIEREN_K * gradients[k] / top)
        ax.imshow(shade, origin="lower", extent=extent, cmap="gray", vmin=0, vmax=1,
                  interpolation="nearest")
        xy = frame.position
        moving = frame.kind != 0
        ax.scatter(1e3 * xy[moving, 0], 1e3 * xy[moving, 1], s=0.5, c="#8b1a1a", linewidths=0)
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        ax.set_aspect("equal")
        ax.set_title(f"t = {1e3 * frame.time:.3f} ms", fontsize=10)
        ax.tick_params(labelsize=8)
        if k % columns == 0:
            ax.set_ylabel("y (mm)", fontsize=9)
        if k >= (rows - 1) * columns:
            ax.set_xlabel("x (mm)", fontsize=9)
    case = run.case
    fig.suptitle(f"{case.get('name', os.path.basename(folder))}: numerical schlieren "
                 f"(|grad rho|, gas cell {1e3 * h:g} mm, l0 {1e3 * case.get('l0', 0):g} mm)",
                 fontsize=11)
    fig.tight_layout()
    path = out or os.path.join(folder, "schlieren.png")
    save_png(fig, path, dpi)
    return path


def probe_history(folder, out=None, measured=None, measured_label="experiment", dpi=150,
                  measured_from=0.0):
    """gas_probes.png: each probe's pressure over time; `measured`: a CSV of
    points drawn over it, its t = 0 at the run's time `measured_from` (ms: an
    experiment's clock starts when the shock passes a gauge). Returns the
    path written."""
    run = open_run(folder)
    h = run.history_array
    names = [n[len("gas."):-len(".p")] for n in h.dtype.names
             if n.startswith("gas.") and n.endswith(".p")]
    if not names:
        raise ValueError(f"{folder}: the run has no gas probes")
    fig = Figure(figsize=(7.5, 4.2))
    ax = fig.subplots()
    for name in names:
        ax.plot(1e3 * h["t"], 1e-3 * h[f"gas.{name}.p"], lw=1.4, label=f"mpsolid: {name}")
    if measured:
        t, p = read_reference(measured, "--measured", "t, p (ms, kPa)")
        ax.plot(t + measured_from, p, "o", ms=3, mfc="none", color="#c0392b",
                label=measured_label)
    ax.set_xlabel("t (ms)")
    ax.set_ylabel("pressure (kPa)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9, frameon=False)
    ax.set_title(f"{run.case.get('name', '')}: gas pressure at the probes", fontsize=11)
    fig.tight_layout()
    path = out or os.path.join(folder, "gas_probes.png")
    save_png(fig, path, dpi)
    return path


def displacement_history(folder, column, out=None, measured=None, measured_label="experiment",
                         dpi=150, measured_from=0.0, against=(), label=None):
    """displacement.png: history.csv's `column` less its first value, in mm,
    against time in ms; `measured`: a CSV of points (t in ms, mm) drawn over
    it, its t = 0 at the run's time `measured_from` (ms); `against`: other
    runs' (folder, label) whose same column is drawn beside it; `label`: the
    run's own (by default its case's name, or the column alone). Returns the
    path written."""
    runs = [(folder, label)] + list(against)
    fig = Figure(figsize=(7.5, 4.2))
    ax = fig.subplots()
    run = None
    for k, (path, label) in enumerate(runs):
        r = open_run(path)
        run = run or r
        h = r.history_array
        if column not in h.dtype.names:
            raise KeyError(f"{path}: history.csv has no column '{column}'")
        if label is None:
            label = f"mpsolid: {column}" if len(runs) == 1 else r.case.get("name", path)
        ax.plot(1e3 * h["t"], 1e3 * (h[column] - h[column][0]), lw=1.4,
                ls="-" if k == 0 else (0, (5, 2 + k)), label=label)
    if measured:
        t, v = read_reference(measured, "--measured-displacement", "t, displacement (ms, mm)")
        ax.plot(t + measured_from, v, "o", ms=3, mfc="none", color="#c0392b",
                label=measured_label)
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel("t (ms)")
    ax.set_ylabel("displacement (mm)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9, frameon=False)
    case = run.case
    cell = case.get("gas", {}).get("cell")  # a run without a gas has no cell to name
    ax.set_title(f"{case.get('name', '')}: {column} (l0 {1e3 * case.get('l0', 0):g} mm"
                 + (f", gas cell {1e3 * cell:g} mm)" if cell else ")"), fontsize=11)
    fig.tight_layout()
    path = out or os.path.join(folder, "displacement.png")
    save_png(fig, path, dpi)
    return path
