#!/usr/bin/python3
"""Pictures of an mpsolid run's gas: writes DIR/schlieren.png and
DIR/gas_probes.png.

    tools/plot_gas.py DIR [--times MS ...] [--columns C] [--measured FILE.csv]
                          [--measured-from MS] [--measured-label TEXT]
                          [--displacement COLUMN] [--measured-displacement FILE.csv]
                          [--measured-displacement-from MS] [--against DIR[:LABEL] ...]
                          [--label TEXT] [--dpi D]

schlieren.png: numerical schlieren (the density gradient's magnitude in grey,
dark at shocks) with the bodies' particles drawn over it, at the frames
nearest --times (ms; default six frames evenly spread). gas_probes.png: each
gas probe's pressure over time, with --measured points (t in ms, p in kPa)
drawn over it. With --displacement COLUMN (a history.csv column, e.g.
panel.xmax), displacement.png: its change since t = 0 in mm, with
--measured-displacement points (t in ms, mm) drawn over it. An experiment's
clock starts at an event (the shock passing a gauge, reaching the panel):
--measured-from and --measured-displacement-from give the run's time (ms)
of that event, and the measured points are drawn from there. --against
draws other runs' same column beside it (a step-force run against a shock,
another grid), each labelled by LABEL or its case's name.

The drawing is the package's mpsolid.plot_gas (taken from the source tree: no
build needed). Needs numpy, h5py and matplotlib (/usr/bin/python3 on
Debian). Exit codes: 0 done; 2 a missing folder, file or library, or a run
without a gas.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from source_package import mpsolid_module, require_libraries  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder")
    parser.add_argument("--times", type=float, nargs="+", help="ms")
    parser.add_argument("--columns", type=int, default=2)
    parser.add_argument("--measured", help="CSV of t (ms), p (kPa)")
    parser.add_argument("--measured-from", type=float, default=0.0,
                        help="the run's time (ms) of the measured series' t = 0")
    parser.add_argument("--measured-label", default="experiment")
    parser.add_argument("--displacement", help="a history.csv column, e.g. panel.xmax")
    parser.add_argument("--measured-displacement", help="CSV of t (ms), displacement (mm)")
    parser.add_argument("--measured-displacement-from", type=float, default=0.0,
                        help="the run's time (ms) of the measured displacement's t = 0")
    parser.add_argument("--against", nargs="+", default=[], metavar="DIR[:LABEL]",
                        help="other runs whose --displacement column is drawn beside it")
    parser.add_argument("--label", help="the run's own label beside --against runs")
    parser.add_argument("--dpi", type=int, default=150)
    args = parser.parse_args()
    if not os.path.isdir(args.folder):
        print(f"plot_gas: {args.folder}: no such folder", file=sys.stderr)
        return 2
    against = [tuple(a.split(":", 1)) if ":" in a else (a, None) for a in args.against]
    for path, _ in against:
        if not os.path.isdir(path):
            print(f"plot_gas: --against {path}: no such folder", file=sys.stderr)
            return 2
    require_libraries("tools/plot_gas.py")
    try:
        plot_gas = mpsolid_module("plot_gas")
        print(plot_gas.schlieren(args.folder, args.times, columns=args.columns, dpi=args.dpi))
        print(plot_gas.probe_history(args.folder, measured=args.measured,
                                     measured_label=args.measured_label, dpi=args.dpi,
                                     measured_from=args.measured_from))
        if args.displacement:
            print(plot_gas.displacement_history(args.folder, args.displacement,
                                                measured=args.measured_displacement,
                                                measured_label=args.measured_label, dpi=args.dpi,
                                                measured_from=args.measured_displacement_from,
                                                against=against, label=args.label))
    except (ImportError, FileNotFoundError, ValueError, KeyError,
            mpsolid_module("plot").PlotError) as e:
        print(f"plot_gas: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
