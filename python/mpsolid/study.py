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
# (The docstring above is `mpsolid study --help`.) This module ties the three
# parts together and is the command line: study_grid (the points from the
# spec), study_runner (each point run by the executable) and study_report (the
# measures, Richardson, study.csv, study.md, study.png).
import argparse
import os
import sys
import time

from . import run_data
from .study_grid import (StudyError, check_points, folder_name, grid, measure_list, parse_vary,
                         point_overrides, reference_list, vary_list)
from .study_report import equivalent_command, point_row, reference_errors, richardson_rows, write_report
from .study_runner import (EXIT_BAD_INPUT, EXIT_STOPPED, PointRunner, executable,
                           run_all, write_provenance)


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
    vary = vary_list(vary)
    measures = measure_list(measures)
    references = reference_list(references, measures)
    if jobs < 1:
        raise StudyError(f"--jobs {jobs}: must be at least 1")
    cores = os.cpu_count() or 1
    threads = threads or max(1, cores // jobs)
    points = grid(vary)
    name = os.path.splitext(os.path.basename(case_path))[0]
    out = os.fspath(out) if out else os.path.join("out", f"study_{name}")

    # Every point is checked before anything runs: the command line's messages.
    check_points(case_path, base, points)
    exe = executable()
    os.makedirs(out, exist_ok=True)
    write_provenance(out, case_path, base, vary, measures, references, jobs, threads, exe)

    runner = PointRunner(exe, threads, fixed_threads)
    results, failures = {}, []
    started = time.monotonic()

    def one(k, point):
        folder = os.path.join(out, folder_name(point))
        what = runner.run(os.path.abspath(case_path), point_overrides(base, point), folder)
        results[k] = what
        info = run_data.read_info(folder, default={})
        done = sum(1 for v in results.values() if v != "not started")
        log(f"mpsolid study: [{done}/{len(points)}] {folder_name(point)}: {what}"
            + (f", {info.get('outcome')} at t = {info.get('simulated_time', 0):g} s in "
               f"{info.get('wall_seconds', 0):.1f} s" if what in ("ran", "stopped") else "")
            + f" ({time.monotonic() - started:.0f} s into the study)")

    status = run_all(points, one, jobs, runner, failures)
    rows = [point_row(p, os.path.join(out, folder_name(p)), measures) for p in points]
    estimates = richardson_rows(rows, vary, measures) if status == 0 else []
    reference_errors(rows, references)
    write_report(out, rows, vary, measures, estimates,
                 equivalent_command(case_path, vary, base, measures, references, jobs, threads, out),
                 f"study of {name}" if plot_png and status == 0 else None, log)
    if failures:
        raise failures[0]
    return StudyResult(out, rows, estimates, status)


def _case_and_overrides(case):
    if isinstance(case, (str, os.PathLike)):
        return os.fspath(case), []
    return case.path, list(case.overrides)


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
