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

The drawing is the package's mpsolid.plot (python/mpsolid/plot.py, taken
from the source tree: no build needed); this is its command line.
Needs numpy, h5py and matplotlib: Debian's python3-h5py and python3-matplotlib
(the script runs with /usr/bin/python3). Exit codes: 0 done; 2 a missing
library, folder or reference file, or a folder without results; 1 results
that cannot be read.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from source_package import mpsolid_module, require_libraries  # noqa: E402


def fail(message, code=2):
    print(f"plot.py: {message}", file=sys.stderr)
    sys.exit(code)


def parse_args():
    parser = argparse.ArgumentParser(
        description="Pictures of an mpsolid run: DIR/frames.png and DIR/history.png.")
    parser.add_argument("dir", help="the run's output folder (mpsolid run ... --out DIR)")
    parser.add_argument("--color", choices=["pressure", "body", "strain"], default="pressure",
                        help="colour elastic bodies by pressure (default), volumetric strain, "
                             "or every body by body")
    parser.add_argument("--frames", type=int, default=12,
                        help="at most this many frames, evenly picked (default 12; "
                             "6 to a row)")
    parser.add_argument("--dpi", type=int, default=150,
                        help="resolution (default 150: frames.png about 2200 px wide)")
    parser.add_argument("--reference", metavar="FILE.csv",
                        help="a reference curve drawn over the rigid-body displacement: "
                             "columns t, x in s and m (a header row allowed)")
    parser.add_argument("--section", metavar="[AXIS=]VALUE",
                        help="a run in space: draw the layer of particles at z = VALUE (m), or "
                             "on the plane x=VALUE or y=VALUE, at the start (a material "
                             "section) instead of them all seen along z")
    parser.add_argument("--describe", action="store_true",
                        help="print what was drawn as JSON on stdout (the PNGs are still written)")
    return parser.parse_args()


def main():
    args = parse_args()
    require_libraries("tools/plot.py")
    plot = mpsolid_module("plot")
    if args.frames < 1:
        fail("--frames must be at least 1")
    if args.dpi < 20:
        fail("--dpi must be at least 20")
    try:
        drawn = plot.plot_run(args.dir, color=args.color, frames=args.frames, dpi=args.dpi,
                              reference=args.reference, section=args.section)
    except plot.PlotError as e:
        fail(str(e), e.code)
    if args.describe:
        print(json.dumps(drawn, indent=2))
    else:
        for what in drawn.values():
            print(f"plot.py: wrote {what['file']} ({what['size_px'][0]} x "
                  f"{what['size_px'][1]} px)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
