"""A study's report: each point's measures from its run folder (read through
run_data), the Richardson estimates over l0 (analysis.richardson), the
errors against them or a stated reference, and what is written: study.csv,
richardson.csv, study.md and study.png."""
import csv
import math
import os
import shlex
import sys

from . import analysis, run_data
from .study_grid import StudyError, measure_names


def measure(history, kind, column):
    """(value, time) of one measure of a history (time None for final)."""
    if column not in history.dtype.names:
        raise StudyError(f"--measure {kind}:{column}: history.csv has no column '{column}' "
                         f"(it has {', '.join(history.dtype.names)})")
    t, x = list(history["t"]), list(history[column])
    if not x:
        raise ValueError("empty history")
    if kind == "first_peak":
        return analysis.first_peak(t, x)
    if kind in ("max", "min"):
        return analysis.extreme(t, x, kind == "max")
    return x[-1], None


def point_row(point, folder, measures):
    """A point's row of study.csv: its values, run.json's outcome and costs,
    and its measures (a measure the run did not reach is left empty, with a
    note)."""
    row = {k: v for k, v in point}
    row["folder"] = os.path.basename(folder)
    info = run_data.read_info(folder, default=None)
    if info is None:
        row["outcome"] = "not run"
        return row
    row["outcome"] = info.get("outcome", "")
    for key in ("final_step", "simulated_time", "particles", "threads", "wall_seconds", "steps_per_second"):
        row[key] = info.get(key, "")
    # A resumed run's wall time is the sum of its segments'.
    segments = info.get("segments") or []
    if segments:
        row["wall_seconds"] = sum(s.get("wall_seconds", 0.0) for s in segments) or row["wall_seconds"]
    history = run_data.read_history(os.path.join(folder, run_data.HISTORY_CSV))
    for kind, column in measures:
        try:
            value, when = measure(history, kind, column)
        except ValueError as e:
            row[f"{kind}({column})"] = ""
            row.setdefault("note", str(e))
            continue
        row[f"{kind}({column})"] = value
        if kind != "final":
            row[f"{kind}({column}).t"] = when
    return row


def richardson_rows(rows, vary, measures):
    """Per group of points differing only in l0 (3 or more, a constant
    ratio), per measure: observed order and extrapolated value. Adds
    error(...) to the group's rows."""
    keys = [k for k, _ in vary]
    if "l0" not in keys:
        return []
    others = [k for k in keys if k != "l0"]
    groups = {}
    for row in rows:
        groups.setdefault(tuple(row[k] for k in others), []).append(row)
    out = []
    for group_key, members in groups.items():
        members = sorted(members, key=lambda r: -float(r["l0"]))
        spacings = [float(r["l0"]) for r in members]
        if len(members) < 3:
            continue
        ratios = [a / b for a, b in zip(spacings, spacings[1:])]
        if max(ratios) - min(ratios) > 1e-6 * max(ratios):
            print(f"mpsolid study: no Richardson estimate for {dict(zip(others, group_key))}: "
                  f"l0 ratios differ ({', '.join(f'{r:g}' for r in ratios)})", file=sys.stderr)
            continue
        for name in measure_names(measures):
            values = [r.get(name, "") for r in members]
            if any(v in ("", None) for v in values):
                continue
            est = analysis.richardson([float(v) for v in values], ratio=ratios[0])
            out.append({**dict(zip(others, group_key)), "measure": name, "points": len(values),
                        "l0": ";".join(r["l0"] for r in members), "observed_order": est["order"],
                        "extrapolated": est["value"], "error_bar": est["error"]})
            for r in members:
                if est["value"] != 0 and math.isfinite(est["value"]):
                    r[f"error({name})"] = abs(float(r[name]) / est["value"] - 1)
    return out


def reference_errors(rows, references):
    """Each row's error against a stated reference, which replaces the
    Richardson estimate as what errors are against."""
    for row in rows:
        for _, name, ref in references:
            if row.get(name, "") != "":
                row[f"error({name})"] = abs(float(row[name]) / ref - 1)


def estimate_lines(estimates, vary):
    """One line per Richardson estimate, for the study's log."""
    lines = []
    for e in estimates:
        group = ", ".join(f"{k}={e[k]}" for k, _ in vary if k != "l0")
        where = f"{e['measure']}" + (f" ({group})" if group else "")
        if math.isfinite(e["observed_order"]):
            lines.append(f"mpsolid study: {where}: observed order {e['observed_order']:.2f}, "
                         f"extrapolated {e['extrapolated']:.6g} ± {e['error_bar']:.2g}")
        else:
            lines.append(f"mpsolid study: {where}: no observed order (the changes do not shrink "
                         f"steadily): finest {e['extrapolated']:.6g} ± {e['error_bar']:.2g} (the last change)")
    return lines


def write_csv(path, rows, first):
    """rows as CSV, the `first` columns first, floats at full precision."""
    columns = list(first)
    for row in rows:
        columns += [k for k in row if k not in columns]
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for row in rows:
            w.writerow({k: (repr(v) if isinstance(v, float) else v) for k, v in row.items()})
    os.replace(tmp, path)


def _cell(value, digits=6):
    if isinstance(value, float) or _is_number(str(value)):
        return f"{float(value):.{digits}g}"
    return str(value) if value is not None else ""


def _is_number(text):
    try:
        float(text)
        return True
    except (TypeError, ValueError):
        return False


def equivalent_command(case_path, vary, sets, measures, references, jobs, threads, out):
    """The `mpsolid study` command line that runs this study."""
    words = ["mpsolid", "study", os.path.relpath(case_path)]
    for k, vs in vary:
        words += ["--vary", f"{k}={','.join(vs)}"]
    for o in sets:
        words += ["--set", o]
    for kind, column in measures:
        words += ["--measure", f"{kind}:{column}"]
    for option, _, value in references:
        words += ["--reference", f"{option}={value!r}"]
    words += ["--jobs", str(jobs), "--threads", str(threads), "--out", os.path.relpath(out)]
    return shlex.join(words)


def write_markdown(path, rows, vary, measures, estimates, command):
    """study.md: the command, the points and the Richardson estimates as
    Markdown tables (what a doc quotes)."""
    keys = [k for k, _ in vary]
    names = measure_names(measures)
    lines = ["Made by:", "", "```sh", command, "```", ""]
    head = keys + ["outcome", "particles", "steps", "wall (s)", "steps/s"]
    for n in names:
        head.append(n)
        if any(f"error({n})" in r for r in rows):
            head.append(f"error({n}) %")
    lines += ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    for r in rows:
        outcome = r.get("outcome", "")
        if outcome not in ("completed", "not run") and r.get("simulated_time", "") != "":
            outcome += f" at {float(r['simulated_time']) * 1e3:.3g} ms"
        cells = [str(r[k]) for k in keys] + [outcome, _cell(r.get("particles", "")),
                                             _cell(r.get("final_step", "")),
                                             _cell(r.get("wall_seconds", ""), 3),
                                             _cell(r.get("steps_per_second", ""), 4)]
        for n in names:
            cells.append(_cell(r.get(n, "")))
            if f"error({n}) %" in head:
                e = r.get(f"error({n})", "")
                cells.append(f"{100 * float(e):.3g}" if e != "" else "")
        lines.append("| " + " | ".join(cells) + " |")
    if estimates:
        others = [k for k in keys if k != "l0"]
        head = others + ["measure", "l0", "observed order", "extrapolated", "error bar"]
        lines += ["", "| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
        for e in estimates:
            lines.append("| " + " | ".join([str(e[k]) for k in others]
                                           + [e["measure"], e["l0"].replace(";", ", "),
                                              _cell(e["observed_order"], 3), _cell(e["extrapolated"], 7),
                                              _cell(e["error_bar"], 2)]) + " |")
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, path)


def plot(path, rows, vary, measures, estimates, title):
    """study.png: one panel per measure (value against the first numeric
    varied key, a line per group, Richardson bands), and the wall time."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    keys = [k for k, _ in vary]
    axis_key = next((k for k in keys if all(_is_number(r[k]) for r in rows)), keys[0])
    others = [k for k in keys if k != axis_key]
    names = [n for n in measure_names(measures) if not n.endswith(".t")] + ["wall_seconds"]
    fig, axes = plt.subplots(1, len(names), figsize=(5.2 * len(names), 4.2), squeeze=False)
    groups = {}
    for row in rows:
        groups.setdefault(tuple(row[k] for k in others), []).append(row)
    numeric = _is_number(rows[0][axis_key])
    for ax, name in zip(axes[0], names):
        for gkey, members in groups.items():
            pts = [(r[axis_key], r.get(name)) for r in members if r.get(name) not in (None, "")]
            if not pts:
                continue
            xs = [float(x) if numeric else x for x, _ in pts]
            label = ", ".join(f"{k}={v}" for k, v in zip(others, gkey)) or None
            line, = ax.plot(xs, [float(y) for _, y in pts], "o-", label=label)
            for est in estimates:
                if est["measure"] == name and tuple(est.get(k) for k in others) == gkey:
                    v, e = est["extrapolated"], est["error_bar"]
                    ax.axhspan(v - e, v + e, color=line.get_color(), alpha=0.15)
                    ax.axhline(v, color=line.get_color(), ls="--", lw=0.8)
        if numeric:
            ax.set_xscale("log")
        if name == "wall_seconds":
            ax.set_yscale("log")
        ax.set_xlabel(axis_key)
        ax.set_title(name)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=100)
    plt.close(fig)
    os.replace(tmp, path)


def write_report(out, rows, vary, measures, estimates, command, plot_title, log):
    """study.csv, richardson.csv (with the estimates logged), study.md and,
    with a `plot_title`, study.png in the study folder `out`."""
    write_csv(os.path.join(out, "study.csv"), rows, [k for k, _ in vary] + ["outcome"])
    if estimates:
        write_csv(os.path.join(out, "richardson.csv"), estimates, [k for k, _ in vary if k != "l0"])
        for line in estimate_lines(estimates, vary):
            log(line)
    write_markdown(os.path.join(out, "study.md"), rows, vary, measures, estimates, command)
    if plot_title:
        plot(os.path.join(out, "study.png"), rows, vary, measures, estimates, plot_title)
