#!/usr/bin/python3
"""Pictures of an mpsolid run: writes DIR/frames.png and DIR/history.png.

    /usr/bin/python3 tools/plot.py DIR [--color body|pressure|strain] [--frames K]

frames.png: the particles of every frame as dots, side by side in time order
(the rod stands on its wall, the plate on top, x pointing down: the push of
the plate goes down the page), in mm at equal aspect, coloured by body; with
--color pressure or strain, elastic bodies are coloured by pressure or
volumetric strain (one colour scale over all frames).
history.png: rigid-body displacement, elastic-body extents and the energies
(kinetic KE, strain PE, external work W and the balance KE + PE - W) against
time.

Needs Debian's python3-h5py and python3-matplotlib (run it with /usr/bin/python3).
Exits 2 with a message if DIR holds no results.
"""
import argparse
import csv
import os
import sys

KIND_WALL, KIND_ELASTIC, KIND_RIGID = 0, 1, 2
KIND_NAMES = {KIND_WALL: "wall", KIND_ELASTIC: "elastic", KIND_RIGID: "rigid"}
# Body colours by kind: elastic bodies in blues/greens, rigid in reds, walls grey.
PALETTE = {
    KIND_ELASTIC: ["#2a6fb0", "#3a9a5b", "#7b4fa6", "#1b9e9e"],
    KIND_RIGID: ["#c8382f", "#e08a1e", "#a63d73"],
    KIND_WALL: ["#555555", "#8c8c8c"],
}


def fail(message, code=2):
    print(f"plot.py: {message}", file=sys.stderr)
    sys.exit(code)


def parse_args():
    parser = argparse.ArgumentParser(
        description="Pictures of an mpsolid run: DIR/frames.png and DIR/history.png.")
    parser.add_argument("dir", help="the run's output folder (mpsolid run ... --out DIR)")
    parser.add_argument("--color", choices=["body", "pressure", "strain"], default="body",
                        help="colour elastic bodies by body (default), pressure or "
                             "volumetric strain")
    parser.add_argument("--frames", type=int, default=11,
                        help="at most this many frames, evenly picked (default 11)")
    parser.add_argument("--dpi", type=int, default=150)
    return parser.parse_args()


def check_folder(folder):
    if not os.path.isdir(folder):
        fail(f"{folder}: no such folder")
    missing = [f for f in ("frames.h5", "history.csv")
               if not os.path.isfile(os.path.join(folder, f))]
    if missing:
        fail(f"{folder} has no results ({' and '.join(missing)} missing): run "
             f"`mpsolid run CASE --out {folder}` first")


def read_history(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        fail(f"{path} has no rows")
    header = rows[0]
    try:
        columns = {name: [float(r[k]) for r in rows[1:]] for k, name in enumerate(header)}
    except (ValueError, IndexError) as e:
        fail(f"{path} is not a history.csv of mpsolid ({e})", 1)
    for needed in ("t", "kinetic_energy", "strain_energy", "external_work"):
        if needed not in columns:
            fail(f"{path} has no column {needed}", 1)
    return columns


def read_frames(path, limit):
    import h5py
    import numpy as np
    try:
        with h5py.File(path, "r") as f:
            names = sorted(f["frames"])
            if not names:
                fail(f"{path} holds no frames")
            if len(names) > limit:
                picks = np.unique(np.round(np.linspace(0, len(names) - 1, limit)).astype(int))
                names = [names[k] for k in picks]
            body_names = [b.decode() if isinstance(b, bytes) else str(b)
                          for b in f["body_names"][()]]
            l0 = float(f.attrs["l0"])
            frames = []
            for name in names:
                g = f["frames"][name]
                frames.append({
                    "time": float(g.attrs["time"]),
                    "position": g["position"][()],
                    "body": g["body"][()],
                    "kind": g["kind"][()],
                    "pressure": g["pressure"][()],
                    "strain": g["volumetric_strain"][()],
                })
    except (OSError, KeyError) as e:
        fail(f"{path} cannot be read as mpsolid frames ({e})", 1)
    return frames, body_names, l0


def body_colours(frames, body_names, field_shown):
    """A colour and kind per body, by the kind of its particles. Rigid bodies
    keep clear of the red and blue ends of the pressure/strain scale."""
    palette_of = dict(PALETTE)
    if field_shown:
        palette_of[KIND_RIGID] = ["#3a9a5b", "#7b4fa6", "#e0b01e"]
    first = frames[0]
    used = {KIND_WALL: 0, KIND_ELASTIC: 0, KIND_RIGID: 0}
    colours, kinds = {}, {}
    for b in range(len(body_names)):
        members = first["kind"][first["body"] == b]
        if members.size == 0:
            continue
        kind = int(members[0])
        palette = palette_of[kind]
        colours[b] = palette[used[kind] % len(palette)]
        kinds[b] = kind
        used[kind] += 1
    return colours, kinds


def time_label(t):
    ms = t * 1e3
    return f"t = {ms:.0f} ms" if abs(ms - round(ms)) < 1e-9 else f"t = {ms:.3g} ms"


def plot_frames(folder, frames, body_names, l0, color_by, dpi):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    what = {"body": "body", "pressure": "pressure", "strain": "volumetric strain"}[color_by]
    colours, kinds = body_colours(frames, body_names, color_by != "body")
    # Picture coordinates in mm: across = y, down the page = x.
    every = np.concatenate([fr["position"] for fr in frames]) * 1e3
    pad = 1.5 * l0 * 1e3
    across = (every[:, 1].min() - pad, every[:, 1].max() + pad)
    down = (every[:, 0].min() - pad, every[:, 0].max() + pad)
    width, height = across[1] - across[0], down[1] - down[0]

    n = len(frames)
    panel_h = 3.6  # inches
    panel_w = panel_h * width / height
    extra = 1.3 if color_by != "body" else 0.0
    fig, axes = plt.subplots(1, n, figsize=(panel_w * n + 1.0 + extra, panel_h + 1.2),
                             sharex=True, sharey=True, squeeze=False)
    axes = axes[0]

    field = {"pressure": "pressure", "strain": "strain"}.get(color_by)
    scale, norm, cmap = 1.0, None, None
    if field:
        from matplotlib.colors import TwoSlopeNorm
        scale = 1e-6 if field == "pressure" else 1.0
        values = np.concatenate([fr[field][fr["kind"] == KIND_ELASTIC] for fr in frames]) * scale
        limit = float(np.percentile(np.abs(values), 99.5)) if values.size else 1.0
        limit = limit if limit > 0 else 1.0
        norm = TwoSlopeNorm(vmin=-limit, vcenter=0.0, vmax=limit)
        cmap = "coolwarm"

    # Dots about one lattice spacing across.
    fig.canvas.draw()
    axes[0].set_xlim(*across)
    axes[0].set_ylim(down[1], down[0])
    axes[0].set_aspect("equal")
    axes[0].apply_aspect()
    pixels = abs(axes[0].transData.transform((l0 * 1e3, 0))[0] -
                 axes[0].transData.transform((0, 0))[0])
    size = (0.9 * pixels * 72.0 / fig.dpi) ** 2

    mappable = None
    for ax, fr in zip(axes, frames):
        pos = fr["position"] * 1e3
        for b, colour in colours.items():
            sel = fr["body"] == b
            if field and kinds[b] == KIND_ELASTIC:
                mappable = ax.scatter(pos[sel, 1], pos[sel, 0], s=size, c=fr[field][sel] * scale,
                                      cmap=cmap, norm=norm, linewidths=0)
            else:
                ax.scatter(pos[sel, 1], pos[sel, 0], s=size, color=colour, linewidths=0,
                           label=body_names[b])
        ax.set_title(time_label(fr["time"]), fontsize=11)
        ax.set_xlabel("y (mm)")
        ax.set_aspect("equal")
        ax.grid(True, linewidth=0.3, alpha=0.5)
        ax.tick_params(labelsize=8)
    axes[0].set_ylabel("x (mm)")
    axes[0].set_xlim(*across)
    axes[0].set_ylim(down[1], down[0])

    from matplotlib.lines import Line2D
    handles, labels = [], []
    for b, colour in colours.items():
        scaled = field and kinds[b] == KIND_ELASTIC
        handles.append(Line2D([], [], marker="o", linestyle="", markersize=8,
                              color="#aaaaaa" if scaled else colour))
        labels.append(f"{body_names[b]} ({KIND_NAMES[kinds[b]]}"
                      + (f", coloured by {what})" if scaled else ")"))
    fig.legend(handles, labels, loc="lower center", bbox_to_anchor=(0.5, 0.0), ncol=len(labels),
               frameon=False, fontsize=10)
    fig.suptitle(f"{os.path.basename(os.path.abspath(folder))}: particles at each frame "
                 f"(colour: {what})", fontsize=12)
    fig.subplots_adjust(left=0.8 / (panel_w * n + 1.0 + extra),
                        right=1 - (0.25 + extra) / (panel_w * n + 1.0 + extra),
                        bottom=0.2, top=0.86, wspace=0.06)
    if mappable is not None:
        cax = fig.add_axes([1 - (extra - 0.25) / (panel_w * n + 1.0 + extra), 0.2,
                            0.18 / (panel_w * n + 1.0 + extra), 0.66])
        bar = fig.colorbar(mappable, cax=cax)
        bar.set_label("pressure (MPa)" if field == "pressure" else "volumetric strain")
    out = os.path.join(folder, "frames.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def plot_history(folder, h, dpi):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    t = np.array(h["t"]) * 1e3
    rigid = [c[:-2] for c in h if c.endswith(".x") and c[:-2] + ".theta" in h]
    elastic = [c[:-5] for c in h if c.endswith(".xmin")]
    fig, axes = plt.subplots(2, 2, figsize=(12, 8), sharex=True)
    (ax_rigid, ax_x), (ax_y, ax_energy) = axes

    for b in rigid:
        ax_rigid.plot(t, np.array(h[b + ".x"]) * 1e3, marker="o", markersize=3,
                      label=f"{b}: x displacement")
        if np.any(np.abs(h[b + ".y"]) > 1e-9):
            ax_rigid.plot(t, np.array(h[b + ".y"]) * 1e3, marker="o", markersize=3,
                          label=f"{b}: y displacement")
    ax_rigid.set_ylabel("displacement (mm)")
    ax_rigid.set_title("rigid bodies")

    for b in elastic:
        ax_x.plot(t, np.array(h[b + ".xmin"]) * 1e3, marker="o", markersize=3, label=f"{b}: x min")
        ax_x.plot(t, np.array(h[b + ".xmax"]) * 1e3, marker="s", markersize=3, label=f"{b}: x max")
        ax_y.plot(t, np.array(h[b + ".ymin"]) * 1e3, marker="o", markersize=3, label=f"{b}: y min")
        ax_y.plot(t, np.array(h[b + ".ymax"]) * 1e3, marker="s", markersize=3, label=f"{b}: y max")
    ax_x.set_ylabel("x (mm)")
    ax_x.set_title("elastic bodies: x extent (particle centres)")
    ax_y.set_ylabel("y (mm)")
    ax_y.set_title("elastic bodies: y extent (particle centres)")

    ke, pe, w = (np.array(h[c]) for c in ("kinetic_energy", "strain_energy", "external_work"))
    ax_energy.plot(t, ke, label="kinetic KE")
    ax_energy.plot(t, pe, label="strain PE")
    ax_energy.plot(t, w, label="external work W")
    ax_energy.plot(t, ke + pe - w, color="black", linestyle="--", label="KE + PE - W")
    ax_energy.set_ylabel("energy (J per m of depth)")
    ax_energy.set_title("energies")

    for ax in axes.flat:
        ax.grid(True, linewidth=0.4, alpha=0.6)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=9)
    for ax in axes[1]:
        ax.set_xlabel("time (ms)")
    fig.suptitle(f"{os.path.basename(os.path.abspath(folder))}: history", fontsize=13)
    fig.tight_layout()
    out = os.path.join(folder, "history.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def main():
    args = parse_args()
    check_folder(args.dir)
    if args.frames < 1:
        fail("--frames must be at least 1")
    history = read_history(os.path.join(args.dir, "history.csv"))
    frames, body_names, l0 = read_frames(os.path.join(args.dir, "frames.h5"), args.frames)
    for out in (plot_frames(args.dir, frames, body_names, l0, args.color, args.dpi),
                plot_history(args.dir, history, args.dpi)):
        print(f"plot.py: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
