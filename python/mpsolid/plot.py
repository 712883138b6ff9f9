"""The pictures of a run folder, read through run_data: frames.png (the
particles of up to K frames in a grid) and history.png (the history's curves
against time). tools/plot.py is their command line and says what each
picture holds; plot_run() draws both and returns what was drawn.

Needs numpy, h5py and matplotlib (Debian's python3-h5py and
python3-matplotlib). The figures are made without pyplot, so drawing leaves
an interactive session's backend and open figures alone.
"""
import csv
import io
import math
import os
import struct
import textwrap

import matplotlib
import numpy as np
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from . import plot_shapes, run_data

KIND_WALL, KIND_ELASTIC, KIND_RIGID = 0, 1, 2
KIND_NAMES = {KIND_WALL: "wall", KIND_ELASTIC: "elastic", KIND_RIGID: "rigid"}
# Body colours by kind (colour by body): elastic bodies in blues/greens, rigid
# in reds, walls grey.
PALETTE = {
    KIND_ELASTIC: ["#2a6fb0", "#3a9a5b", "#7b4fa6", "#1b9e9e"],
    KIND_RIGID: ["#c8382f", "#e08a1e", "#a63d73"],
    KIND_WALL: ["#555555", "#8c8c8c"],
}
# Colouring by a field: rigid bodies and walls in neutral greys, darker than
# the colour map's pale middle.
GREYS = {KIND_RIGID: ["#6f6f6f", "#8f8f8f", "#555555"], KIND_WALL: ["#2f2f2f", "#474747"]}
BLOWUP_COLOUR = "#d4001a"
OUTLINE_COLOUR = "#404040"   # a shaped body's outline at t = 0
PRESSURE_COLOUR = "#5e3c99"  # a pressure load's arrows
COLOUR_MAP = "coolwarm"
MAX_COLUMNS = 6
FIGURE_WIDTH_IN = 14.6   # frames.png: 2190 px at 150 dpi
COLOUR_CLIP_PERCENTILE = 99.0
COLOUR_CLIP_WHEN = 1.25  # clip when the largest |value| exceeds the percentile by this factor
# How elastic bodies may be coloured: the frames.h5 field of each, and its words.
COLOUR_FIELDS = {"pressure": "pressure", "strain": "volumetric_strain"}
COLOUR_WORDS = {"body": "body", "pressure": "pressure", "strain": "volumetric strain"}
HISTORY_COLUMNS_NEEDED = ("t", "kinetic_energy", "strain_energy", "external_work")


class PlotError(Exception):
    """A run folder that cannot be drawn: `code` 2 for something missing (a
    folder, its results, a reference file), 1 for results that cannot be read."""

    def __init__(self, message, code=2):
        super().__init__(message)
        self.code = code


# ---------------------------------------------------------------- reading


def check_folder(folder):
    """Raises PlotError unless `folder` holds a run's frames and history."""
    if not os.path.isdir(folder):
        raise PlotError(f"{folder}: no such folder")
    missing = [f for f in (run_data.FRAMES_H5, run_data.HISTORY_CSV)
               if not os.path.isfile(os.path.join(folder, f))]
    if missing:
        raise PlotError(f"{folder} has no results ({' and '.join(missing)} missing): run "
                        f"`mpsolid run CASE --out {folder}` first")


def history_to_draw(folder):
    """history.csv as {column: array}, with at least one row and the energies."""
    path = os.path.join(folder, run_data.HISTORY_CSV)
    try:
        columns = run_data.read_history_columns(folder)
    except (OSError, ValueError) as e:
        raise PlotError(f"{path} is not a history.csv of mpsolid ({e})", 1) from None
    if not columns or next(iter(columns.values())).size == 0:
        raise PlotError(f"{path} has no rows", 1)
    for needed in HISTORY_COLUMNS_NEEDED:
        if needed not in columns:
            raise PlotError(f"{path} has no column {needed}", 1)
    return columns


# A section across each axis: the position columns it draws (across the
# section, then the axis itself last) and their names.
SECTION_AXES = {"x": ((1, 2, 0), ("y", "z")), "y": ((0, 2, 1), ("x", "z")),
                "z": ((0, 1, 2), ("x", "y"))}


class Section:
    """A frame cut to the particles of `keep` (a boolean mask in id order):
    read as the frame is, field by field, its positions in the section's
    plane (`axis_names`) first."""

    def __init__(self, frame, keep, axis="z"):
        self._frame, self._keep = frame, keep
        self._columns, self.axis_names = SECTION_AXES[axis]
        self.time, self.step = frame.time, frame.step

    def __getitem__(self, name):
        values = self._frame[name][self._keep]
        return values[:, self._columns] if name == "position" else values

    def fields(self):
        return self._frame.fields()


def parse_section(section):
    """A section as (axis, value in m): a number is a z, "x=0.05" a plane
    across x; raises PlotError for anything else."""
    if isinstance(section, (int, float)):
        return "z", float(section)
    axis, _, value = str(section).rpartition("=")
    axis = axis.strip() or "z"
    try:
        at = float(value)
    except ValueError:
        at = None
    if axis not in SECTION_AXES or at is None or not np.isfinite(at):
        raise PlotError(f"--section {section}: expected Z, or x=X, y=Y or z=Z (m)")
    return axis, at


def cut_to_section(frames, section, l0):
    """The frames cut to one layer of particles: those within half a spacing
    of the particle nearest the plane (`section`: see parse_section) in the
    first frame (the same particles in every panel: a material section),
    and that layer's (axis, value); raises PlotError for a plane run or a
    plane off every body."""
    axis, at = parse_section(section)
    position = frames[0]["position"]
    if position.shape[1] != 3:
        raise PlotError("--section needs a run in space (dimension = 3)")
    column = position[:, "xyz".index(axis)]
    nearest = column[np.argmin(np.abs(column - at))]
    if abs(nearest - at) > l0:
        raise PlotError(f"--section {axis}={at:g}: no particle within l0 = {l0:g} m of that "
                        f"{axis} ({axis} from {column.min():g} to {column.max():g} m)")
    keep = np.abs(column - nearest) < 0.5 * l0
    return [Section(frame, keep, axis) for frame in frames], (axis, float(nearest))


def pick(count, limit):
    """Up to `limit` indices of 0..count-1, evenly spread, first and last kept."""
    if count <= limit:
        return list(range(count))
    if limit == 1:
        return [count - 1]
    return sorted(set(int(k) for k in np.round(np.linspace(0, count - 1, limit))))


def read_frames(folder, limit, field):
    """Up to `limit` frames of frames.h5 (pick), their fields for drawing read
    now, so that an unreadable file fails here and not half-way through a
    picture; with the body names, l0 and the number of frames stored."""
    path = os.path.join(folder, run_data.FRAMES_H5)
    try:
        stored = run_data.Frames(path)
        if len(stored) == 0:
            raise PlotError(f"{path} holds no frames", 1)
        frames = [stored[k] for k in pick(len(stored), limit)]
        for frame in frames:
            for name in ("position", "body", "kind") + ((field,) if field else ()):
                frame[name]
        l0 = float(stored.attrs["l0"])
    except (OSError, KeyError) as e:
        raise PlotError(f"{path} cannot be read as mpsolid frames ({e})", 1) from None
    return frames, stored.body_names, l0, len(stored)


def read_reference(path, option="--reference", units="t, x (seconds, metres)"):
    """(t, x) arrays from a CSV of two columns (`units`: t, x in s, m for
    --reference); a header row and # comments allowed. A user's file, not a
    run's: read here; errors name `option`."""
    if not os.path.isfile(path):
        raise PlotError(f"{option} {path}: no such file")
    t, x = [], []
    with open(path, newline="") as f:
        for number_, row in enumerate(csv.reader(f), start=1):
            if not row or not "".join(row).strip() or row[0].lstrip().startswith("#"):
                continue
            try:
                t.append(float(row[0]))
                x.append(float(row[1]))
            except (ValueError, IndexError):
                if t:   # only the first row may be a header
                    raise PlotError(f"{option} {path}: line {number_} is not two numbers "
                                    f"{units}: {row}") from None
    if not t:
        raise PlotError(f"{option} {path}: no rows of {units}")
    return np.array(t), np.array(x)


# ---------------------------------------------------------------- words


def number(v, digits=3):
    """v to `digits` significant digits, without '-0' or 'e-05' padding."""
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
    """A time in s as milliseconds: the pictures' time unit."""
    return f"{number(t * 1e3, 4)} ms"


def force_words(name, load):
    """'load shock: 11.2 kN in +x on plate from 1 ms', or None for a load
    without a constant force."""
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
    """The title line (case, model, l0, dt, loads), the blow-up (or None) and
    the footnote, from run.json and case.resolved.toml (either may be {})."""
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
    """'blow-up at t = ...: criterion (particle N of body)'."""
    words = f"blow-up at t = {ms(blowup['time'])}: {blowup['criterion']}"
    if blowup.get("particle_id") is not None:
        words += f" (particle {blowup['particle_id']}"
        words += f" of {blowup['body']})" if blowup.get("body") else ")"
    return words


def wrap_to(text, width_in, fontsize):
    """Lines of text that fit a width in inches at a font size (an average
    glyph taken as 0.55 em)."""
    return textwrap.wrap(text, max(20, int(width_in * 72.0 / (0.55 * fontsize))))


# ---------------------------------------------------------------- figures


def header_lines(fig_w, title, subtitle, alarm):
    """The heading's lines as (text, font size, colour) and its height in inches."""
    lines = [(text, 13, "black") for text in wrap_to(title, fig_w - 0.4, 13)]
    lines.append((subtitle, 10.5, "#333333"))
    lines += [(text, 10, BLOWUP_COLOUR) for text in (wrap_to(alarm, fig_w - 0.4, 10)
                                                     if alarm else [])]
    return lines, 0.2 + sum(size * 1.45 / 72.0 for _, size, _ in lines) + 0.1


def draw_header(fig, fig_h, lines, notes):
    """The heading at the top of the figure, the footnote at its bottom left."""
    y = 0.2
    for text, size, colour in lines:
        fig.text(0.5, 1 - y / fig_h, text, ha="center", va="top", fontsize=size, color=colour)
        y += size * 1.45 / 72.0
    fig.text(0.006, 0.05 / fig_h, "\n".join(notes), ha="left", va="bottom", fontsize=7,
             color="#777777")


def frame_axes(ax, across, down, labelsize, ticklength):
    """A frame panel's axes: across (mm) to the right, down (mm) down the
    page, equal aspect, a light grid behind the particles."""
    ax.set_xlim(*across)
    ax.set_ylim(down[1], down[0])
    ax.set_aspect("equal")
    ax.grid(True, linewidth=0.3, alpha=0.5)
    ax.set_axisbelow(True)
    ax.tick_params(labelsize=labelsize, length=ticklength)


def legend_marker(colour, size=8):
    """A legend entry's dot."""
    return Line2D([], [], marker="o", linestyle="", markersize=size, color=colour)


def save_png(fig, out, dpi):
    """Writes the figure as a PNG; where Pillow has libimagequant (Debian's
    does), as 256 well-chosen colours, a third of the size with no visible
    banding (the dots' many anti-aliased blends otherwise make megabytes)."""
    buffer = io.BytesIO()
    fig.savefig(buffer, dpi=dpi, format="png")
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
    """[width, height] in pixels of a PNG file, from its header."""
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


class FrameView:
    """Where the particles go on the page, in mm. Normally x points down the
    page and y across (the rod stands on its wall, the push of the plate goes
    down the page); a body far longer in x than in y (a strip) lies along
    the page, x across. The box holds every frame's particles, padded."""

    def __init__(self, frames, l0):
        every = np.concatenate([fr["position"] for fr in frames]) * 1e3
        every = every[np.all(np.isfinite(every), axis=1)]
        pad = 1.5 * l0 * 1e3
        x_range = (every[:, 0].min() - pad, every[:, 0].max() + pad)
        y_range = (every[:, 1].min() - pad, every[:, 1].max() + pad)
        # The page's first and second axes: x and y, or a section's own.
        self.names = getattr(frames[0], "axis_names", ("x", "y"))
        first, second = (f"{name} (mm)" for name in self.names)
        self.x_along = (x_range[1] - x_range[0]) > 4.0 * (y_range[1] - y_range[0])
        if self.x_along:
            self.across, self.down, self.labels = x_range, y_range[::-1], (first, second)
        else:
            self.across, self.down, self.labels = y_range, x_range, (second, first)
        self.width = self.across[1] - self.across[0]
        self.height = abs(self.down[1] - self.down[0])

    def page(self, p):
        """(across, down) of positions p in mm (... x 2)."""
        return (p[..., 0], p[..., 1]) if self.x_along else (p[..., 1], p[..., 0])


class FramesLayout:
    """frames.png's geometry in inches: margins, gaps, then panels at the
    data's aspect; as many columns (at most MAX_COLUMNS) as give the largest
    panels in a figure at most 13 inches high. The height is known once the
    heading and the legend are (set_height)."""

    GAP, ROW_GAP, CHROME = 0.12, 0.42, 2.4   # CHROME: heading, ticks, legend, footnote, about

    def __init__(self, n, view, colourbar):
        self.n, self.gap, self.row_gap = n, self.GAP, self.ROW_GAP
        self.left, self.right = 0.75, 1.75 if colourbar else 0.3
        choices = [(c,) + self._trial(c, view) for c in range(min(MAX_COLUMNS, n), 0, -1)]
        fitting = [ch for ch in choices if ch[2]] or choices[:1]
        best = max(ch[1] for ch in fitting)
        # Among the (nearly) largest: the fewest empty slots, then the most columns.
        self.columns, _, _, self.rows, self.panel_w, self.panel_h = min(
            (ch for ch in fitting if ch[1] >= 0.98 * best),
            key=lambda ch: (ch[3] * ch[0] - n, -ch[0]))
        self.fig_w = (self.left + self.right + self.columns * self.panel_w
                      + (self.columns - 1) * self.gap)
        if self.fig_w < 12.0:      # room for the titles and the legend: centre the grid
            self.left += (12.0 - self.fig_w) / 2
            self.fig_w = 12.0
        self.top = self.fig_h = None

    def _trial(self, columns, view):
        """(panel area, fits 13 inches, rows, panel width, panel height)."""
        rows = math.ceil(self.n / columns)
        panel_w = (FIGURE_WIDTH_IN - self.left - self.right - (columns - 1) * self.gap) / columns
        panel_h = panel_w * view.height / view.width
        if panel_h > 5.0:              # a tall body: keep the figure's height sensible
            panel_h = 5.0
            panel_w = panel_h * view.width / view.height
        height = self.CHROME + rows * panel_h + (rows - 1) * self.row_gap
        return panel_w * panel_h, height <= 13.0, rows, panel_w, panel_h

    def set_height(self, top, bottom):
        """The figure's height from the room above and below the grid."""
        self.top = top
        self.fig_h = top + bottom + self.rows * self.panel_h + (self.rows - 1) * self.row_gap

    def place(self, k):
        """(row, column) of the k-th panel, in time order row by row."""
        return divmod(k, self.columns)

    def panel_box(self, k):
        """The k-th panel's [left, bottom, width, height] in figure fractions."""
        r, c = self.place(k)
        x0 = self.left + c * (self.panel_w + self.gap)
        y0 = self.fig_h - self.top - (r + 1) * self.panel_h - r * self.row_gap
        return [x0 / self.fig_w, y0 / self.fig_h, self.panel_w / self.fig_w,
                self.panel_h / self.fig_h]

    def colourbar_box(self):
        """The colourbar's box, right of the grid and as tall as it."""
        grid_top = self.fig_h - self.top
        grid_bottom = grid_top - self.rows * self.panel_h - (self.rows - 1) * self.row_gap
        x0 = self.left + self.columns * self.panel_w + (self.columns - 1) * self.gap + 0.22
        return [x0 / self.fig_w, grid_bottom / self.fig_h, 0.17 / self.fig_w,
                (grid_top - grid_bottom) / self.fig_h]


def frames_legend(colours, kinds, body_names, scale, blowup):
    """(handles, labels): each body drawn in its own colour, the elastic
    bodies coloured by a field as one entry, and the ringed particle."""
    handles, labels = [], []
    for b, colour in colours.items():
        if scale and kinds[b] == KIND_ELASTIC:
            continue
        handles.append(legend_marker(colour))
        labels.append(f"{body_names[b]} ({KIND_NAMES[kinds[b]]})")
    scaled = [body_names[b] for b in colours if kinds[b] == KIND_ELASTIC]
    if scale and scaled:
        handles.insert(0, legend_marker(matplotlib.colormaps[COLOUR_MAP](0.8)))
        labels.insert(0, f"{', '.join(scaled)} (elastic, coloured by {scale['quantity']})")
    if blowup and blowup.get("position"):
        handles.append(Line2D([], [], marker="o", linestyle="", markersize=11,
                              markerfacecolor="none", markeredgecolor=BLOWUP_COLOUR,
                              markeredgewidth=1.6))
        labels.append(f"particle {blowup.get('particle_id')} at the blow-up "
                      f"(t = {ms(blowup['time'])})")
    return handles, labels


def legend_shape(labels, fig_w):
    """(columns, rows) of the legend: one row if it fits, else two."""
    columns = len(labels)
    if sum(len(l) * 9.5 * 0.55 / 72.0 + 0.45 for l in labels) > fig_w - 0.4:
        columns = math.ceil(len(labels) / 2)
    return columns, math.ceil(len(labels) / max(columns, 1))


def draw_particles(ax, frame, view, colours, kinds, field, scale, norm, size):
    """One frame's particles, body by body; the elastic ones coloured by the
    field when there is one. Returns the field's last scatter (or None)."""
    mappable = None
    position = frame["position"]
    across_mm, down_mm = view.page(position * 1e3)
    for b, colour in colours.items():
        sel = np.flatnonzero(frame["body"] == b)
        if position.shape[1] == 3:  # in space, seen from +z: the nearer drawn over the farther
            sel = sel[np.argsort(position[sel, 2], kind="stable")]
        if field and kinds[b] == KIND_ELASTIC:
            mappable = ax.scatter(across_mm[sel], down_mm[sel], s=size,
                                  c=frame[field][sel] * scale["scale"], cmap=COLOUR_MAP,
                                  norm=norm, linewidths=0)
        else:
            ax.scatter(across_mm[sel], down_mm[sel], s=size, color=colour, linewidths=0)
    return mappable


def label_frame_panel(ax, k, layout, view, title):
    """Its time above it; tick labels and axis names only on the grid's outer
    edges (the bottom of each column, the left of each row)."""
    _, c = layout.place(k)
    ax.set_title(title, fontsize=10, pad=4)
    if k + layout.columns >= layout.n:   # nothing under this panel
        ax.set_xlabel(view.labels[0], fontsize=9)
    else:
        ax.tick_params(labelbottom=False)
    if c == 0:
        ax.set_ylabel(view.labels[1], fontsize=9)
    else:
        ax.tick_params(labelleft=False)


def mark_last_good_state(ax, title, blowup, view, ring_size):
    """The last frame before a blow-up: a red frame and title, 'last good
    state', and the diagnosed particle ringed. Returns the ring's position
    in mm (or None)."""
    for spine in ax.spines.values():
        spine.set_edgecolor(BLOWUP_COLOUR)
        spine.set_linewidth(1.8)
    ax.set_title(title, fontsize=10, pad=4, color=BLOWUP_COLOUR)
    ax.text(0.5, 0.985, "last good state", transform=ax.transAxes, ha="center",
            va="top", fontsize=8.5, color=BLOWUP_COLOUR, fontweight="bold",
            bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=1.5))
    if not blowup.get("position"):
        return None
    # In space the two coordinates of the page's axes (a section's own).
    where = blowup["position"]
    px, py = (where["xyz".index(name)] * 1e3 for name in view.names) if len(where) == 3 else (
        v * 1e3 for v in where)
    ax.scatter(*view.page(np.array([[px, py]])), s=ring_size, facecolors="none",
               edgecolors=BLOWUP_COLOUR, linewidths=1.6, zorder=5)
    return [px, py]


def draw_colourbar(fig, mappable, scale, layout):
    """The one colourbar of every panel, an arrow at an end whose values were
    clipped; returns its description."""
    cax = fig.add_axes(layout.colourbar_box())
    lo, hi = scale["data_range"] or (0, 0)
    limit = scale["limit"]
    extend = ("both" if lo < -limit and hi > limit else
              "min" if lo < -limit else "max" if hi > limit else "neither")
    bar = fig.colorbar(mappable, cax=cax, extend=extend)
    bar.set_label(scale["label"], fontsize=10)
    bar.ax.tick_params(labelsize=8.5)
    return {"label": scale["label"], "quantity": scale["quantity"], "unit": scale["unit"],
            "limits": [-limit, limit], "clipped": scale["clipped"],
            "data_range": scale["data_range"], "extend": extend}


def draw_frame_panels(fig, frames, layout, view, colours, kinds, field, scale, l0, blowup,
                      shapes):
    """Every frame's panel (with the shaped bodies' outlines and the pressure
    loads' arrows of `shapes`), the last one marked after a blow-up; returns
    the panels' descriptions and the field's scatter (None without a field)."""
    # Dots about one lattice spacing across.
    points_per_mm = layout.panel_w * 72.0 / view.width
    size = (0.9 * l0 * 1e3 * points_per_mm) ** 2
    norm = Normalize(vmin=-scale["limit"], vmax=scale["limit"]) if field else None
    panels, mappable = [], None
    for k, frame in enumerate(frames):
        ax = fig.add_axes(layout.panel_box(k))
        drawn = draw_particles(ax, frame, view, colours, kinds, field, scale, norm, size)
        plot_shapes.draw_outlines(ax, shapes["outlines"], view, OUTLINE_COLOUR)
        plot_shapes.draw_pressure_arrows(ax, frame, shapes["loaded"], view,
                                         0.06 * max(view.width, 1e-9), PRESSURE_COLOUR)
        mappable = drawn if drawn is not None else mappable
        frame_axes(ax, view.across, view.down, labelsize=8, ticklength=3)
        label = f"t = {ms(frame.time)}"
        label_frame_panel(ax, k, layout, view, label)
        r, c = layout.place(k)
        panel = {"time": frame.time, "title": label, "row": r, "column": c,
                 "last_good_state": False}
        if blowup and k == len(frames) - 1:
            panel["last_good_state"] = True
            ring = mark_last_good_state(ax, label, blowup, view,
                                        (6 * l0 * 1e3 * points_per_mm) ** 2)
            if ring is not None:
                panel["ring_mm"] = ring
        panels.append(panel)
    return panels, mappable


def plot_frames(folder, frames, body_names, l0, total, color_by, dpi, title, blowup, footnote,
                case=None, section=None):
    """Writes FOLDER/frames.png: the frames in a grid, one colour scale over
    every panel (or body colours), the shaped bodies' reference outlines and
    the pressure loads' arrows (from `case`, the resolved case), and returns
    what was drawn."""
    field = COLOUR_FIELDS.get(color_by)
    colours, kinds = body_colours(frames, body_names, field is not None)
    case = case or {}
    shapes = {"outlines": plot_shapes.shape_outlines(case),
              "loaded": plot_shapes.loaded_particles(case, list(body_names), frames[0], l0)}
    scale = colour_scale(frames, field) if field else None
    view = FrameView(frames, l0)
    n = len(frames)
    layout = FramesLayout(n, view, colourbar=field is not None)

    shown = f"{n} of {total} frames" if n < total else f"{n} frames"
    seen = ", seen along z (the nearer particles over the farther)" if case.get(
        "dimension", 2) == 3 else ""
    if section is not None:
        seen = f", the layer at {section[0]} = {number(section[1] * 1e3)} mm at the start"
    heading, top = header_lines(
        layout.fig_w, title, f"particles at {shown}{seen}, coloured by {COLOUR_WORDS[color_by]}",
        blowup_words(blowup) + "; the last frame is the last good state" if blowup else None)
    notes = wrap_to(footnote, layout.fig_w - 0.2, 7)
    handles, labels = frames_legend(colours, kinds, body_names, scale, blowup)
    if shapes["outlines"]:
        handles.append(Line2D([], [], color=OUTLINE_COLOUR, linewidth=0.9,
                              linestyle=(0, (3, 2))))
        labels.append("outline at t = 0")
    if any(len(v) for v in shapes["loaded"].values()):
        handles.append(Line2D([], [], color=PRESSURE_COLOUR, marker=r"$\rightarrow$",
                              linestyle="", markersize=10))
        labels.append("pressure on the loaded surface")
    legend_columns, legend_rows = legend_shape(labels, layout.fig_w)
    layout.set_height(top + 0.12, 0.62 + 0.36 * legend_rows + 0.14 + 0.12 * len(notes))
    fig = Figure(figsize=(layout.fig_w, layout.fig_h))
    panels, mappable = draw_frame_panels(fig, frames, layout, view, colours, kinds, field,
                                         scale, l0, blowup, shapes)
    fig.legend(handles, labels, loc="lower center", ncol=legend_columns, frameon=False,
               fontsize=9.5, bbox_to_anchor=(0.5, (0.1 + 0.12 * len(notes)) / layout.fig_h))
    colorbar = draw_colourbar(fig, mappable, scale, layout) if mappable is not None else None
    draw_header(fig, layout.fig_h, heading, notes)
    out = os.path.join(folder, "frames.png")
    save_png(fig, out, dpi)
    return {"file": out, "size_px": png_size(out), "rows": layout.rows,
            "columns": layout.columns,
            "orientation": f"{view.names[0]} " + ("across" if view.x_along else "down")
                           + " the page",
            "color": color_by, "title": title,
            "section": None if section is None else {"axis": section[0], "at_m": section[1]},
            "section_z_m": section[1] if section and section[0] == "z" else None,
            "panels": panels,
            "colorbar": colorbar,
            "legend": labels, "footnote": footnote,
            "outlines": {b: len(lines) for b, lines in shapes["outlines"].items()},
            "pressure_particles": {name: len(v) for name, v in shapes["loaded"].items()},
            "blowup": None if not blowup else {
                "time": blowup["time"], "criterion": blowup["criterion"],
                "last_good_state_panel": n - 1,
                "particle_position_mm": panels[-1].get("ring_mm")}}


# ---------------------------------------------------------------- history.png


class HistoryFigure:
    """history.png's panels by name, in a grid of 3 columns, and what each
    shows (its title, axis label and lines: --describe's record)."""

    COLUMNS, PANEL_HEIGHT_IN = 3, 4.0

    def __init__(self, names, fig_w, top, bottom):
        self.names = names
        rows = math.ceil(len(names) / self.COLUMNS)
        self.fig_h = self.PANEL_HEIGHT_IN * rows + top + bottom
        self.fig = Figure(figsize=(fig_w, self.fig_h))
        grid = self.fig.subplots(rows, self.COLUMNS, squeeze=False)
        for ax in grid.flat[len(names):]:
            ax.set_visible(False)
        self.axes = dict(zip(names, grid.flat))
        self.panels = {}

    def panel(self, name, heading, ylabel):
        """Titles panel `name`; its x axis is time in ms."""
        ax = self.axes[name]
        ax.set_title(heading, fontsize=11)
        ax.set_ylabel(ylabel)
        ax.set_xlabel("time (ms)")
        self.panels[name] = {"title": heading, "ylabel": ylabel, "lines": []}

    def line(self, name, x, y, label, **style):
        """A labelled curve on panel `name`."""
        self.axes[name].plot(x, y, label=label, **style)
        self.panels[name]["lines"].append(label)

    def described(self):
        return [dict(name=name, **self.panels[name]) for name in self.names]


def history_bodies(h):
    """The history's rigid bodies (BODY.x and BODY.theta, in space BODY.qw),
    elastic bodies (BODY.xmin...) and probes (probe.NAME.x), by name."""
    rigid = [c[:-2] for c in h if c.endswith(".x")
             and (c[:-2] + ".theta" in h or c[:-2] + ".qw" in h)]
    elastic = [c[:-5] for c in h if c.endswith(".xmin")]
    probes = [c[6:-2] for c in h if c.startswith("probe.") and c.endswith(".x")]
    return rigid, elastic, probes


def in_space(h):
    """Whether the history is of a run in space (its momenta are vectors)."""
    return "momentum_z" in h


def history_panel_names(rigid, elastic, probes, space=False, moves=True):
    """The panels in page order: each only where the history has its columns
    (in space the rigid bodies' spins and the z extents too, and their
    displacement only where one moves)."""
    names = ["rigid"] if rigid and (not space or moves) else []
    if rigid and space:
        names += ["spin"]
    if elastic or probes:
        names += ["x", "y", "z"] if space else ["x", "y"]
    return names + ["energy", "balance", "speed"]


def draw_rigid(hf, t, h, rigid, marker, reference):
    """The rigid bodies' displacement (y and z only where they move), and
    the reference curve over it."""
    hf.panel("rigid", "rigid bodies: displacement", "displacement (mm)")
    for b in rigid:
        hf.line("rigid", t, h[b + ".x"] * 1e3, f"{b}: x", linewidth=1.6, **marker)
        for axis in ("y", "z"):
            if b + "." + axis in h and np.any(np.abs(h[b + "." + axis]) > 1e-9):
                hf.line("rigid", t, h[b + "." + axis] * 1e3, f"{b}: {axis}", linewidth=1.2,
                        **marker)
    if reference is not None:
        path, (rt, rx) = reference
        hf.line("rigid", rt * 1e3, rx * 1e3, f"reference: {os.path.basename(path)}",
                color="black", linestyle="--", linewidth=1.2,
                **({"marker": "x", "markersize": 4} if rt.size <= 60 else {}))
        hf.panels["rigid"]["reference"] = {"file": os.path.abspath(path), "points": int(rt.size)}


def body_axes_rates(h, b):
    """A rigid body's angular velocity in its own axes as they were at the
    start, R^-1 omega with R its rotation from the start (BODY.qw...), as
    three arrays."""
    w = np.stack([h[f"{b}.omega_{a}"] for a in "xyz"], axis=1)
    u = -np.stack([h[f"{b}.q{a}"] for a in "xyz"], axis=1)  # the inverse turn
    uw = np.cross(u, w)
    turned = w + 2.0 * h[f"{b}.qw"][:, None] * uw + 2.0 * np.cross(u, uw)
    return turned[:, 0], turned[:, 1], turned[:, 2]


def draw_spins(hf, t, h, rigid, marker):
    """In space: each rigid body's angular velocity in its own axes (a body
    tumbling about its intermediate axis shows each flip as that
    component's change of sign)."""
    hf.panel("spin", "rigid bodies: angular velocity in the body's axes",
             "angular velocity (rad/s)")
    for b in rigid:
        for axis, rate, style in zip("xyz", body_axes_rates(h, b), ("-", "--", ":")):
            hf.line("spin", t, rate, f"{b}: about its {axis} axis", linewidth=1.4, linestyle=style,
                    **marker)


def draw_extents(hf, t, h, elastic, probes, marker):
    """Per axis, each elastic body's extent (a band between min and max) and
    the probes."""
    cycle = matplotlib.rcParams["axes.prop_cycle"].by_key()["color"]
    for axis in ("x", "y", "z") if in_space(h) else ("x", "y"):
        hf.panel(axis, f"elastic bodies: {axis} extent"
                 + (" and probes" if probes else " (particle centres)"), f"{axis} (mm)")
        for k, b in enumerate(elastic):
            lo, hi = h[f"{b}.{axis}min"] * 1e3, h[f"{b}.{axis}max"] * 1e3
            colour = cycle[k % len(cycle)]
            hf.axes[axis].fill_between(t, lo, hi, color=colour, alpha=0.12, linewidth=0)
            hf.line(axis, t, hi, f"{b}: {axis} max", color=colour, linewidth=1.5, **marker)
            hf.line(axis, t, lo, f"{b}: {axis} min", color=colour, linewidth=1.5,
                    linestyle="-.", **marker)
        for p in probes:
            hf.line(axis, t, h[f"probe.{p}.{axis}"] * 1e3, f"probe {p}", linewidth=1.1,
                    linestyle=":", **marker)


def draw_energies(hf, t, h):
    """External work, kinetic and strain energy, and their sum."""
    ke, pe, w = h["kinetic_energy"], h["strain_energy"], h["external_work"]
    hf.panel("energy", "energies", "energy (J)" if in_space(h) else "energy (J per m of depth)")
    hf.line("energy", t, w, "external work W", color="black", linewidth=1.6)
    hf.line("energy", t, ke, "kinetic KE", color="#d1495b", linewidth=1.4)
    hf.line("energy", t, pe, "strain PE", color="#2a6fb0", linewidth=1.4)
    hf.line("energy", t, ke + pe, "KE + PE", color="#7b4fa6", linewidth=1.0, linestyle="--")


def draw_balance(hf, t, h, marker):
    """The energy-balance error (KE + PE - W - E0) / max W in % (max(KE +
    PE) where no work is done), the numbers behind it as a legend entry."""
    ke, pe, w = h["kinetic_energy"], h["strain_energy"], h["external_work"]
    e0 = ke[0] + pe[0]
    w_max = float(np.max(np.abs(w)))
    reference_energy = w_max if w_max > 0 else float(np.max(np.abs(ke + pe)))
    by = "max W" if w_max > 0 else "max(KE + PE)"
    error = (ke + pe - w - e0) / (reference_energy if reference_energy > 0 else 1.0) * 100.0
    hf.panel("balance", "energy balance error", f"(KE + PE − W − E0) / {by} (%)")
    hf.line("balance", t, error, f"(KE + PE − W − E0) / {by}", color="black", linewidth=1.4,
            **marker)
    ax = hf.axes["balance"]
    ax.axhline(0.0, color="#999999", linewidth=0.8)
    final = float(error[-1])
    # The numbers behind it as a legend entry of its own (the legend finds a free corner).
    ax.plot([], [], linestyle="none",
            label=f"E0 = {number(e0)} J, {by} = {number(reference_energy)} J\n"
                  f"at t = {ms(h['t'][-1])}: {number(final)} %")
    hf.panels["balance"].update({"E0": float(e0), "normalised_by": by,
                                 "scale": reference_energy, "final_percent": final,
                                 "max_abs_percent": float(np.max(np.abs(error)))})


def draw_speed(hf, t, h, marker):
    """The fastest particle's speed (where the history has it)."""
    hf.panel("speed", "fastest particle", "max speed (m/s)")
    if "max_speed" in h:
        hf.line("speed", t, h["max_speed"], "max |v|", color="#3a9a5b", linewidth=1.4,
                **marker)


def finish_time_panels(hf, t, blowup):
    """Grid, ticks, the time range and legends of every panel; after a
    blow-up, its time as a line a little inside the right edge, what follows
    shaded."""
    for name, ax in hf.axes.items():
        ax.grid(True, linewidth=0.4, alpha=0.6)
        ax.tick_params(labelsize=9)
        if blowup:
            tb = blowup["time"] * 1e3
            right = max(t.max(), tb) + 0.04 * (max(t.max(), tb) - t.min())
            ax.set_xlim(t.min(), right)
            ax.axvspan(tb, right, color=BLOWUP_COLOUR, alpha=0.07, linewidth=0)
            ax.axvline(tb, color=BLOWUP_COLOUR, linestyle="--", linewidth=1.3,
                       label=f"blow-up, t = {ms(blowup['time'])}")
            hf.panels[name]["blowup_marker"] = {"time": blowup["time"],
                                                "criterion": blowup["criterion"]}
        else:
            ax.set_xlim(t.min(), t.max())
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8.5, loc="best", framealpha=0.85)


def annotate_criterion(ax, blowup):
    """The blow-up's criterion written beside its line (on the balance panel)."""
    ax.annotate(
        "\n".join(["blow-up criterion:"] + [
            piece for part in blowup["criterion"].replace(" (", "\n(", 1).split("\n")
            for piece in textwrap.wrap(part, 40)]),
        xy=(blowup["time"] * 1e3, 1.0), xycoords=("data", "axes fraction"),
        xytext=(-6, -40), textcoords="offset points", ha="right", va="top", fontsize=8,
        color=BLOWUP_COLOUR,
        bbox=dict(facecolor="white", edgecolor=BLOWUP_COLOUR, alpha=0.9, linewidth=0.6))


def plot_history(folder, h, dpi, title, blowup, footnote, reference):
    """Writes FOLDER/history.png: displacement, extents and probes, energies,
    the energy balance and the fastest speed against time; returns what was
    drawn. `reference` is (path, (t, x)) or None."""
    t = h["t"] * 1e3
    marker = {"marker": "o", "markersize": 2.5} if t.size <= 60 else {}
    rigid, elastic, probes = history_bodies(h)
    if reference is not None and not rigid:
        raise PlotError("--reference: this run has no rigid body to compare its "
                        "displacement with")
    fig_w = FIGURE_WIDTH_IN
    heading, top = header_lines(fig_w, title, f"history: {t.size} rows to t = {ms(h['t'][-1])}",
                                blowup_words(blowup) if blowup else None)
    notes = wrap_to(footnote, fig_w - 0.2, 7)
    bottom = 0.12 + 0.12 * len(notes)
    moves = reference is not None or any(np.any(np.abs(h[f"{b}.{axis}"]) > 1e-9) for b in rigid for axis in "xyz"
                if f"{b}.{axis}" in h)
    hf = HistoryFigure(history_panel_names(rigid, elastic, probes, in_space(h), moves), fig_w,
                       top, bottom)

    if "rigid" in hf.axes:
        draw_rigid(hf, t, h, rigid, marker, reference)
    if "spin" in hf.axes:
        draw_spins(hf, t, h, rigid, marker)
    if "x" in hf.axes:
        draw_extents(hf, t, h, elastic, probes, marker)
    draw_energies(hf, t, h)
    draw_balance(hf, t, h, marker)
    draw_speed(hf, t, h, marker)
    finish_time_panels(hf, t, blowup)
    if blowup:
        annotate_criterion(hf.axes["balance"], blowup)

    draw_header(hf.fig, hf.fig_h, heading, notes)
    hf.fig.tight_layout(rect=(0, bottom / hf.fig_h, 1, 1 - top / hf.fig_h), h_pad=1.6,
                        w_pad=1.5)
    out = os.path.join(folder, "history.png")
    save_png(hf.fig, out, dpi)
    return {"file": out, "size_px": png_size(out), "title": title, "footnote": footnote,
            "panels": hf.described(),
            "reference": hf.panels.get("rigid", {}).get("reference"),
            "blowup": None if not blowup else {"time": blowup["time"],
                                               "criterion": blowup["criterion"]}}


# ---------------------------------------------------------------- both


def plot_run(folder, color="pressure", frames=12, dpi=150, reference=None, section=None):
    """Writes FOLDER/frames.png and FOLDER/history.png of a run folder:
    `color` pressure, strain or body; at most `frames` frames; `reference` a
    CSV file of t, x (s, m) drawn over the rigid-body displacement; in space
    `section` a z (m), or "x=X", "y=Y" or "z=Z": the layer of particles on
    that plane at the start instead of all of them seen along z. Returns
    what was drawn, {"frames": ...,
    "history": ...}; raises PlotError."""
    check_folder(folder)
    curve = (reference, read_reference(reference)) if reference else None
    history = history_to_draw(folder)
    chosen, body_names, l0, total = read_frames(folder, frames, COLOUR_FIELDS.get(color))
    if section is not None:
        chosen, section = cut_to_section(chosen, section, l0)
    case = run_data.read_case(folder, default={})
    title, blowup, footnote = describe_run(folder, run_data.read_info(folder, default={}), case)
    return {"frames": plot_frames(folder, chosen, body_names, l0, total, color, dpi, title,
                                  blowup, footnote, case, section),
            "history": plot_history(folder, history, dpi, title, blowup, footnote, curve)}
