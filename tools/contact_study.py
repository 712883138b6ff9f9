#!/usr/bin/python3
"""Contact on against contact off over several mpsolid runs: a table of the
rigid body's displacement and a grid of particle pictures.

    tools/contact_study.py --run LABEL=DIR [--run LABEL=DIR ...]
                           [--pair CONTACT_LABEL:NOCONTACT_LABEL ...]
                           [--out-md FILE.md] [--out-png FILE.png]
                           [--body plate] [--times-ms 1,2,...,10] [--dpi D]

The table (printed, and written to --out-md) has one row per run: the rigid
body's displacement (history column BODY.x, in mm) interpolated at each of
--times-ms (default every millisecond from 1 to 10; a time past the run's
end gives an empty cell); the first peak (analysis.first_peak); the later
peaks, every local maximum and minimum after it whose prominence is at
least 2 % of the first peak's value, each refined by the same three-sample
parabola; the energy-balance error max |KE + PE + CE - W - E0| / max |W| in
% (CE the contact energy, 0 without a contact_energy column; E0 = KE + PE +
CE at the first row); and, for a run with contact, the smallest
contact_min_distance (mm). A second table gives the differences between
consecutive runs, in the order given, with the same contact setting (both
with a contact_energy column or both without): a resolution series, the
later run minus the earlier. A list of the runs (folder, case, l0, contact,
outcome) follows.

--out-png: one row per time of --times-ms and two columns per --pair
(contact on | off; one column per run when no --pair is given). Each panel
shows the particles of the frame nearest that time, coloured by body as
tools/plot.py --color body does, the elastic bodies drawn over the walls
and rigid bodies so that interpenetration shows; in mm at equal aspect, one
scale for all panels, x down the page; titled with the label and the time
(and the time asked for, where the nearest frame is elsewhere). About 2200
px wide at the default --dpi 150 with 2 or 3 pairs (a panel is at most 3.2
inches, so one pair gives a narrower picture), as tall as the rows need.

Reads the runs with mpsolid.run_data and measures with mpsolid.analysis;
draws with mpsolid.plot's colours and PNG writer (all three from the source
tree's python/mpsolid: no build needed). A run still in progress (no
run.json yet) is read as far as it got. Needs numpy, h5py and matplotlib
(Debian's /usr/bin/python3). Exit codes: 0 done; 2 a bad argument, a missing
folder, history.csv, frames.h5 or column; 1 results that cannot be read.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from source_package import mpsolid_module, require_libraries  # noqa: E402

PROMINENCE_SHARE = 0.02      # later peaks: prominence at least 2 % of the first peak
MIN_FIGURE_WIDTH_IN = 9.0
MAX_PANEL_IN = 3.2          # a panel's larger side: with one pair, 10 rows stay ~5000 px tall
DEFAULT_TIMES_MS = "1,2,3,4,5,6,7,8,9,10"

analysis = mpsolid_module("analysis")
# Set by main() once require_libraries() has checked numpy, h5py and matplotlib.
np = run_data = plot = None


def fail(message, code=2):
    print(f"contact_study.py: {message}", file=sys.stderr)
    sys.exit(code)


# ---------------------------------------------------------------- arguments


def parse_args():
    parser = argparse.ArgumentParser(
        description="Contact on against contact off: a displacement table and particle pictures.")
    parser.add_argument("--run", action="append", required=True, metavar="LABEL=DIR",
                        help="a run folder and its label (repeat; the order matters for the "
                             "differences table)")
    parser.add_argument("--pair", action="append", default=[],
                        metavar="CONTACT_LABEL:NOCONTACT_LABEL",
                        help="two runs side by side in --out-png (repeat, up to 3 is readable)")
    parser.add_argument("--out-md", metavar="FILE.md", help="write the tables here too")
    parser.add_argument("--out-png", metavar="FILE.png", help="write the particle pictures here")
    parser.add_argument("--body", default="plate",
                        help="the rigid body whose displacement BODY.x is measured (default plate)")
    parser.add_argument("--times-ms", default=DEFAULT_TIMES_MS, metavar="T1,T2,...",
                        help="the times in ms of the table's columns and the picture's rows "
                             f"(default {DEFAULT_TIMES_MS})")
    parser.add_argument("--dpi", type=int, default=150,
                        help="resolution of --out-png (default 150: about 2200 px wide)")
    return parser.parse_args()


def parse_runs(items):
    """[(label, folder)] from LABEL=DIR items, labels unique."""
    runs = []
    for item in items:
        label, sep, folder = item.partition("=")
        if not sep or not label or not folder:
            fail(f"--run {item}: expected LABEL=DIR")
        if label in (l for l, _ in runs):
            fail(f"--run {item}: the label {label} is given twice")
        runs.append((label, folder))
    return runs


def parse_pairs(items, labels):
    pairs = []
    for item in items:
        on, sep, off = item.partition(":")
        if not sep or not on or not off:
            fail(f"--pair {item}: expected CONTACT_LABEL:NOCONTACT_LABEL")
        for label in (on, off):
            if label not in labels:
                fail(f"--pair {item}: no --run is labelled {label} (labels: {', '.join(labels)})")
        pairs.append((on, off))
    return pairs


def parse_times(text):
    try:
        times = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        fail(f"--times-ms {text}: expected numbers in ms separated by commas")
    if not times or any(not math.isfinite(t) or t < 0 for t in times):
        fail(f"--times-ms {text}: expected one or more times >= 0 in ms")
    return times


# ---------------------------------------------------------------- reading


def check_folder(folder, need_frames):
    if not os.path.isdir(folder):
        fail(f"{folder}: no such folder")
    wanted = [run_data.HISTORY_CSV] + ([run_data.FRAMES_H5] if need_frames else [])
    missing = [f for f in wanted if not os.path.isfile(os.path.join(folder, f))]
    if missing:
        fail(f"{folder} has no {' and '.join(missing)}: not an mpsolid run folder, or the run "
             f"has not written it yet")


def history_with_body(folder, body):
    """history.csv as {column: array}: at least one row, the energies
    (mpsolid.plot.history_to_draw) and BODY.x."""
    try:
        h = plot.history_to_draw(folder)
    except plot.PlotError as e:
        fail(str(e), e.code)
    if f"{body}.x" not in h:
        rigid = sorted(plot.history_bodies(h)[0])
        fail(f"{os.path.join(folder, run_data.HISTORY_CSV)} has no column {body}.x (rigid bodies: "
             f"{', '.join(rigid) or 'none'}); choose one with --body")
    return h


def read_frames(folder):
    path = os.path.join(folder, run_data.FRAMES_H5)
    try:
        frames = run_data.Frames(path)
    except (OSError, KeyError) as e:
        fail(f"{path} cannot be read as mpsolid frames ({e})", 1)
    if len(frames) == 0:
        fail(f"{path} holds no frames", 1)
    return frames


# ---------------------------------------------------------------- measures


def displacement_at(t, x, times):
    """x interpolated at each time; None past the ends of t."""
    return [float(np.interp(s, t, x)) if t[0] <= s <= t[-1] else None for s in times]


def prominence(x, k):
    """The topographic prominence of the local maximum x[k]: its height above
    the higher of the lowest points on either side before a higher sample
    (or the end of the series)."""
    bases = []
    for step in (-1, 1):
        j, lowest = k + step, x[k]
        while 0 <= j < len(x) and x[j] <= x[k]:
            lowest = min(lowest, x[j])
            j += step
        bases.append(lowest)
    return x[k] - max(bases)


def refine(t, x, k, sign):
    """(time, value) of the extremum at sample k (sign +1 a maximum, -1 a
    minimum) through analysis.first_peak's parabola on the samples k-1..k+1
    (shifted to be positive, which the parabola does not see)."""
    window = [sign * v for v in x[k - 1:k + 2]]
    base = min(window) - 1.0
    value, time = analysis.first_peak(t[k - 1:k + 2], [v - base for v in window])
    return time, sign * (value + base)


def later_peaks(t, x, first_time, first_value):
    """[(time, value)] of the local maxima and minima after the first peak's
    sample whose prominence is at least PROMINENCE_SHARE of its value."""
    threshold = PROMINENCE_SHARE * abs(first_value)
    start = int(np.argmin(np.abs(t - first_time))) + 1
    peaks = []
    for k in range(max(start, 1), len(x) - 1):
        for sign in (1, -1):
            a, b, c = sign * x[k - 1], sign * x[k], sign * x[k + 1]
            if b > a and b >= c and prominence(sign * x, k) >= threshold:
                peaks.append(refine(t, x, k, sign))
    return peaks


def balance_error(h):
    """max |KE + PE + CE - W - E0| / max |W| in %."""
    ce = h.get("contact_energy", np.zeros_like(h["t"]))
    total = h["kinetic_energy"] + h["strain_energy"] + ce
    w = h["external_work"]
    scale = float(np.max(np.abs(w))) or float(np.max(np.abs(total))) or 1.0
    return float(np.max(np.abs(total - w - total[0]))) / scale * 100.0


def measure_run(label, folder, h, body, times_ms):
    """Everything the tables show of one run (SI units)."""
    t, x = h["t"], h[f"{body}.x"]
    measure = {"label": label, "folder": folder, "contact": "contact_energy" in h,
               "end": float(t[-1]), "at": displacement_at(t, x, [s * 1e-3 for s in times_ms]),
               "first_peak": None, "later_peaks": [], "balance_percent": balance_error(h),
               "min_distance": None}
    try:
        value, time = analysis.first_peak(t, x)
        measure["first_peak"] = (time, value)
        measure["later_peaks"] = later_peaks(t, x, time, value)
    except ValueError:
        pass
    if "contact_min_distance" in h:
        measure["min_distance"] = float(np.min(h["contact_min_distance"]))
    return measure


def describe(label, folder, h):
    """One line on a run: folder, case, l0, contact, outcome."""
    run, case = run_data.read_info(folder, default={}), run_data.read_case(folder, default={})
    parts = [case.get("name") or run.get("case") or "case unknown"]
    if "l0" in case:
        parts.append(f"l0 = {plot.number(float(case['l0']) * 1e3)} mm")
    parts.append("contact on" if "contact_energy" in h else "contact off")
    outcome = run.get("outcome") or "in progress (no run.json)"
    parts.append(f"{outcome} to t = {plot.number(float(h['t'][-1]) * 1e3, 4)} ms")
    return f"- {label}: {os.path.abspath(folder)} ({', '.join(parts)})"


# ---------------------------------------------------------------- tables


def mm(v, digits=3):
    return "" if v is None else f"{v * 1e3:.{digits}f}"


def row(cells):
    return "| " + " | ".join(cells) + " |"


def results_table(measures, times_ms, body):
    head = (["run"] + [f"x({plot.number(s, 4)} ms)" for s in times_ms]
            + ["first peak t (ms)", "first peak x (mm)", "later peaks",
               "balance error (%)", "min contact distance (mm)"])
    lines = [f"## {body}.x, displacement (mm)", "", row(head), row(["---"] * len(head))]
    for m in measures:
        peak = m["first_peak"]
        later = "; ".join(f"{t * 1e3:.2f} ms: {v * 1e3:.3f} mm" for t, v in m["later_peaks"])
        lines.append(row([m["label"]] + [mm(v) for v in m["at"]]
                         + ([f"{peak[0] * 1e3:.3f}", mm(peak[1])] if peak else ["", ""])
                         + [later or ("" if peak else "no first peak"),
                            f"{m['balance_percent']:.3g}",
                            mm(m["min_distance"]) if m["contact"] else "no contact"]))
    return lines


def consecutive_pairs(measures):
    """Consecutive runs, in the order given, among those with the same contact setting."""
    pairs = []
    for contact in (True, False):
        group = [m for m in measures if m["contact"] == contact]
        pairs += list(zip(group, group[1:]))
    return pairs


def difference(a, b):
    return None if a is None or b is None else b - a


def differences_table(measures, times_ms, body):
    lines = ["## differences between resolutions (later run minus earlier, mm)", ""]
    pairs = consecutive_pairs(measures)
    if not pairs:
        return lines + ["No two runs with the same contact setting."]
    head = (["runs", "contact"] + [f"Δx({plot.number(s, 4)} ms)" for s in times_ms]
            + ["Δ first peak x"])
    lines += [row(head), row(["---"] * len(head))]
    for a, b in pairs:
        peak = difference(a["first_peak"] and a["first_peak"][1],
                          b["first_peak"] and b["first_peak"][1])
        lines.append(row([f"{b['label']} − {a['label']}", "on" if a["contact"] else "off"]
                         + [mm(difference(va, vb)) for va, vb in zip(a["at"], b["at"])]
                         + [mm(peak)]))
    return lines


def report(measures, descriptions, times_ms, body):
    notes = [f"Later peaks: local extrema after the first peak with a prominence of at least "
             f"{PROMINENCE_SHARE * 100:g} % of its value. Balance error: "
             f"max |KE + PE + CE − W − E0| / max |W|. An empty cell: past the run's end."]
    return "\n".join(results_table(measures, times_ms, body) + [""] + notes + [""]
                     + differences_table(measures, times_ms, body) + ["", "## runs", ""]
                     + descriptions) + "\n"


# ---------------------------------------------------------------- pictures


def nearest_frame(frames, t):
    """The frame nearest time t, or None when it is more than half a frame
    interval away (the run ended before t)."""
    times = frames.times
    k = int(np.argmin(np.abs(times - t)))
    interval = float(np.median(np.diff(times))) if times.size > 1 else 0.0
    return frames[k] if abs(times[k] - t) <= 0.5 * interval + 1e-9 else None


def panel_grid(columns, runs, times_ms):
    """[row][column] of {"label", "time", "frame" (or None), "l0", "frames"}."""
    opened = {label: read_frames(runs[label]) for label in dict.fromkeys(columns)}
    grid = []
    for s in times_ms:
        grid.append([{"label": label, "time": s * 1e-3, "frames": opened[label],
                      "frame": nearest_frame(opened[label], s * 1e-3),
                      "l0": float(opened[label].attrs.get("l0", 0.0))}
                     for label in columns])
    return grid


def data_box(grid):
    """(x range, y range) in mm over every panel's particles, padded."""
    points = [p["frame"]["position"] for line in grid for p in line if p["frame"] is not None]
    if not points:
        fail("no frame of any run is near the times of --times-ms")
    every = np.concatenate(points) * 1e3
    every = every[np.all(np.isfinite(every), axis=1)]
    pad = 1.5 * max(p["l0"] for line in grid for p in line) * 1e3
    return ((every[:, 0].min() - pad, every[:, 0].max() + pad),
            (every[:, 1].min() - pad, every[:, 1].max() + pad))


def draw_panel(ax, panel, x_range, y_range, points_per_mm, legend):
    """The particles of one frame, walls and rigid bodies first, elastic on top."""
    from matplotlib.ticker import MaxNLocator
    frame, frames = panel["frame"], panel["frames"]
    plot.frame_axes(ax, y_range, x_range, labelsize=7, ticklength=2.5)
    ax.xaxis.set_major_locator(MaxNLocator(nbins=4))
    title = f"{panel['label']}, t = {plot.ms(panel['time'])}"
    if frame is not None and abs(frame.time - panel["time"]) > 1e-6:
        title = f"{panel['label']}, t = {plot.ms(frame.time)} (asked {plot.ms(panel['time'])})"
    ax.set_title(title, fontsize=9, pad=3)
    if frame is None:
        ax.text(0.5, 0.5, f"no frame\n(run ends at {plot.ms(frames.times[-1])})",
                transform=ax.transAxes, ha="center", va="center", fontsize=8, color="#777777")
        return
    colours, kinds = plot.body_colours([frame], frames.body_names, False)
    size = (0.9 * panel["l0"] * 1e3 * points_per_mm) ** 2
    position, body = frame["position"] * 1e3, frame["body"]
    for b, colour in sorted(colours.items(), key=lambda bc: kinds[bc[0]] == plot.KIND_ELASTIC):
        sel = body == b
        ax.scatter(position[sel, 1], position[sel, 0], s=size, color=colour, linewidths=0,
                   zorder=3 if kinds[b] == plot.KIND_ELASTIC else 2)
        legend.setdefault(f"{frames.body_names[b]} ({plot.KIND_NAMES[kinds[b]]})", colour)


def plot_pictures(out, grid, runs, contact, pairs, dpi):
    from matplotlib.figure import Figure

    x_range, y_range = data_box(grid)
    data_w, data_h = y_range[1] - y_range[0], x_range[1] - x_range[0]
    rows, columns = len(grid), len(grid[0])
    left, right, gap, pair_gap, row_gap = 0.6, 0.2, 0.15, 0.4, 0.34
    gaps = [pair_gap if pairs and c % 2 == 0 else gap for c in range(1, columns)]
    panel_w = (plot.FIGURE_WIDTH_IN - left - right - sum(gaps)) / columns
    panel_w = min(panel_w, MAX_PANEL_IN, MAX_PANEL_IN * data_w / data_h)
    panel_h = panel_w * data_h / data_w
    # Few columns: a narrower figure (room for the title kept), the grid centred.
    fig_w = left + right + sum(gaps) + columns * panel_w
    if fig_w < MIN_FIGURE_WIDTH_IN:
        left += (MIN_FIGURE_WIDTH_IN - fig_w) / 2
        fig_w = MIN_FIGURE_WIDTH_IN
    top, bottom = 0.85, 0.95
    fig_h = top + bottom + rows * panel_h + (rows - 1) * row_gap
    fig = Figure(figsize=(fig_w, fig_h))
    points_per_mm = panel_w * 72.0 / data_w
    legend = {}
    for r, line in enumerate(grid):
        x0 = left
        for c, panel in enumerate(line):
            y0 = fig_h - top - (r + 1) * panel_h - r * row_gap
            ax = fig.add_axes([x0 / fig_w, y0 / fig_h, panel_w / fig_w, panel_h / fig_h])
            draw_panel(ax, panel, x_range, y_range, points_per_mm, legend)
            if r == rows - 1:
                ax.set_xlabel("y (mm)", fontsize=8)
            else:
                ax.tick_params(labelbottom=False)
            if c == 0:
                ax.set_ylabel("x (mm)", fontsize=8)
            else:
                ax.tick_params(labelleft=False)
            x0 += panel_w + (gaps[c] if c < columns - 1 else 0)

    if pairs:
        shown = "; ".join(f"{on} (contact {'on' if contact[on] else 'off'}) | "
                          f"{off} (contact {'on' if contact[off] else 'off'})"
                          for on, off in pairs)
    else:
        shown = ", ".join(f"{p['label']} (contact {'on' if contact[p['label']] else 'off'})"
                          for p in grid[0])
    fig.text(0.5, 1 - 0.15 / fig_h, f"particles, coloured by body: {shown}", ha="center",
             va="top", fontsize=12)
    fig.text(0.5, 1 - 0.42 / fig_h, "the frame nearest each time; elastic bodies drawn over "
             "walls and rigid bodies, so an overlap is interpenetration", ha="center", va="top",
             fontsize=9.5, color="#333333")
    handles = [plot.legend_marker(colour) for colour in legend.values()]
    fig.legend(handles, list(legend), loc="lower center", ncol=max(len(legend), 1),
               frameon=False, fontsize=9.5, bbox_to_anchor=(0.5, 0.2 / fig_h))
    folders = "; ".join(f"{label}: {os.path.abspath(folder)}" for label, folder in runs.items()
                        if label in {p["label"] for p in grid[0]})
    fig.text(0.006, 0.04 / fig_h, folders, ha="left", va="bottom", fontsize=6.5, color="#777777")
    plot.save_png(fig, out, dpi)
    return plot.png_size(out)


# ---------------------------------------------------------------- main


def check_outputs(args):
    if args.dpi < 20:
        fail("--dpi must be at least 20")
    for option, path in (("--out-md", args.out_md), ("--out-png", args.out_png)):
        folder = os.path.dirname(os.path.abspath(path)) if path else None
        if folder and not os.path.isdir(folder):
            fail(f"{option} {path}: no such folder {folder}")


def write_text(path, text):
    try:
        with open(path, "w") as f:
            f.write(text)
    except OSError as e:
        fail(f"--out-md {path}: cannot write it ({e.strerror})")


def main():
    global np, run_data, plot
    args = parse_args()
    require_libraries("tools/contact_study.py")
    import numpy
    np, run_data, plot = numpy, mpsolid_module("run_data"), mpsolid_module("plot")
    runs = dict(parse_runs(args.run))
    pairs = parse_pairs(args.pair, list(runs))
    times_ms = parse_times(args.times_ms)
    check_outputs(args)
    columns = [label for pair in pairs for label in pair] or list(runs)
    for label, folder in runs.items():
        check_folder(folder, need_frames=bool(args.out_png) and label in columns)

    histories = {label: history_with_body(folder, args.body) for label, folder in runs.items()}
    measures = [measure_run(label, runs[label], h, args.body, times_ms)
                for label, h in histories.items()]
    descriptions = [describe(label, runs[label], h) for label, h in histories.items()]
    text = report(measures, descriptions, times_ms, args.body)
    print(text, end="")
    if args.out_md:
        write_text(args.out_md, text)
    if args.out_png:
        grid = panel_grid(columns, runs, times_ms)
        contact = {m["label"]: m["contact"] for m in measures}
        size = plot_pictures(args.out_png, grid, runs, contact, pairs, args.dpi)
        print(f"contact_study.py: wrote {args.out_png} ({size[0]} x {size[1]} px)",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
