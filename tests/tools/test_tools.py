#!/usr/bin/python3
"""The pictures and the XDMF sidecar, end to end, on a short run.

    /usr/bin/python3 tests/tools/test_tools.py PATH_TO_MPSOLID   (from the repository root)

- frames.xdmf parses as XML, lists every frame of frames.h5 at its time, and
  every dataset it references exists in frames.h5 with the shape and type it
  states; every field (id, kind, body, velocity, rotation, angular velocity,
  strain, pressure) is there;
- output.compression = 4 gives deflated datasets with the same values;
- tools/plot.py writes frames.png and history.png, valid PNGs of sensible
  size, also with --color pressure, and fails clearly (exit 2,
  a message naming what is missing) on a folder without results.
Prints "ok: ..." per check, "FAIL: ..." per failure; exits 1 if any failed.
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PLOT = os.path.join(ROOT, "tools", "plot.py")
CASE = os.path.join(ROOT, "cases", "shock_rod.toml")
FIELDS = {"id", "kind", "body", "velocity", "rotation", "angular_velocity", "volumetric_strain",
          "pressure"}
failures = []


def check(condition, what, detail=""):
    if condition:
        print(f"ok: {what}")
    else:
        print(f"FAIL: {what}{': ' + detail if detail else ''}")
        failures.append(what)
    return condition


def run_mpsolid(binary, out, *sets):
    shutil.rmtree(out, ignore_errors=True)
    args = [binary, "run", CASE, "--out", out, "--threads", "1", "--set", "time.end=5e-5",
            "--set", "output.frame_interval=5e-6"]
    for s in sets:
        args += ["--set", s]
    result = subprocess.run(args, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                            timeout=300)
    if result.returncode != 0:
        print(result.stdout, result.stderr)
    return result.returncode


def xdmf_type(number_type, precision):
    return {("Float", 8): np.dtype("<f8"), ("Int", 4): np.dtype("<i4"), ("Char", 1): np.dtype("i1"),
            ("Float", 4): np.dtype("<f4")}.get((number_type, precision))


def check_xdmf(folder):
    path = os.path.join(folder, "frames.xdmf")
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        check(False, "frames.xdmf parses as XML", str(e))
        return
    check(root.tag == "Xdmf", "frames.xdmf is an Xdmf document")
    series = root.find("Domain/Grid")
    check(series is not None and series.get("GridType") == "Collection"
          and series.get("CollectionType") == "Temporal", "frames.xdmf holds a temporal collection")
    grids = series.findall("Grid") if series is not None else []
    with h5py.File(os.path.join(folder, "frames.h5"), "r") as f:
        frames = sorted(f["frames"])
        check(len(grids) == len(frames) == 11,
              "frames.xdmf lists every frame of frames.h5", f"{len(grids)} grids, {len(frames)} frames")
        bad, items = [], 0
        for grid, name in zip(grids, frames):
            time = float(grid.find("Time").get("Value"))
            if time != f["frames"][name].attrs["time"]:
                bad.append(f"{name}: time {time} vs {f['frames'][name].attrs['time']}")
            topology = grid.find("Topology")
            n = int(topology.get("NumberOfElements"))
            if topology.get("TopologyType") != "Polyvertex" or n != f["frames"][name]["id"].shape[0]:
                bad.append(f"{name}: topology {topology.attrib}")
            if grid.find("Geometry").get("GeometryType") != "XY":
                bad.append(f"{name}: geometry is not XY")
            names = {a.get("Name") for a in grid.findall("Attribute")}
            if names != FIELDS:
                bad.append(f"{name}: attributes {sorted(names)}")
            for a in grid.findall("Attribute"):
                kind = a.get("AttributeType")
                dims = a.find("DataItem").get("Dimensions").split()
                if kind != ("Vector" if len(dims) == 2 else "Scalar"):
                    bad.append(f"{name}: {a.get('Name')} is {kind} with dimensions {dims}")
            for item in grid.iter("DataItem"):
                items += 1
                file_name, _, dataset = item.text.strip().partition(":")
                dims = tuple(int(d) for d in item.get("Dimensions").split())
                dtype = xdmf_type(item.get("NumberType"), int(item.get("Precision")))
                if item.get("Format") != "HDF" or file_name != "frames.h5":
                    bad.append(f"{dataset}: in {file_name} ({item.get('Format')})")
                elif dataset not in f:
                    bad.append(f"{dataset}: missing from frames.h5")
                elif f[dataset].shape != dims:
                    bad.append(f"{dataset}: shape {f[dataset].shape}, XDMF says {dims}")
                elif dtype is None or f[dataset].dtype != dtype:
                    bad.append(f"{dataset}: type {f[dataset].dtype}, XDMF says "
                               f"{item.get('NumberType')} {item.get('Precision')}")
        check(not bad and items == 9 * len(frames),
              f"every dataset frames.xdmf references ({items}) exists with its shape and type",
              "; ".join(bad[:5]))


PARAVIEW_SCRIPT = r'''
import sys
from paraview.simple import XDMFReader
r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipelineInformation()
times = list(r.TimestepValues)
r.UpdatePipeline(times[-1])
info = r.GetDataInformation()
ranges = {name: r.PointData[name].GetRange(0) for name in r.PointData.keys()}
print("RESULT", repr((times, info.GetNumberOfPoints(), ranges)))
'''


def check_paraview(folder):
    """ParaView's own Xdmf reader, where ParaView is installed (Debian's
    paraview and python3-paraview; not needed otherwise)."""
    pvbatch = shutil.which("pvbatch") or shutil.which("pvbatch3.11")
    if not pvbatch:
        print("skip: ParaView (pvbatch) not installed; its Xdmf reader is not tried")
        return
    script = os.path.join(folder, "pvcheck.py")
    with open(script, "w") as f:
        f.write(PARAVIEW_SCRIPT)
    result = subprocess.run([pvbatch, "--force-offscreen-rendering", script,
                             os.path.join(folder, "frames.xdmf")],
                            capture_output=True, text=True, timeout=300)
    os.remove(script)
    lines = [l for l in result.stdout.splitlines() if l.startswith("RESULT ")]
    if not check(result.returncode == 0 and lines, "ParaView's Xdmf reader opens frames.xdmf",
                 result.stderr[-500:]):
        return
    times, points, ranges = eval(lines[0][len("RESULT "):])
    with h5py.File(os.path.join(folder, "frames.h5"), "r") as f:
        names = sorted(f["frames"])
        expected_times = [f["frames"][n].attrs["time"] for n in names]
        last = f["frames"][names[-1]]
        expected = {k: (float(last[k][()].min()), float(last[k][()].max()))
                    for k in ("pressure", "volumetric_strain", "rotation", "id")}
        n = last["id"].shape[0]
    check(times == expected_times and points == n and set(ranges) == FIELDS
          and all(tuple(ranges[k]) == v for k, v in expected.items()),
          "ParaView reads every frame, particle and field with the stored values",
          f"{times} {points} {ranges}")


def check_compression(plain, packed):
    with h5py.File(os.path.join(plain, "frames.h5"), "r") as a, \
            h5py.File(os.path.join(packed, "frames.h5"), "r") as b:
        same, deflated = True, True
        for name in a["frames"]:
            for field in a["frames"][name]:
                da, db = a["frames"][name][field], b["frames"][name][field]
                same &= da.dtype == db.dtype and da[()].tobytes() == db[()].tobytes()
                deflated &= db.compression == "gzip" and da.compression is None
    check(same, "compressed frames hold the same values, bit for bit")
    check(deflated, "output.compression = 4 deflates every dataset (and 0 none)")
    sizes = [os.path.getsize(os.path.join(d, "frames.h5")) for d in (plain, packed)]
    check(sizes[1] < sizes[0], "the compressed frames.h5 is smaller", f"{sizes}")


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def check_plot(folder):
    for color in ("body", "pressure"):
        for name in ("frames.png", "history.png"):
            if os.path.exists(os.path.join(folder, name)):
                os.remove(os.path.join(folder, name))
        result = subprocess.run([sys.executable, PLOT, folder, "--color", color],
                                capture_output=True, text=True, timeout=300)
        check(result.returncode == 0, f"plot.py --color {color} exits 0",
              result.stdout + result.stderr)
        for name, least in (("frames.png", (800, 200)), ("history.png", (800, 500))):
            size = png_size(os.path.join(folder, name))
            check(size is not None and least[0] <= size[0] <= 20000 and least[1] <= size[1] <= 8000,
                  f"plot.py --color {color}: {name} is a PNG of sensible size ({size})")

    empty = tempfile.mkdtemp(prefix="mpsolid_plot_empty.")
    try:
        result = subprocess.run([sys.executable, PLOT, empty], capture_output=True, text=True,
                                timeout=120)
        check(result.returncode == 2 and "no results" in result.stderr
              and "frames.h5" in result.stderr,
              "plot.py on a folder without results exits 2 naming what is missing",
              f"exit {result.returncode}: {result.stderr.strip()}")
        check(not os.listdir(empty), "plot.py writes nothing into a folder without results")
        result = subprocess.run([sys.executable, PLOT, os.path.join(empty, "nope")],
                                capture_output=True, text=True, timeout=120)
        check(result.returncode == 2 and "no such folder" in result.stderr,
              "plot.py on a missing folder exits 2", result.stderr.strip())
    finally:
        shutil.rmtree(empty)


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    binary = os.path.abspath(sys.argv[1])
    tmp = tempfile.mkdtemp(prefix="mpsolid_tools.")
    try:
        plain, packed = os.path.join(tmp, "plain"), os.path.join(tmp, "packed")
        if not check(run_mpsolid(binary, plain) == 0, "a short run"):
            return 1
        check_xdmf(plain)
        check_paraview(plain)
        if check(run_mpsolid(binary, packed, "output.compression=4") == 0,
                 "a short run with output.compression = 4"):
            check_compression(plain, packed)
            check_xdmf(packed)
        check_plot(plain)
    finally:
        shutil.rmtree(tmp)
    print()
    if failures:
        print(f"test_tools: {len(failures)} check(s) FAILED")
        return 1
    print("test_tools: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
