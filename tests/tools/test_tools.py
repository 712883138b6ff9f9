#!/usr/bin/python3
"""The pictures and the XDMF sidecar, end to end, on a short run.

    /usr/bin/python3 tests/tools/test_tools.py PATH_TO_MPSOLID   (from the repository root)

- frames.xdmf parses as XML, lists every frame of frames.h5 at its time, and
  every dataset it references exists in frames.h5 with the shape and type it
  states; every field (id, kind, body, velocity, rotation, angular velocity,
  strain, pressure, surface flag, normal) is there;
- output.compression = 4 gives deflated datasets with the same values;
- tools/plot.py writes frames.png and history.png, valid PNGs of sensible
  size, also with --color pressure, and fails clearly (exit 2,
  a message naming what is missing) on a folder without results;
- its pictures, through --describe (what was drawn, as JSON): frames in a
  grid of at most 6 columns and more than one row for 12 frames, about
  2000-2400 px wide, coloured by pressure by default with a colourbar
  labelled with the quantity and unit (body colours with a legend on
  request), the title giving case, model, l0, dt and force; history.png
  with the energy-balance error on its own panel relative to max W; a
  --reference curve drawn on the displacement panel (a missing file: exit
  2); a blow-up run (the 55.9 kN rod with the paper model, exit 3) marked on
  every time panel with its criterion and its last frame as the last good
  state; a ring under internal pressure drawn with its two outlines and
  arrows on its inner surface, whose frames' normals point into the hole;
  in space, a cube's pressed face's arrows on that face's particles;
- a gas's grid in frames.xdmf (a second temporal collection of cell
  fields on a 2DCoRectMesh, every dataset present with its count) and
  tools/plot_gas.py's schlieren.png and gas_probes.png;
- tools/plot.py is an executable (#!/usr/bin/python3) and, under a Python
  without h5py or matplotlib, exits 2 with one line naming the package and
  /usr/bin/python3, no traceback.
Prints "ok: ..." per check, "FAIL: ..." per failure; exits 1 if any failed.
"""
import csv
import json
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
CASE_55KN = os.path.join(ROOT, "cases", "shock_rod_55kN_short_wall.toml")
CASE_RING = os.path.join(ROOT, "cases", "ring_pressure.toml")
CASE_GAS = os.path.join(ROOT, "cases", "giordano_panel.toml")
CASE_CUBE = os.path.join(ROOT, "cases", "spinning_cube.toml")
FIELDS = {"id", "kind", "body", "velocity", "rotation", "angular_velocity", "volumetric_strain",
          "pressure", "surface", "normal"}
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, verdict  # noqa: E402


def run_mpsolid(binary, out, *sets, case=CASE, short=True, expect=0):
    shutil.rmtree(out, ignore_errors=True)
    args = [binary, "run", case, "--out", out, "--threads", "1"]
    if short:
        args += ["--set", "time.end=5e-5", "--set", "output.frame_interval=5e-6"]
    for s in sets:
        args += ["--set", s]
    result = subprocess.run(args, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                            timeout=300)
    if result.returncode != expect:
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
        check(not bad and items == (len(FIELDS) + 1) * len(frames),
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


def describe(folder, *options):
    """Runs plot.py FOLDER --describe OPTIONS: (exit code, what was drawn or None, stderr)."""
    result = subprocess.run([sys.executable, PLOT, folder, "--describe", *options],
                            capture_output=True, text=True, timeout=300)
    try:
        drawn = json.loads(result.stdout) if result.returncode == 0 else None
    except ValueError:
        drawn = None
    return result.returncode, drawn, result.stdout[-400:] + result.stderr[-800:]


def check_pictures(folder):
    """The grid, colouring, titles and panels of a run with more frames than shown."""
    code, drawn, output = describe(folder)
    if not check(code == 0 and drawn is not None, "plot.py --describe exits 0 with JSON", output):
        return
    frames, history = drawn["frames"], drawn["history"]
    size = png_size(os.path.join(folder, "frames.png"))
    check(size is not None and list(size) == frames["size_px"],
          "--describe gives frames.png's size in pixels", f"{size} vs {frames['size_px']}")
    check(len(frames["panels"]) == 12 and frames["columns"] <= 6 and frames["rows"] >= 2,
          "12 frames by default, in a grid of at most 6 columns and more than one row",
          f"{len(frames['panels'])} panels, {frames['rows']} x {frames['columns']}")
    check(size is not None and 1900 <= size[0] <= 2500 and size[1] <= 2000,
          "frames.png is about 2000-2400 px wide at the default dpi", f"{size}")
    check(all(p["title"].startswith("t = ") and p["title"].endswith(" ms")
              for p in frames["panels"]), "every frame panel gives its time in ms",
          f"{[p['title'] for p in frames['panels']]}")
    times = [p["time"] for p in frames["panels"]]
    with h5py.File(os.path.join(folder, "frames.h5"), "r") as f:
        stored = sorted(f["frames"][n].attrs["time"] for n in f["frames"])
    check(times == sorted(times) and times[0] == stored[0] and times[-1] == stored[-1],
          "the frames shown run in time order from the first frame to the last")
    bar = frames["colorbar"]
    check(frames["color"] == "pressure" and bar is not None and "pressure" in bar["label"]
          and bar["unit"] in ("MPa", "kPa", "Pa") and f"({bar['unit']}" in bar["label"],
          "colouring by pressure by default, one colourbar labelled with the quantity and unit",
          f"{frames['color']}, {bar}")
    if bar is not None:
        lo, hi = bar["data_range"]
        clipped = lo < bar["limits"][0] or hi > bar["limits"][1]
        check(clipped == bar["clipped"] and (not clipped or "clipped" in bar["label"]),
              "a clipped colour scale says so in the colourbar label", f"{bar}")
    for what in (frames, history):
        title = what["title"]
        check(title.startswith("shock_rod") and "model paper" in title and "l0 = 2 mm" in title
              and "dt = 10 ns" in title and "11.2 kN" in title,
              "the title gives case, model, l0, dt and force", title)
        check(os.path.abspath(folder) in what["footnote"] and os.path.basename(folder)
              not in title, "the folder's name is a footnote, not the title", what["footnote"])
    panels = {p["name"]: p for p in history["panels"]}
    balance = panels.get("balance", {})
    ylabel = balance.get("ylabel", "")
    check("energy" in panels and balance.get("lines") and "max W" in ylabel and "E0" in ylabel
          and ylabel.endswith("(%)") and "external work W" in panels["energy"]["lines"]
          and "external work W" not in balance["lines"],
          "the energy-balance error (KE + PE - W - E0) / max W in % has a panel of its own",
          f"{balance}")
    h = {}
    with open(os.path.join(folder, "history.csv"), newline="") as f:
        rows = list(csv.reader(f))
    for k, name in enumerate(rows[0]):
        h[name] = np.array([float(r[k]) for r in rows[1:]])
    e = h["kinetic_energy"] + h["strain_energy"]
    expected = (e[-1] - h["external_work"][-1] - e[0]) / np.max(np.abs(h["external_work"])) * 100
    check(abs(balance.get("final_percent", 1e9) - expected) <= 1e-9 * max(1.0, abs(expected)),
          "the balance panel's last value is (KE + PE - W - E0) / max W in %",
          f"{balance.get('final_percent')} vs {expected}")
    check(set(panels) >= {"rigid", "x", "y", "energy", "balance"} and history["blowup"] is None
          and all("blowup_marker" not in p for p in history["panels"]),
          "history.png: displacement, extents, energies and balance; no blow-up marked",
          f"{sorted(panels)}")

    code, drawn, output = describe(folder, "--color", "body")
    if check(code == 0 and drawn is not None, "plot.py --color body --describe exits 0", output):
        legend = drawn["frames"]["legend"]
        check(drawn["frames"]["colorbar"] is None and any(l.startswith("rod") for l in legend)
              and any(l.startswith("plate") for l in legend),
              "--color body: body colours with a legend, no colourbar", f"{legend}")

    reference = os.path.join(folder, "reference plate.csv")
    with open(reference, "w") as f:
        f.write("t,x\n" + "".join(f"{k * 5e-6:.6g},{k * 1e-5:.6g}\n" for k in range(11)))
    code, drawn, output = describe(folder, "--reference", reference)
    if check(code == 0 and drawn is not None, "plot.py --reference FILE.csv exits 0", output):
        ref = drawn["history"]["reference"]
        rigid = {p["name"]: p for p in drawn["history"]["panels"]}["rigid"]
        check(ref is not None and ref["points"] == 11
              and "reference: reference plate.csv" in rigid["lines"],
              "--reference: the curve (header row skipped) is drawn on the displacement panel, "
              "labelled with the file name", f"{ref}, {rigid['lines']}")
    code, drawn, output = describe(folder, "--reference", reference + ".missing")
    check(code == 2 and "no such file" in output, "--reference with a missing file exits 2",
          output)
    os.remove(reference)


def check_blowup(folder):
    code, drawn, output = describe(folder)
    if not check(code == 0 and drawn is not None, "plot.py --describe on a blow-up exits 0",
                 output):
        return
    with open(os.path.join(folder, "run.json")) as f:
        diagnosis = json.load(f)["diagnosis"]
    criterion, when = diagnosis["criterion"], diagnosis["time"]
    markers = [p.get("blowup_marker") for p in drawn["history"]["panels"]]
    check(markers and all(m and m["time"] == when and m["criterion"] == criterion
                          for m in markers),
          "history.png marks the blow-up time with its criterion on every time panel",
          f"{markers}")
    frames = drawn["frames"]
    check(frames["blowup"] is not None and frames["blowup"]["criterion"] == criterion
          and frames["panels"][-1]["last_good_state"]
          and not any(p["last_good_state"] for p in frames["panels"][:-1]),
          "frames.png marks the last frame as the last good state, with the criterion",
          f"{frames['blowup']}")
    ring = frames["blowup"] and frames["blowup"]["particle_position_mm"]
    check(ring is not None and all(abs(a - b * 1e3) < 1e-9
                                   for a, b in zip(ring, diagnosis["position"])),
          "frames.png rings the diagnosed particle at its position", f"{ring}")


def check_missing_libraries(folder):
    check(os.access(PLOT, os.X_OK), "tools/plot.py is executable")
    with open(PLOT) as f:
        check(f.readline().strip() == "#!/usr/bin/python3",
              "tools/plot.py starts with #!/usr/bin/python3")
    result = subprocess.run([PLOT, folder], capture_output=True, text=True, timeout=300)
    check(result.returncode == 0, "tools/plot.py DIR runs as an executable",
          result.stdout + result.stderr)
    for module, package in (("h5py", "python3-h5py"), ("matplotlib", "python3-matplotlib")):
        # A Python without the module: the import machinery refuses names set to None.
        program = (f"import runpy, sys; sys.modules[{module!r}] = None; "
                   f"sys.argv = [{PLOT!r}, {folder!r}]; runpy.run_path({PLOT!r}, "
                   f"run_name='__main__')")
        result = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                                timeout=120)
        lines = result.stderr.strip().splitlines()
        check(result.returncode == 2 and len(lines) == 1 and package in lines[0]
              and "/usr/bin/python3" in lines[0] and "Traceback" not in result.stderr,
              f"under a Python without {module}, plot.py exits 2 with one line naming "
              f"{package} and /usr/bin/python3", f"exit {result.returncode}: {result.stderr}")


def check_shapes(folder):
    """A shaped body's outlines and a pressure's arrows, and the frames' surface."""
    code, drawn, output = describe(folder)
    if not check(code == 0 and drawn is not None, "plot.py --describe on the ring exits 0", output):
        return
    frames = drawn["frames"]
    check(frames["outlines"] == {"ring": 2} and "outline at t = 0" in frames["legend"],
          "the ring's two circles are drawn over its particles, with a legend entry",
          f"{frames['outlines']}, {frames['legend']}")
    with h5py.File(os.path.join(folder, "frames.h5"), "r") as f:
        first = f["frames"]["000000"]
        position, surface, normal = first["position"][()], first["surface"][()], first["normal"][()]
    r = np.hypot(position[:, 0], position[:, 1])
    inner = (surface == 1) & (r < 0.0105)
    outward = np.einsum("ij,ij->i", normal[inner], -position[inner] / r[inner, None])
    check(frames["pressure_particles"].get("inflate", 0) == inner.sum() > 50
          and "pressure on the loaded surface" in frames["legend"],
          "the pressure's arrows stand on the inner surface's particles, with a legend entry",
          f"{frames['pressure_particles']} vs {inner.sum()} inner surface particles")
    check(outward.min() > 0.9 and np.all(normal[surface == 0] == 0),
          "the inner surface's normals point into the hole, interior particles have none",
          f"smallest cosine {outward.min():.3f}")


def check_space_pressure(folder):
    """In space, a pressure on a cube's front face (z high): its arrows stand
    on that face's particles (those whose normals point along +z)."""
    code, drawn, output = describe(folder)
    if not check(code == 0 and drawn is not None, "plot.py --describe on the cube exits 0", output):
        return
    with h5py.File(os.path.join(folder, "frames.h5"), "r") as f:
        first = f["frames"]["000000"]
        position, surface, normal = first["position"][()], first["surface"][()], first["normal"][()]
    front = (surface == 1) & (position[:, 2] > position[:, 2].max() - 1e-9) & (normal[:, 2] > 0.9)
    check(drawn["frames"]["pressure_particles"].get("front", 0) == front.sum() > 20,
          "in space, a pressure's arrows stand on its face's particles",
          f"{drawn['frames']['pressure_particles']} vs {front.sum()} front face particles")


def check_gas(folder):
    """The gas's grid in frames.xdmf (a second temporal collection, a
    2DCoRectMesh of the gas's nodes with its cell fields, each dataset in
    frames.h5 with the count it states) and tools/plot_gas.py's pictures."""
    root = ET.parse(os.path.join(folder, "frames.xdmf")).getroot()
    series = root.findall("Domain/Grid")
    check(len(series) == 2 and series[1].get("Name") == "gas",
          "frames.xdmf holds the particles' and the gas's time series")
    if len(series) != 2:
        return
    bad = []
    with h5py.File(os.path.join(folder, "frames.h5"), "r") as f:
        nx, ny = int(f.attrs["gas_nx"]), int(f.attrs["gas_ny"])
        grids = series[1].findall("Grid")
        check(len(grids) == len(f["frames"]), "the gas's series lists every frame")
        for grid in grids:
            topology = grid.find("Topology")
            if (topology.get("TopologyType") != "2DCoRectMesh"
                    or topology.get("Dimensions") != f"{ny + 1} {nx + 1}"):
                bad.append(f"topology {topology.attrib}")
            names = {a.get("Name") for a in grid.findall("Attribute")}
            if names != {"density", "velocity", "pressure", "solid"}:
                bad.append(f"attributes {sorted(names)}")
            for a in grid.findall("Attribute"):
                item = a.find("DataItem")
                dataset = item.text.strip().partition(":")[2]
                count = int(np.prod([int(d) for d in item.get("Dimensions").split()]))
                if a.get("Center") != "Cell" or dataset not in f or f[dataset].size != count:
                    bad.append(f"{dataset}: {count} values stated")
                elif count != nx * ny * (2 if a.get("Name") == "velocity" else 1):
                    bad.append(f"{dataset}: {count} values for {nx} x {ny} cells")
    check(not bad, "every gas dataset frames.xdmf references exists with its count", "; ".join(bad[:5]))
    result = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "tools", "plot_gas.py"), folder,
                             "--times", "0.01", "0.02"], capture_output=True, text=True, timeout=300)
    check(result.returncode == 0, "tools/plot_gas.py runs", result.stderr[-300:])
    for name, least in (("schlieren.png", 1500), ("gas_probes.png", 800)):
        size = png_size(os.path.join(folder, name))
        check(size is not None and size[0] >= least, f"{name} is a PNG at least {least} px wide",
              str(size))
    # A body's displacement beside another run's (here the same run, shifted
    # measured points): displacement.png; a missing --against folder: exit 2.
    tip = os.path.join(ROOT, "docs", "data", "giordano_tip_measured_digitized.csv")
    result = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "tools", "plot_gas.py"), folder,
                             "--displacement", "panel.xmax", "--measured-displacement", tip,
                             "--measured-displacement-from", "0.048", "--against",
                             f"{folder}:again"], capture_output=True, text=True, timeout=300)
    size = png_size(os.path.join(folder, "displacement.png"))
    check(result.returncode == 0 and size is not None and size[0] >= 800,
          "tools/plot_gas.py --displacement --against: displacement.png", result.stderr[-300:])
    result = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "tools", "plot_gas.py"), folder,
                             "--displacement", "panel.xmax", "--against",
                             os.path.join(folder, "elsewhere")], capture_output=True, text=True)
    check(result.returncode == 2 and "elsewhere" in result.stderr,
          "tools/plot_gas.py --against a missing folder: exit 2 naming it")
    result = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "tools", "plot_gas.py"),
                             os.path.join(folder, "nowhere")], capture_output=True, text=True)
    check(result.returncode == 2 and "nowhere" in result.stderr,
          "tools/plot_gas.py on a missing folder: exit 2 naming it")


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
        check_missing_libraries(plain)
        grid = os.path.join(tmp, "grid")
        if check(run_mpsolid(binary, grid, "output.frame_interval=2e-6") == 0,
                 "a short run with 26 frames"):
            check_pictures(grid)
        ring = os.path.join(tmp, "ring")
        if check(run_mpsolid(binary, ring, "time.end=2e-4", "output.frame_interval=5e-5",
                             case=CASE_RING, short=False) == 0,
                 "a short run of the ring under internal pressure"):
            check_shapes(ring)
        cube = os.path.join(tmp, "cube")
        if check(run_mpsolid(binary, cube, "l0=0.008", "time.end=0.002",
                             "output.frame_interval=0.001", "output.history_interval=0.001",
                             "loads.front.type=\"pressure\"",
                             "loads.front.body=\"cube\"", "loads.front.pressure=1e3",
                             "loads.front.face=\"front\"", case=CASE_CUBE, short=False) == 0,
                 "a short run of a cube in space with a pressure on its front face"):
            check_space_pressure(cube)
        gas = os.path.join(tmp, "gas")
        if check(run_mpsolid(binary, gas, "gas.cell=0.001", "gas.shock.x=-0.002", "time.end=2e-5",
                             "output.frame_interval=1e-5", case=CASE_GAS, short=False) == 0,
                 "a short run of the Giordano panel in its gas"):
            check_gas(gas)
        blowup = os.path.join(tmp, "blowup")
        if check(run_mpsolid(binary, blowup, "model=paper", "time.end=0.001", case=CASE_55KN,
                             short=False, expect=3) == 3,
                 "the 55.9 kN rod with the paper model blows up (exit 3)"):
            check_blowup(blowup)
    finally:
        shutil.rmtree(tmp)
    return verdict("test_tools")


if __name__ == "__main__":
    sys.exit(main())
