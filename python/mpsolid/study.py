"""A study: a grid of runs of one case, one folder per point, then a table.

  mpsolid study CASE --vary l0=0.002,0.001,0.0005 --vary model=paper,finite_strain
                [--set KEY=VALUE]... [--measure first_peak:plate.x]... [--jobs N]
                [--threads T] [--out DIR]

Each point is the command line's run (`mpsolid run CASE --set ...`) in
DIR/<key=value,...>/, at most N at a time with the cores split between them.
The study is resumable: a point whose run completed (or was stopped by a
blow-up check, itself a result) is not run again; one stopped by a signal is
resumed from its checkpoint to the same bits; one that left nothing usable is
run afresh. A study stopped by SIGINT or SIGTERM stops its runs (each writes
its checkpoint) and exits 4; running the same command again continues it.

Then DIR/study.csv (one row per point: the varied values, the outcome, wall
time, steps/s and the measures), DIR/richardson.csv, DIR/study.png and
DIR/study.md (the same tables in Markdown, with the equivalent command). When
l0 is varied over 3 or more values with a constant ratio, each measure of
each group of points that differ only in l0 gets the observed order of
convergence and a Richardson-extrapolated value with an error bar
(analysis.richardson), and every point of the group its error against it.

--reference KIND:COLUMN=VALUE gives a measure a known value (theory, or a
finer study's extrapolation): each point's error is then against it.

Measures (history.csv columns, e.g. plate.x, kinetic_energy, rod.xmax):
  first_peak:COL  the first maximum above half the largest value (parabola-refined) and its time
  max:COL, min:COL  the largest / smallest value and its time
  final:COL       the last value
"""
import argparse
import csv
import json
import math
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import threading
import time

from . import analysis
from .run_data import read_history

MEASURE_KINDS = ("first_peak", "max", "min", "final")
EXIT_BAD_INPUT, EXIT_STOPPED = 2, 4


class StudyError(ValueError):
    """Bad study input (exit 2 on the command line)."""


# ---- the grid ---------------------------------------------------------------

def split_values(text):
    """'a,b,[1,2],"x,y"' -> ['a', 'b', '[1,2]', '"x,y"']: commas inside
    brackets or quotes do not split."""
    values, depth, quote, start = [], 0, None, 0
    for k, ch in enumerate(text):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            values.append(text[start:k].strip())
            start = k + 1
    values.append(text[start:].strip())
    return values


def parse_vary(text):
    """'KEY=V1,V2,...' -> (KEY, [V1, V2, ...]) as TOML texts."""
    key, sep, rest = text.partition("=")
    key = key.strip()
    if not sep or not key or not rest.strip():
        raise StudyError(f"--vary '{text}': expected KEY=VALUE1,VALUE2,... (e.g. l0=0.002,0.001)")
    values = split_values(rest)
    if any(v == "" for v in values):
        raise StudyError(f"--vary '{text}': an empty value")
    if len(set(values)) != len(values):
        raise StudyError(f"--vary '{text}': a value is listed twice")
    return key, values


def parse_measure(text):
    kind, sep, column = text.partition(":")
    if not sep or kind not in MEASURE_KINDS or not column:
        raise StudyError(f"--measure '{text}': expected KIND:COLUMN with KIND one of "
                         f"{', '.join(MEASURE_KINDS)} (e.g. first_peak:plate.x)")
    return kind, column


def parse_reference(text):
    """'first_peak:plate.x=0.0116961' -> ('first_peak:plate.x', 'first_peak(plate.x)', 0.0116961):
    the option's KIND:COLUMN, the measure's name in study.csv, the value;
    'first_peak:plate.x.t=...' names the measure's time."""
    option, sep, value = text.rpartition("=")
    try:
        number = float(value)
    except ValueError:
        number = math.nan
    if not sep or not math.isfinite(number) or number == 0:
        raise StudyError(f"--reference '{text}': expected KIND:COLUMN=VALUE with a finite, nonzero "
                         f"VALUE (e.g. first_peak:plate.x=0.0116961)")
    timed = option.endswith(".t")
    kind, column = parse_measure(option.removesuffix(".t"))
    return option, f"{kind}({column})" + (".t" if timed else ""), number


def toml_text(value):
    """A Python value as the TOML text --set reads (strings pass as given:
    on the command line a bare word is a string)."""
    if isinstance(value, str):
        return value
    from . import toml_value
    return toml_value(value)


def folder_name(point):
    """'l0=0.002,model=paper': readable, unique per point, safe as a name."""
    parts = [f"{k}={v}" for k, v in point]
    name = ",".join(parts)
    return re.sub(r"[^A-Za-z0-9._=,+\-\[\]]", "_", name)


def grid(vary):
    """Every combination of the varied values, the first key slowest."""
    points = [[]]
    for key, values in vary:
        points = [p + [(key, v)] for p in points for v in values]
    return points


# ---- one point --------------------------------------------------------------

def executable():
    """The mpsolid executable: $MPSOLID_EXECUTABLE, else the one this package
    was built or installed with."""
    exe = os.environ.get("MPSOLID_EXECUTABLE")
    if not exe:
        from ._build_paths import MPSOLID_EXECUTABLE as exe
    if not os.access(exe, os.X_OK):
        raise StudyError(f"the mpsolid executable '{exe}' is missing (build it, or set MPSOLID_EXECUTABLE)")
    return exe


def read_run_json(folder):
    try:
        with open(os.path.join(folder, "run.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def point_state(folder, overrides):
    """'done' (completed or stopped by a blow-up check), 'resume' (stopped by
    a signal, checkpoint there), 'fresh' (nothing usable), or raises when the
    folder holds a run of other settings."""
    info = read_run_json(folder)
    if info is None:
        return "fresh"
    if info.get("overrides") != overrides:
        raise StudyError(f"{folder} holds a run with other settings ({info.get('overrides')}); "
                         f"remove it or choose another --out")
    outcome = info.get("outcome", "")
    if outcome in ("completed", "unstable"):
        return "done"
    if os.path.isfile(os.path.join(folder, "checkpoint.h5")):
        return "resume"
    return "fresh"


class PointRunner:
    """Runs points as child processes; stop() asks every running child to
    stop (SIGINT: each writes its checkpoint) and starts no more."""

    def __init__(self, exe, threads, fixed_threads):
        self.exe, self.threads, self.fixed_threads = exe, threads, fixed_threads
        self.children = set()
        self.stopping = False
        self.lock = threading.Lock()

    def run(self, case_path, overrides, folder):
        state = point_state(folder, overrides)
        if state == "done":
            return "skipped"
        if state == "resume":
            cmd = [self.exe, "resume", folder]
        else:
            cmd = [self.exe, "run", case_path, "--out", folder, "--force"]
            for o in overrides:
                cmd += ["--set", o]
        cmd += ["--threads", str(self.threads)] + (["--fixed-threads"] if self.fixed_threads else [])
        os.makedirs(folder, exist_ok=True)
        with self.lock:
            if self.stopping:
                return "not started"
            with open(os.path.join(folder, "mpsolid.log"), "a") as log:
                log.write(f"$ {' '.join(cmd)}\n")
                log.flush()
                # Own process group: a Ctrl-C reaches the study, which stops its runs in order.
                child = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
            self.children.add(child)
        code = child.wait()
        with self.lock:
            self.children.discard(child)
        if code == EXIT_BAD_INPUT:
            with open(os.path.join(folder, "mpsolid.log")) as log:
                raise StudyError(f"{folder}: mpsolid refused the point:\n{log.read()[-2000:]}")
        return {0: "ran", 3: "ran", EXIT_STOPPED: "stopped"}.get(code, f"failed (exit {code})")

    def stop(self):
        with self.lock:
            self.stopping = True
            for child in self.children:
                child.send_signal(signal.SIGINT)


# ---- measures and the table -------------------------------------------------

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


def measure_names(measures):
    names = []
    for kind, column in measures:
        names.append(f"{kind}({column})")
        if kind != "final":
            names.append(f"{kind}({column}).t")
    return names


def point_row(point, folder, measures):
    row = {k: v for k, v in point}
    row["folder"] = os.path.basename(folder)
    info = read_run_json(folder)
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
    history = read_history(os.path.join(folder, "history.csv"))
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


def write_csv(path, rows, first):
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
    """One panel per measure (value against the first numeric varied key, a
    line per group, Richardson bands), and the wall time."""
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


def _is_number(text):
    try:
        float(text)
        return True
    except (TypeError, ValueError):
        return False


# ---- the study --------------------------------------------------------------

class StudyResult:
    """What a study wrote: `rows` (one dict per point, as study.csv),
    `richardson` (one dict per group and measure), `folder`, and the exit
    status (0 all points done, 4 stopped before the end)."""

    def __init__(self, folder, rows, richardson, status):
        self.folder, self.rows, self.richardson, self.status = folder, rows, richardson, status

    def __repr__(self):
        done = sum(r["outcome"] != "not run" for r in self.rows)
        return f"StudyResult('{self.folder}': {done} of {len(self.rows)} points, status {self.status})"


def study(case, vary, measures=(), sets=(), out=None, jobs=1, threads=None, fixed_threads=False,
          plot_png=True, log=print, references=()):
    """Runs the grid `vary` ({key: [values]} or [(key, [values])], values as
    Python values or TOML texts) of `case` (a path, or an mpsolid.Case whose
    overrides apply to every point), `sets` ("key=value" for every point),
    measures as "kind:column". Returns a StudyResult; raises StudyError (a
    ValueError) for bad input before anything runs."""
    case_path, base = _case_and_overrides(case)
    base += list(sets)
    vary = [(k, [toml_text(v) for v in vs]) for k, vs in (vary.items() if isinstance(vary, dict) else vary)]
    if not vary:
        raise StudyError("nothing to vary: give at least one --vary KEY=V1,V2,...")
    if len({k for k, _ in vary}) != len(vary):
        raise StudyError("a key is varied twice")
    measures = [parse_measure(m) if isinstance(m, str) else tuple(m) for m in measures]
    references = [parse_reference(r) for r in references]
    for _, name, _ in references:
        if name not in measure_names(measures):
            raise StudyError(f"--reference for {name}: that is not one of the measures "
                             f"({', '.join(measure_names(measures)) or 'none given'})")
    if jobs < 1:
        raise StudyError(f"--jobs {jobs}: must be at least 1")
    cores = os.cpu_count() or 1
    threads = threads or max(1, cores // jobs)
    points = grid(vary)
    name = os.path.splitext(os.path.basename(case_path))[0]
    out = os.fspath(out) if out else os.path.join("out", f"study_{name}")

    # Every point is checked before anything runs: the command line's messages.
    from . import Case
    for point in points:
        c = Case.load(case_path)
        for o in base + [f"{k}={v}" for k, v in point]:
            key, _, value = o.partition("=")
            c.set_text(key, value)
    exe = executable()

    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "study.json.tmp"), "w") as f:
        json.dump({"case": os.path.abspath(case_path), "sets": base, "vary": vary,
                   "measures": [f"{k}:{c}" for k, c in measures],
                   "references": {name: value for _, name, value in references},
                   "jobs": jobs, "threads": threads,
                   "executable": exe, "package": os.path.dirname(os.path.abspath(__file__))}, f,
                  indent=2)
    os.replace(os.path.join(out, "study.json.tmp"), os.path.join(out, "study.json"))

    runner = PointRunner(exe, threads, fixed_threads)
    results, failures = {}, []
    started = time.monotonic()

    def one(k, point):
        folder = os.path.join(out, folder_name(point))
        overrides = base + [f"{key}={v}" for key, v in point]
        what = runner.run(os.path.abspath(case_path), overrides, folder)
        results[k] = what
        info = read_run_json(folder) or {}
        done = sum(1 for v in results.values() if v != "not started")
        log(f"mpsolid study: [{done}/{len(points)}] {folder_name(point)}: {what}"
            + (f", {info.get('outcome')} at t = {info.get('simulated_time', 0):g} s in "
               f"{info.get('wall_seconds', 0):.1f} s" if what in ("ran", "stopped") else "")
            + f" ({time.monotonic() - started:.0f} s into the study)")

    status = _run_all(points, one, jobs, runner, failures)
    rows = [point_row(p, os.path.join(out, folder_name(p)), measures) for p in points]
    estimates = richardson_rows(rows, vary, measures) if status == 0 else []
    # A stated reference replaces the Richardson estimate as what errors are against.
    for row in rows:
        for _, name, ref in references:
            if row.get(name, "") != "":
                row[f"error({name})"] = abs(float(row[name]) / ref - 1)
    first = [k for k, _ in vary] + ["outcome"]
    write_csv(os.path.join(out, "study.csv"), rows, first)
    if estimates:
        write_csv(os.path.join(out, "richardson.csv"), estimates, [k for k, _ in vary if k != "l0"])
        for e in estimates:
            group = ", ".join(f"{k}={e[k]}" for k, _ in vary if k != "l0")
            where = f"{e['measure']}" + (f" ({group})" if group else "")
            if math.isfinite(e["observed_order"]):
                log(f"mpsolid study: {where}: observed order {e['observed_order']:.2f}, "
                    f"extrapolated {e['extrapolated']:.6g} ± {e['error_bar']:.2g}")
            else:
                log(f"mpsolid study: {where}: no observed order (the changes do not shrink "
                    f"steadily): finest {e['extrapolated']:.6g} ± {e['error_bar']:.2g} (the last change)")
    write_markdown(os.path.join(out, "study.md"), rows, vary, measures, estimates,
                   equivalent_command(case_path, vary, base, measures, references, jobs, threads, out))
    if plot_png and status == 0:
        plot(os.path.join(out, "study.png"), rows, vary, measures, estimates, f"study of {name}")
    if failures:
        raise failures[0]
    return StudyResult(out, rows, estimates, status)


def _case_and_overrides(case):
    if isinstance(case, (str, os.PathLike)):
        return os.fspath(case), []
    return case.path, list(case.overrides)


def _run_all(points, one, jobs, runner, failures):
    """Runs one(k, point) for every point on `jobs` threads. SIGINT or SIGTERM
    stops the runs (checkpoints) and returns 4."""
    from concurrent.futures import ThreadPoolExecutor, wait

    stop = threading.Event()

    def guarded(k, point):
        if stop.is_set():
            return
        try:
            one(k, point)
        except Exception as e:  # noqa: BLE001: the first failure stops the study
            failures.append(e)
            stop.set()
            runner.stop()

    previous = {}

    def on_signal(signum, frame):
        stop.set()
        runner.stop()

    in_main = threading.current_thread() is threading.main_thread()
    if in_main:
        for s in (signal.SIGINT, signal.SIGTERM):
            previous[s] = signal.signal(s, on_signal)
    try:
        with ThreadPoolExecutor(max_workers=jobs) as pool:
            futures = [pool.submit(guarded, k, p) for k, p in enumerate(points)]
            wait(futures)
    finally:
        for s, h in previous.items():
            signal.signal(s, h)
    if failures:
        return EXIT_BAD_INPUT
    return EXIT_STOPPED if stop.is_set() else 0


def main(argv=None):
    p = argparse.ArgumentParser(prog="mpsolid study", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("case", help="case file (TOML)")
    p.add_argument("--vary", action="append", default=[], metavar="KEY=V1,V2,...",
                   help="a case key and its values (repeat for a grid)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="sets",
                   help="a case key for every point")
    p.add_argument("--measure", action="append", default=[], metavar="KIND:COLUMN",
                   help="first_peak|max|min|final : a history.csv column")
    p.add_argument("--reference", action="append", default=[], metavar="KIND:COLUMN=VALUE",
                   help="a measure's reference value: each point's error against it (instead of "
                        "the Richardson estimate); KIND:COLUMN.t=VALUE for its time")
    p.add_argument("--jobs", type=int, default=1, help="points run at the same time (default 1)")
    p.add_argument("--threads", type=int, default=None,
                   help="threads per run (default: the cores divided by --jobs)")
    p.add_argument("--fixed-threads", action="store_true", help="passed to every run")
    p.add_argument("--out", default=None, help="study folder (default out/study_<case name>)")
    p.add_argument("--no-plot", action="store_true", help="skip study.png")
    args = p.parse_args(argv)
    try:
        vary = [parse_vary(v) for v in args.vary]
        r = study(args.case, vary, measures=args.measure, sets=args.sets, out=args.out, jobs=args.jobs,
                  threads=args.threads, fixed_threads=args.fixed_threads, plot_png=not args.no_plot,
                  references=args.reference)
    except ValueError as e:  # StudyError and mpsolid.InputError
        print(f"mpsolid: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if r.status == EXIT_STOPPED:
        print(f"mpsolid study: stopped; run the same command again to continue ({r.folder})",
              file=sys.stderr)
    else:
        written = ["study.csv"] + (["richardson.csv"] if r.richardson else []) + ["study.md"] \
            + ([] if args.no_plot else ["study.png"])
        print(f"mpsolid study: wrote {', '.join(written)} in {r.folder}")
    return r.status


if __name__ == "__main__":
    sys.exit(main())
