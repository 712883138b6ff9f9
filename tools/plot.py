#!/usr/bin/python3
"""Pictures of an mpsolid run: writes DIR/frames.png and DIR/history.png.

    tools/plot.py DIR [--color pressure|body|strain] [--frames K] [--dpi D]
                      [--reference FILE.csv] [--describe]

frames.png: the particles of up to K frames (default 12, evenly picked, the
first and last always among them) in a grid of at most 6 columns, time order
row by row; each panel in mm at equal aspect (the rod stands on its wall, the
plate on top, x pointing down the page), its time above it. Elastic bodies are
coloured by pressure (default; MPa or kPa, > 0 in compression) or volumetric
strain, one colour scale over every panel with one colourbar; if a few
outlying particles would wash the scale out it is clipped to the 99th
percentile of |value| and the colourbar says so (and the data range). Rigid
bodies and walls are then neutral greys. --color body colours every body by
body, with a legend. About 2200 px wide at the default --dpi 150.
history.png: rigid-body displacement (with --reference, a curve from a CSV of
t, x in seconds and metres, a header row allowed, drawn over it), elastic-body
extents and probes, the energies (kinetic KE, strain PE, external work W), the
energy-balance error (KE + PE - W - E0) / max W in percent (E0 = KE + PE at
the first row) on its own panel, and the fastest particle's speed, against
time in ms.
Both titles give the case, model, l0, dt and the loads (from
case.resolved.toml and run.json); the run folder is a footnote. If the run
blew up (run.json outcome "unstable"), every time panel has a line at the
blow-up time, its criterion is written under the title, and in frames.png the
last frame is marked "last good state" with the diagnosed particle ringed.
--describe prints what was drawn as JSON on stdout (the PNGs are still
written).

Needs numpy, h5py and matplotlib: Debian's python3-h5py and python3-matplotlib
(the script runs with /usr/bin/python3). Exit codes: 0 done; 2 a missing
library, folder or reference file, or a folder without results; 1 results
that cannot be read.
"""
import argparse
import csv
import json
import math
import os
import sys
import textwrap

KIND_WALL, KIND_ELASTIC, KIND_RIGID = 0, 1, 2
KIND_NAMES = {KIND_WALL: "wall", KIND_ELASTIC: "elastic", KIND_RIGID: "rigid"}
# Body colours by kind (--color body): elastic bodies in blues/greens, rigid in
# reds, walls grey.
PALETTE = {
    KIND_ELASTIC: ["#2a6fb0", "#3a9a5b", "#7b4fa6", "#1b9e9e"],
    KIND_RIGID: ["#c8382f", "#e08a1e", "#a63d73"],
    KIND_WALL: ["#555555", "#8c8c8c"],
}
# Colouring by a field: rigid bodies and walls in neutral greys, darker than
# the colour map's pale middle.
GREYS = {KIND_RIGID: ["#6f6f6f", "#8f8f8f", "#555555"], KIND_WALL: ["#2f2f2f", "#474747"]}
BLOWUP_COLOUR = "#d4001a"
MAX_COLUMNS = 6
FIGURE_WIDTH_IN = 14.6   # frames.png: 2190 px at 150 dpi
COLOUR_CLIP_PERCENTILE = 99.0
COLOUR_CLIP_WHEN = 1.25  # clip when the largest |value| exceeds the percentile by this factor

np = h5py = plt = None   # loaded by load_libraries()


def frame_axes(ax, across, down, labelsize, ticklength):
    """A frame panel's axes: across (mm) to the right, down (mm) down the
    page, equal aspect, a light grid behind the particles."""
    ax.set_xlim(*across)
    ax.set_ylim(down[1], down[0])
    ax.set_aspect("equal")
    ax.grid(True, linewidth=0.3, alpha=0.5)
    ax.set_axisbelow(True)
    ax.tick_params(labelsize=labelsize, length=ticklength)


def fail(message, code=2):
    print(f"plot.py: {message}", file=sys.stderr)
    sys.exit(code)


def load_libraries():
    """numpy, h5py and matplotlib, imported here so that a Python without them
    gets one clear line rather than a traceback."""
    global np, h5py, plt
    missing = []
    for name in ("numpy", "h5py", "matplotlib"):
        try:
            __import__(name)
        except ImportError:
            missing.append(name)
    if missing:
        packages = " and ".join({"numpy": "python3-numpy", "h5py": "python3-h5py",
                                 "matplotlib": "python3-matplotlib"}[m] for m in missing)
        fail(f"this Python ({sys.executable}) has no {', '.join(missing)}: install {packages} "
             f"(apt-get install {packages.replace(' and ', ' ')}) or run it with Debian's "
             f"/usr/bin/python3 tools/plot.py ...")
    import numpy
    import h5py as h5
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot
    np, h5py, plt = numpy, h5, pyplot


def parse_args():
    parser = argparse.ArgumentParser(
        description="Pictures of an mpsolid run: DIR/frames.png and DIR/history.png.")
    parser.add_argument("dir", help="the run's output folder (mpsolid run ... --out DIR)")
    parser.add_argument("--color", choices=["pressure", "body", "strain"], default="pressure",
                        help="colour elastic bodies by pressure (default), volumetric strain, "
                             "or every body by body")
    parser.add_argument("--frames", type=int, default=12,
                        help="at most this many frames, evenly picked (default 12; "
                             f"{MAX_COLUMNS} to a row)")
    parser.add_argument("--dpi", type=int, default=150,
                        help="resolution (default 150: frames.png about 2200 px wide)")
    parser.add_argument("--reference", metavar="FILE.csv",
                        help="a reference curve drawn over the rigid-body displacement: "
                             "columns t, x in s and m (a header row allowed)")
    parser.add_argument("--describe", action="store_true",
                        help="print what was drawn as JSON on stdout (the PNGs are still written)")
    return parser.parse_args()


def check_folder(folder):
    if not os.path.isdir(folder):
        fail(f"{folder}: no such folder")
    missing = [f for f in ("frames.h5", "history.csv")
               if not os.path.isfile(os.path.join(folder, f))]
    if missing:
        fail(f"{folder} has no results ({' and '.join(missing)} missing): run "
             f"`mpsolid run CASE --out {folder}` first")


# ---------------------------------------------------------------- reading


def read_history(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        fail(f"{path} has no rows", 1)
    header = rows[0]
    try:
        columns = {name: [float(r[k]) for r in rows[1:]] for k, name in enumerate(header)}
    except (ValueError, IndexError) as e:
        fail(f"{path} is not a history.csv of mpsolid ({e})", 1)
    for needed in ("t", "kinetic_energy", "strain_energy", "external_work"):
        if needed not in columns:
            fail(f"{path} has no column {needed}", 1)
    return {name: np.array(values) for name, values in columns.items()}


def pick(count, limit):
    """Up to `limit` indices of 0..count-1, evenly spread, first and last kept."""
    if count <= limit:
        return list(range(count))
    if limit == 1:
        return [count - 1]
    return sorted(set(int(k) for k in np.round(np.linspace(0, count - 1, limit))))


def read_frames(path, limit):
    try:
        with h5py.File(path, "r") as f:
            names = sorted(f["frames"])
            if not names:
                fail(f"{path} holds no frames", 1)
            total = len(names)
            names = [names[k] for k in pick(total, limit)]
            body_names = [b.decode() if isinstance(b, bytes) else str(b)
                          for b in f["body_names"][()]]
            l0 = float(f.attrs["l0"])
            frames = []
            for name in names:
                g = f["frames"][name]
                frames.append({
                    "time": float(g.attrs["time"]),
                    "step": int(g.attrs["step"]) if "step" in g.attrs else None,
                    "position": g["position"][()],
                    "body": g["body"][()],
                    "kind": g["kind"][()],
                    "pressure": g["pressure"][()],
                    "strain": g["volumetric_strain"][()],
                })
    except (OSError, KeyError) as e:
        fail(f"{path} cannot be read as mpsolid frames ({e})", 1)
    return frames, body_names, l0, total


def read_run(folder):
    """run.json and case.resolved.toml, each {} when absent or unreadable."""
    run, case = {}, {}
    try:
        with open(os.path.join(folder, "run.json")) as f:
            run = json.load(f)
    except (OSError, ValueError):
        pass
    try:
        import tomllib
        with open(os.path.join(folder, "case.resolved.toml"), "rb") as f:
            case = tomllib.load(f)
    except (ImportError, OSError, ValueError):
        pass
    return run, case


def read_reference(path):
    """(t, x) arrays from a CSV of t, x (s, m); a header row and # comments allowed."""
    if not os.path.isfile(path):
        fail(f"--reference {path}: no such file")
    t, x = [], []
    with open(path, newline="") as f:
        for number, row in enumerate(csv.reader(f), start=1):
            if not row or not "".join(row).strip() or row[0].lstrip().startswith("#"):
                continue
            try:
                t.append(float(row[0]))
                x.append(float(row[1]))
            except (ValueError, IndexError):
                if t:   # only the first row may be a header
                    fail(f"--reference {path}: line {number} is not two numbers t, x: {row}")
    if not t:
        fail(f"--reference {path}: no rows of t, x (seconds, metres)")
    return np.array(t), np.array(x)


# ---------------------------------------------------------------- words


def number(v, digits=3):
    if v == 0:
        return "0"   # and not "-0"
    text = f"{v:.{digits}g}"
    if "e" in text:
        mantissa, exponent = text.split("e")
        text = f"{mantissa}e{int(exponent)}"
    return text


def seconds(v):
    """1e-8 -> '10 ns', 3.3e-6 -> '3.3 µs'."""
    if v == 0:
        return "0 s"
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)):
        if abs(v) >= scale:
            return f"{number(v / scale)} {unit}"
    return f"{number(v / 1e-12)} ps"


def ms(t):
    return f"{number(t * 1e3, 4)} ms"


def force_words(name, load):
    force = load.get("force")
    if not isinstance(force, list) or len(force) != 2:
        return None
    fx, fy = (float(c) for c in force)
    if fy == 0.0:
        size = f"{number(abs(fx) / 1e3)} kN in {'+' if fx >= 0 else '-'}x"
    elif fx == 0.0:
        size = f"{number(abs(fy) / 1e3)} kN in {'+' if fy >= 0 else '-'}y"
    else:
        size = f"({number(fx / 1e3)}, {number(fy / 1e3)}) kN"
    words = f"load {name}: {size}"
    if load.get("body"):
        words += f" on {load['body']}"
    if load.get("start"):
        words += f" from {ms(float(load['start']))}"
    return words


def describe_run(folder, run, case):
    """The title line (case, model, l0, dt, loads), the blow-up (or None) and the footnote."""
    name = case.get("name") or run.get("case") or os.path.basename(os.path.abspath(folder))
    parts = [name]
    model = case.get("model") or run.get("model")
    if model:
        parts.append(f"model {model}")
    if "l0" in case:
        parts.append(f"l0 = {number(float(case['l0']) * 1e3)} mm")
    time_table = case.get("time", {})
    dt = run.get("dt")
    if time_table.get("dt") == "auto" or "stable_step" in run:
        parts.append(f"dt = auto: {seconds(dt)}" if dt else "dt = auto")
    elif dt or isinstance(time_table.get("dt"), (int, float)):
        parts.append(f"dt = {seconds(float(dt or time_table['dt']))}")
    loads = [w for w in (force_words(n, l) for n, l in case.get("loads", {}).items()) if w]
    title = ", ".join(parts) + ("; " + "; ".join(loads) if loads else "")

    blowup = None
    diagnosis = run.get("diagnosis") or {}
    if run.get("outcome") == "unstable":
        blowup = {"time": diagnosis.get("time", run.get("simulated_time")),
                  "criterion": diagnosis.get("criterion", "unstable (no diagnosis in run.json)"),
                  "last_good_time": diagnosis.get("last_good_time"),
                  "particle_id": diagnosis.get("particle_id"),
                  "body": diagnosis.get("body"),
                  "position": diagnosis.get("position")}

    notes = [f"run folder: {os.path.abspath(folder)}"]
    if run.get("overrides"):
        overrides = run["overrides"]
        if isinstance(overrides, list):
            overrides = ", ".join(str(o) for o in overrides)
        notes.append(f"overrides: {overrides}")
    if run.get("outcome") and run["outcome"] != "completed":
        notes.append(f"outcome: {run['outcome']}")
    if run.get("git_commit"):
        notes.append(f"mpsolid {run.get('version', '')} {run['git_commit']}".replace("  ", " "))
    return title, blowup, "; ".join(notes)


def blowup_words(blowup):
    words = f"blow-up at t = {ms(blowup['time'])}: {blowup['criterion']}"
    if blowup.get("particle_id") is not None:
        words += f" (particle {blowup['particle_id']}"
        words += f" of {blowup['body']})" if blowup.get("body") else ")"
    return words


def wrap_to(text, width_in, fontsize):
    """Lines of text that fit a width in inches at a font size (an average
    glyph taken as 0.55 em)."""
    return textwrap.wrap(text, max(20, int(width_in * 72.0 / (0.55 * fontsize))))


def header_lines(fig_w, title, subtitle, alarm):
    """The heading's lines as (text, font size, colour) and its height in inches."""
    lines = [(text, 13, "black") for text in wrap_to(title, fig_w - 0.4, 13)]
    lines.append((subtitle, 10.5, "#333333"))
    lines += [(text, 10, BLOWUP_COLOUR) for text in (wrap_to(alarm, fig_w - 0.4, 10)
                                                     if alarm else [])]
    return lines, 0.2 + sum(size * 1.45 / 72.0 for _, size, _ in lines) + 0.1


def draw_header(fig, fig_h, lines, notes):
    y = 0.2
    for text, size, colour in lines:
        fig.text(0.5, 1 - y / fig_h, text, ha="center", va="top", fontsize=size, color=colour)
        y += size * 1.45 / 72.0
    fig.text(0.006, 0.05 / fig_h, "\n".join(notes), ha="left", va="bottom", fontsize=7,
             color="#777777")


def save_png(fig, out, dpi):
    """Writes the figure as a PNG; where Pillow has libimagequant (Debian's
    does), as 256 well-chosen colours, a third of the size with no visible
    banding (the dots' many anti-aliased blends otherwise make megabytes)."""
    import io
    buffer = io.BytesIO()
    fig.savefig(buffer, dpi=dpi, format="png")
    plt.close(fig)
    try:
        from PIL import Image, features
        if not features.check_feature("libimagequant"):
            raise ImportError("no libimagequant")
        image = Image.open(io.BytesIO(buffer.getvalue())).convert("RGB")
        image.quantize(colors=256, method=Image.Quantize.LIBIMAGEQUANT,
                       dither=Image.Dither.NONE).save(out, format="png", optimize=True)
    except (ImportError, AttributeError, ValueError, OSError):
        with open(out, "wb") as f:
            f.write(buffer.getvalue())


def png_size(path):
    import struct
    with open(path, "rb") as f:
        head = f.read(24)
    return list(struct.unpack(">II", head[16:24])) if head[12:16] == b"IHDR" else None


# ---------------------------------------------------------------- frames.png


def body_colours(frames, body_names, field_shown):
    """A colour and kind per body present, by the kind of its particles."""
    first = frames[0]
    used = {KIND_WALL: 0, KIND_ELASTIC: 0, KIND_RIGID: 0}
    colours, kinds = {}, {}
    for b in range(len(body_names)):
        members = first["kind"][first["body"] == b]
        if members.size == 0:
            continue
        kind = int(members[0])
        palette = (GREYS if field_shown and kind != KIND_ELASTIC else PALETTE)[kind]
        colours[b] = palette[used[kind] % len(palette)]
        kinds[b] = kind
        used[kind] += 1
    return colours, kinds


def colour_scale(frames, field):
    """Symmetric limits about 0 for the field over the elastic particles of
    every frame, its unit and whether it had to be clipped."""
    values = np.concatenate([fr[field][fr["kind"] == KIND_ELASTIC] for fr in frames])
    values = values[np.isfinite(values)]
    if field == "pressure":
        biggest = float(np.abs(values).max()) if values.size else 0.0
        unit, scale = ("MPa", 1e-6) if biggest >= 1e6 else ("kPa", 1e-3) if biggest >= 1e3 \
            else ("Pa", 1.0)
        quantity, symbol = "pressure", "p"
        label = f"pressure p ({unit}; > 0 in compression)"
    else:
        unit, scale, quantity, symbol = "1", 1.0, "volumetric strain", "tr ε"
        label = "volumetric strain (dimensionless)"
    values = values * scale
    if values.size == 0:
        return {"quantity": quantity, "unit": unit, "scale": scale, "limit": 1.0,
                "clipped": False, "data_range": None, "label": label}
    biggest = float(np.abs(values).max())
    typical = float(np.percentile(np.abs(values), COLOUR_CLIP_PERCENTILE))
    clipped = typical > 0 and biggest > COLOUR_CLIP_WHEN * typical
    limit = typical if clipped else biggest
    limit = limit if limit > 0 else 1.0
    lo, hi = float(values.min()), float(values.max())
    if clipped:
        label += (f"\ncolour clipped to ±{number(limit)} (the {COLOUR_CLIP_PERCENTILE:g}th "
                  f"percentile of |{symbol}|); range {number(lo)} .. {number(hi)}")
    return {"quantity": quantity, "unit": unit, "scale": scale, "limit": limit,
            "clipped": clipped, "data_range": [lo, hi], "label": label}


def plot_frames(folder, frames, body_names, l0, total, color_by, dpi, title, blowup, footnote):
    from matplotlib.colors import Normalize
    from matplotlib.lines import Line2D

    field = {"pressure": "pressure", "strain": "strain"}.get(color_by)
    colours, kinds = body_colours(frames, body_names, field is not None)
    scale = colour_scale(frames, field) if field else None

    # Picture coordinates in mm. Normally x points down the page and y across
    # (the rod stands on its wall, the push of the plate goes down the page);
    # a body far longer in x than in y (a strip) lies along the page, x across.
    every = np.concatenate([fr["position"] for fr in frames]) * 1e3
    every = every[np.all(np.isfinite(every), axis=1)]
    pad = 1.5 * l0 * 1e3
    x_range = (every[:, 0].min() - pad, every[:, 0].max() + pad)
    y_range = (every[:, 1].min() - pad, every[:, 1].max() + pad)
    x_along = (x_range[1] - x_range[0]) > 4.0 * (y_range[1] - y_range[0])
    if x_along:
        across, down, names = x_range, y_range[::-1], ("x (mm)", "y (mm)")
        picture = lambda p: (p[..., 0], p[..., 1])
    else:
        across, down, names = y_range, x_range, ("y (mm)", "x (mm)")
        picture = lambda p: (p[..., 1], p[..., 0])
    data_w, data_h = across[1] - across[0], abs(down[1] - down[0])

    # Layout in inches: margins, gaps, then panels at the data's aspect; as
    # many columns (at most 6) as give the largest panels in a figure at most
    # 13 inches high.
    n = len(frames)
    left, gap, row_gap = 0.75, 0.12, 0.42
    right = 1.75 if field else 0.3
    chrome = 2.4   # heading, tick labels, legend and footnote, about

    def layout(columns):
        rows = math.ceil(n / columns)
        panel_w = (FIGURE_WIDTH_IN - left - right - (columns - 1) * gap) / columns
        panel_h = panel_w * data_h / data_w
        if panel_h > 5.0:              # a tall body: keep the figure's height sensible
            panel_h = 5.0
            panel_w = panel_h * data_w / data_h
        height = chrome + rows * panel_h + (rows - 1) * row_gap
        return panel_w * panel_h, height <= 13.0, rows, panel_w, panel_h

    choices = [(c,) + layout(c) for c in range(min(MAX_COLUMNS, n), 0, -1)]
    fitting = [ch for ch in choices if ch[2]] or choices[:1]
    best = max(ch[1] for ch in fitting)
    # Among the (nearly) largest: the fewest empty slots, then the most columns.
    columns, _, _, rows, panel_w, panel_h = min(
        (ch for ch in fitting if ch[1] >= 0.98 * best),
        key=lambda ch: (ch[3] * ch[0] - n, -ch[0]))
    fig_w = left + right + columns * panel_w + (columns - 1) * gap
    if fig_w < 12.0:               # room for the titles and the legend: centre the grid
        left += (12.0 - fig_w) / 2
        fig_w = 12.0
    shown = f"{n} of {total} frames" if n < total else f"{n} frames"
    what = {"body": "body", "pressure": "pressure", "strain": "volumetric strain"}[color_by]
    heading, top = header_lines(
        fig_w, title, f"particles at {shown}, coloured by {what}",
        blowup_words(blowup) + "; the last frame is the last good state" if blowup else None)
    top += 0.12
    notes = wrap_to(footnote, fig_w - 0.2, 7)
    cmap = "coolwarm"
    # The legend: one row if it fits, else two.
    handles, labels = [], []
    for b, colour in colours.items():
        scaled = field and kinds[b] == KIND_ELASTIC
        if scaled:
            continue
        handles.append(Line2D([], [], marker="o", linestyle="", markersize=8, color=colour))
        labels.append(f"{body_names[b]} ({KIND_NAMES[kinds[b]]})")
    scaled = [body_names[b] for b in colours if kinds[b] == KIND_ELASTIC]
    if field and scaled:
        handles.insert(0, Line2D([], [], marker="o", linestyle="", markersize=8,
                                 color=plt.get_cmap(cmap)(0.8)))
        labels.insert(0, f"{', '.join(scaled)} (elastic, coloured by {scale['quantity']})")
    if blowup and blowup.get("position"):
        handles.append(Line2D([], [], marker="o", linestyle="", markersize=11,
                              markerfacecolor="none", markeredgecolor=BLOWUP_COLOUR,
                              markeredgewidth=1.6))
        labels.append(f"particle {blowup.get('particle_id')} at the blow-up "
                      f"(t = {ms(blowup['time'])})")
    legend_columns = len(labels)
    if sum(len(l) * 9.5 * 0.55 / 72.0 + 0.45 for l in labels) > fig_w - 0.4:
        legend_columns = math.ceil(len(labels) / 2)
    legend_rows = math.ceil(len(labels) / max(legend_columns, 1))
    bottom = 0.62 + 0.36 * legend_rows + 0.14 + 0.12 * len(notes)  # ticks, legend, footnote
    fig_h = top + bottom + rows * panel_h + (rows - 1) * row_gap
    fig = plt.figure(figsize=(fig_w, fig_h))

    # Dots about one lattice spacing across.
    points_per_mm = panel_w * 72.0 / data_w
    size = (0.9 * l0 * 1e3 * points_per_mm) ** 2
    norm = Normalize(vmin=-scale["limit"], vmax=scale["limit"]) if field else None

    panels, mappable, axes = [], None, []
    for k, fr in enumerate(frames):
        r, c = divmod(k, columns)
        x0 = left + c * (panel_w + gap)
        y0 = fig_h - top - (r + 1) * panel_h - r * row_gap
        ax = fig.add_axes([x0 / fig_w, y0 / fig_h, panel_w / fig_w, panel_h / fig_h])
        axes.append(ax)
        across_mm, down_mm = picture(fr["position"] * 1e3)
        for b, colour in colours.items():
            sel = fr["body"] == b
            if field and kinds[b] == KIND_ELASTIC:
                mappable = ax.scatter(across_mm[sel], down_mm[sel], s=size,
                                      c=fr[field][sel] * scale["scale"], cmap=cmap, norm=norm,
                                      linewidths=0)
            else:
                ax.scatter(across_mm[sel], down_mm[sel], s=size, color=colour, linewidths=0)
        frame_axes(ax, across, down, labelsize=8, ticklength=3)
        label = f"t = {ms(fr['time'])}"
        ax.set_title(label, fontsize=10, pad=4)
        below_empty = k + columns >= n   # nothing under this panel
        if below_empty:
            ax.set_xlabel(names[0], fontsize=9)
        else:
            ax.tick_params(labelbottom=False)
        if c == 0:
            ax.set_ylabel(names[1], fontsize=9)
        else:
            ax.tick_params(labelleft=False)
        panel = {"time": fr["time"], "title": label, "row": r, "column": c,
                 "last_good_state": False}
        if blowup and k == n - 1:
            panel["last_good_state"] = True
            for spine in ax.spines.values():
                spine.set_edgecolor(BLOWUP_COLOUR)
                spine.set_linewidth(1.8)
            ax.set_title(label, fontsize=10, pad=4, color=BLOWUP_COLOUR)
            ax.text(0.5, 0.985, "last good state", transform=ax.transAxes, ha="center",
                    va="top", fontsize=8.5, color=BLOWUP_COLOUR, fontweight="bold",
                    bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=1.5))
            if blowup.get("position"):
                px, py = (v * 1e3 for v in blowup["position"])
                ax.scatter(*picture(np.array([[px, py]])), s=(6 * l0 * 1e3 * points_per_mm) ** 2,
                           facecolors="none", edgecolors=BLOWUP_COLOUR, linewidths=1.6,
                           zorder=5)
                panel["ring_mm"] = [px, py]
        panels.append(panel)

    fig.legend(handles, labels, loc="lower center", ncol=legend_columns, frameon=False,
               fontsize=9.5, bbox_to_anchor=(0.5, (0.1 + 0.12 * len(notes)) / fig_h))

    colorbar = None
    if mappable is not None:
        grid_top = fig_h - top
        grid_bottom = grid_top - rows * panel_h - (rows - 1) * row_gap
        x0 = left + columns * panel_w + (columns - 1) * gap + 0.22
        cax = fig.add_axes([x0 / fig_w, grid_bottom / fig_h, 0.17 / fig_w,
                            (grid_top - grid_bottom) / fig_h])
        lo, hi = scale["data_range"] or (0, 0)
        extend = ("both" if lo < -scale["limit"] and hi > scale["limit"] else
                  "min" if lo < -scale["limit"] else "max" if hi > scale["limit"] else
                  "neither")
        bar = fig.colorbar(mappable, cax=cax, extend=extend)
        bar.set_label(scale["label"], fontsize=10)
        bar.ax.tick_params(labelsize=8.5)
        colorbar = {"label": scale["label"], "quantity": scale["quantity"],
                    "unit": scale["unit"], "limits": [-scale["limit"], scale["limit"]],
                    "clipped": scale["clipped"], "data_range": scale["data_range"],
                    "extend": extend}

    draw_header(fig, fig_h, heading, notes)
    out = os.path.join(folder, "frames.png")
    save_png(fig, out, dpi)
    return {"file": out, "size_px": png_size(out), "rows": rows, "columns": columns,
            "orientation": "x across the page" if x_along else "x down the page",
            "color": color_by, "title": title, "panels": panels, "colorbar": colorbar,
            "legend": labels, "footnote": footnote,
            "blowup": None if not blowup else {
                "time": blowup["time"], "criterion": blowup["criterion"],
                "last_good_state_panel": n - 1,
                "particle_position_mm": panels[-1].get("ring_mm")}}


# ---------------------------------------------------------------- history.png


def plot_history(folder, h, dpi, title, blowup, footnote, reference):
    t = h["t"] * 1e3
    marker = {"marker": "o", "markersize": 2.5} if t.size <= 60 else {}
    rigid = [c[:-2] for c in h if c.endswith(".x") and c[:-2] + ".theta" in h]
    elastic = [c[:-5] for c in h if c.endswith(".xmin")]
    probes = [c[6:-2] for c in h if c.startswith("probe.") and c.endswith(".x")]

    names = []
    if rigid:
        names.append("rigid")
    if elastic or probes:
        names += ["x", "y"]
    names += ["energy", "balance", "speed"]
    if reference is not None and not rigid:
        fail("--reference: this run has no rigid body to compare its displacement with")
    columns = 3
    rows = math.ceil(len(names) / columns)
    fig_w = FIGURE_WIDTH_IN
    heading, top = header_lines(fig_w, title, f"history: {t.size} rows to t = {ms(h['t'][-1])}",
                                blowup_words(blowup) if blowup else None)
    notes = wrap_to(footnote, fig_w - 0.2, 7)
    bottom = 0.12 + 0.12 * len(notes)
    fig_h = 4.0 * rows + top + bottom
    fig, grid = plt.subplots(rows, columns, figsize=(fig_w, fig_h), squeeze=False)
    for ax in grid.flat[len(names):]:
        ax.set_visible(False)
    axes = dict(zip(names, grid.flat))
    panels = {}

    def panel(name, ax, heading, ylabel):
        ax.set_title(heading, fontsize=11)
        ax.set_ylabel(ylabel)
        ax.set_xlabel("time (ms)")
        panels[name] = {"title": heading, "ylabel": ylabel, "lines": []}

    def line(name, x, y, label, **style):
        axes[name].plot(x, y, label=label, **style)
        panels[name]["lines"].append(label)

    if rigid:
        panel("rigid", axes["rigid"], "rigid bodies: displacement", "displacement (mm)")
        for b in rigid:
            line("rigid", t, h[b + ".x"] * 1e3, f"{b}: x", linewidth=1.6, **marker)
            if np.any(np.abs(h[b + ".y"]) > 1e-9):
                line("rigid", t, h[b + ".y"] * 1e3, f"{b}: y", linewidth=1.2, **marker)
        if reference is not None:
            path, (rt, rx) = reference
            line("rigid", rt * 1e3, rx * 1e3, f"reference: {os.path.basename(path)}",
                 color="black", linestyle="--", linewidth=1.2,
                 **({"marker": "x", "markersize": 4} if rt.size <= 60 else {}))
            panels["rigid"]["reference"] = {"file": os.path.abspath(path), "points": int(rt.size)}
    if "x" in axes:
        for axis in ("x", "y"):
            panel(axis, axes[axis], f"elastic bodies: {axis} extent"
                  + (" and probes" if probes else " (particle centres)"), f"{axis} (mm)")
            cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
            for k, b in enumerate(elastic):
                lo, hi = h[f"{b}.{axis}min"] * 1e3, h[f"{b}.{axis}max"] * 1e3
                colour = cycle[k % len(cycle)]
                axes[axis].fill_between(t, lo, hi, color=colour, alpha=0.12, linewidth=0)
                line(axis, t, hi, f"{b}: {axis} max", color=colour, linewidth=1.5, **marker)
                line(axis, t, lo, f"{b}: {axis} min", color=colour, linewidth=1.5,
                     linestyle="-.", **marker)
            for p in probes:
                line(axis, t, h[f"probe.{p}.{axis}"] * 1e3, f"probe {p}", linewidth=1.1,
                     linestyle=":", **marker)

    ke, pe, w = h["kinetic_energy"], h["strain_energy"], h["external_work"]
    panel("energy", axes["energy"], "energies", "energy (J per m of depth)")
    line("energy", t, w, "external work W", color="black", linewidth=1.6)
    line("energy", t, ke, "kinetic KE", color="#d1495b", linewidth=1.4)
    line("energy", t, pe, "strain PE", color="#2a6fb0", linewidth=1.4)
    line("energy", t, ke + pe, "KE + PE", color="#7b4fa6", linewidth=1.0, linestyle="--")

    e0 = ke[0] + pe[0]
    w_max = float(np.max(np.abs(w)))
    reference_energy = w_max if w_max > 0 else float(np.max(np.abs(ke + pe)))
    by = "max W" if w_max > 0 else "max(KE + PE)"
    error = (ke + pe - w - e0) / (reference_energy if reference_energy > 0 else 1.0) * 100.0
    panel("balance", axes["balance"], "energy balance error",
          f"(KE + PE − W − E0) / {by} (%)")
    line("balance", t, error, f"(KE + PE − W − E0) / {by}", color="black", linewidth=1.4,
         **marker)
    axes["balance"].axhline(0.0, color="#999999", linewidth=0.8)
    final = float(error[-1])
    # The numbers behind it as a legend entry of its own (the legend finds a free corner).
    axes["balance"].plot([], [], linestyle="none",
                         label=f"E0 = {number(e0)} J, {by} = {number(reference_energy)} J\n"
                               f"at t = {ms(h['t'][-1])}: {number(final)} %")
    panels["balance"].update({"E0": float(e0), "normalised_by": by,
                              "scale": reference_energy, "final_percent": final,
                              "max_abs_percent": float(np.max(np.abs(error)))})

    panel("speed", axes["speed"], "fastest particle", "max speed (m/s)")
    if "max_speed" in h:
        line("speed", t, h["max_speed"], "max |v|", color="#3a9a5b", linewidth=1.4, **marker)

    for name, ax in axes.items():
        ax.grid(True, linewidth=0.4, alpha=0.6)
        ax.tick_params(labelsize=9)
        if blowup:
            # The line a little inside the right edge, what follows it shaded.
            tb = blowup["time"] * 1e3
            right = max(t.max(), tb) + 0.04 * (max(t.max(), tb) - t.min())
            ax.set_xlim(t.min(), right)
            ax.axvspan(tb, right, color=BLOWUP_COLOUR, alpha=0.07, linewidth=0)
            ax.axvline(tb, color=BLOWUP_COLOUR, linestyle="--", linewidth=1.3,
                       label=f"blow-up, t = {ms(blowup['time'])}")
            panels[name]["blowup_marker"] = {"time": blowup["time"],
                                             "criterion": blowup["criterion"]}
        else:
            ax.set_xlim(t.min(), t.max())
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8.5, loc="best", framealpha=0.85)
    if blowup:
        axes["balance"].annotate(
            "\n".join(["blow-up criterion:"] + [
                piece for part in blowup["criterion"].replace(" (", "\n(", 1).split("\n")
                for piece in textwrap.wrap(part, 40)]),
            xy=(blowup["time"] * 1e3, 1.0), xycoords=("data", "axes fraction"),
            xytext=(-6, -40), textcoords="offset points", ha="right", va="top", fontsize=8,
            color=BLOWUP_COLOUR,
            bbox=dict(facecolor="white", edgecolor=BLOWUP_COLOUR, alpha=0.9, linewidth=0.6))

    draw_header(fig, fig_h, heading, notes)
    fig.tight_layout(rect=(0, bottom / fig_h, 1, 1 - top / fig_h), h_pad=1.6, w_pad=1.5)
    out = os.path.join(folder, "history.png")
    save_png(fig, out, dpi)
    return {"file": out, "size_px": png_size(out), "title": title, "footnote": footnote,
            "panels": [dict(name=name, **panels[name]) for name in names],
            "reference": panels.get("rigid", {}).get("reference"),
            "blowup": None if not blowup else {"time": blowup["time"],
                                               "criterion": blowup["criterion"]}}


def main():
    args = parse_args()
    load_libraries()
    check_folder(args.dir)
    if args.frames < 1:
        fail("--frames must be at least 1")
    if args.dpi < 20:
        fail("--dpi must be at least 20")
    reference = (args.reference, read_reference(args.reference)) if args.reference else None
    history = read_history(os.path.join(args.dir, "history.csv"))
    frames, body_names, l0, total = read_frames(os.path.join(args.dir, "frames.h5"), args.frames)
    run, case = read_run(args.dir)
    title, blowup, footnote = describe_run(args.dir, run, case)
    drawn = {"frames": plot_frames(args.dir, frames, body_names, l0, total, args.color, args.dpi,
                                   title, blowup, footnote),
             "history": plot_history(args.dir, history, args.dpi, title, blowup, footnote,
                                     reference)}
    if args.describe:
        print(json.dumps(drawn, indent=2))
    else:
        for what in drawn.values():
            print(f"plot.py: wrote {what['file']} ({what['size_px'][0]} x "
                  f"{what['size_px'][1]} px)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
