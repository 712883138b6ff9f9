#!/usr/bin/python3
"""tools/contact_study.py end to end on two tiny runs.

    /usr/bin/python3 tests/tools/test_contact_study.py PATH_TO_MPSOLID

Runs the 55.9 kN rod with contact (cases/shock_rod_55kN.toml) and without
(cases/shock_rod_55kN_short_wall.toml) at l0 = 4 mm to t = 2 ms, frames every
1 ms (the wall made 8 mm thick, two particles: at l0 = 4 mm the 4 mm wall is
one particle thick, which the finite-strain model refuses where the tall
wall reaches past the rod), then checks that the tool:
- prints a Markdown table with one row per run, the plate displacement
  positive and growing at 1 and 2 ms, empty cells past the runs' end (3 ms),
  no first peak yet, a small balance error, a contact distance for the
  contact run only, and writes the same text to --out-md;
- gives a differences table for consecutive runs with the same contact
  setting only (the contact run given twice: differences 0);
- writes --out-png, a PNG about 2200 px wide for two pairs;
- exits 2 with a message naming the folder for a missing folder and for a
  folder without history.csv.
Prints "ok: ..." per check, "FAIL: ..." per failure; exits 1 if any failed.
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TOOL = os.path.join(ROOT, "tools", "contact_study.py")
CONTACT_CASE = os.path.join(ROOT, "cases", "shock_rod_55kN.toml")
NO_CONTACT_CASE = os.path.join(ROOT, "cases", "shock_rod_55kN_short_wall.toml")
SETTINGS = ["l0=0.004", "time.end=0.002", "output.frame_interval=0.001",
            "bodies.wall.x=[0.100,0.108]"]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, verdict  # noqa: E402


def start_run(binary, case, out):
    args = [binary, "run", case, "--out", out, "--threads", "1"]
    for setting in SETTINGS:
        args += ["--set", setting]
    return subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)


def make_runs(binary, tmp):
    """The two runs, side by side; their folders, or None if one failed."""
    folders = {"contact": os.path.join(tmp, "contact"), "none": os.path.join(tmp, "none")}
    jobs = {"contact": start_run(binary, CONTACT_CASE, folders["contact"]),
            "none": start_run(binary, NO_CONTACT_CASE, folders["none"])}
    ok = True
    for name, job in jobs.items():
        output, _ = job.communicate(timeout=120)
        ok &= check(job.returncode == 0, f"the tiny {name} run completes", output[-800:])
    return folders if ok else None


def tool(*args):
    return subprocess.run(["/usr/bin/python3", TOOL, *args], stdin=subprocess.DEVNULL,
                          capture_output=True, text=True, timeout=120)


def tables(text):
    """{heading: [row cells]} of the Markdown tables under each '## ' heading."""
    found, heading = {}, None
    for line in text.splitlines():
        if line.startswith("## "):
            heading = line[3:]
            found[heading] = []
        elif line.startswith("|") and heading is not None:
            found[heading].append([c.strip() for c in line.strip().strip("|").split("|")])
    return found


def check_table(rows):
    head, body = rows[0], rows[2:]
    by_label = {r[0]: dict(zip(head, r)) for r in body}
    check(sorted(by_label) == ["c", "c_again", "n"] and len(body) == 3,
          "the table has one row per run", str([r[0] for r in body]))
    for label, r in by_label.items():
        try:
            x1, x2 = float(r["x(1 ms)"]), float(r["x(2 ms)"])
        except (KeyError, ValueError):
            check(False, f"{label}: displacement at 1 and 2 ms are numbers", str(r))
            continue
        check(0 < x1 < x2 < 100, f"{label}: plate displacement positive and growing "
              f"(1 ms: {x1} mm, 2 ms: {x2} mm)")
        check(r["x(3 ms)"] == "" and r["x(10 ms)"] == "",
              f"{label}: empty cells past the run's end", f"{r['x(3 ms)']!r}, {r['x(10 ms)']!r}")
        check(r["first peak x (mm)"] == "" and r["later peaks"] == "no first peak",
              f"{label}: no first peak before 2 ms", str(r))
        check(0 <= float(r["balance error (%)"]) < 1.0,
              f"{label}: energy balance error below 1 % ({r['balance error (%)']} %)")
    distance = by_label.get("c", {}).get("min contact distance (mm)", "")
    check(distance.replace(".", "").isdigit() and 0 < float(distance) < 20,
          f"the contact run has a minimum contact distance ({distance} mm)")
    check(by_label.get("n", {}).get("min contact distance (mm)") == "no contact",
          "the run without contact has none")


def check_differences(rows):
    body = rows[2:] if rows else []
    check(len(body) == 1 and body[0][0] == "c_again − c" and body[0][1] == "on",
          "differences: only the two runs with contact are paired", str(body))
    if body:
        values = [v for v in body[0][2:] if v]
        check(values and all(float(v) == 0.0 for v in values),
              "differences of a run with itself are 0", str(body[0]))


def check_png(path):
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError as e:
        check(False, "--out-png is written", str(e))
        return
    check(head[:8] == b"\x89PNG\r\n\x1a\n", "--out-png is a PNG")
    width, height = struct.unpack(">II", head[16:24])
    check(1900 <= width <= 2400 and height > width,
          f"--out-png is about 2200 px wide, 10 rows tall ({width} x {height} px)")


def check_errors(tmp, folder):
    missing = os.path.join(tmp, "no_such_run")
    result = tool("--run", f"x={missing}")
    check(result.returncode == 2 and missing in result.stderr and "Traceback" not in result.stderr,
          "a missing folder: exit 2 naming it", f"{result.returncode}: {result.stderr}")
    empty = os.path.join(tmp, "empty")
    os.mkdir(empty)
    result = tool("--run", f"c={folder}", "--run", f"x={empty}")
    check(result.returncode == 2 and empty in result.stderr and "history.csv" in result.stderr
          and "Traceback" not in result.stderr,
          "a folder without history.csv: exit 2 naming it", f"{result.returncode}: {result.stderr}")


def main():
    if len(sys.argv) != 2 or not os.access(sys.argv[1], os.X_OK):
        print(__doc__)
        return 2
    tmp = tempfile.mkdtemp(prefix="contact_study_")
    try:
        folders = make_runs(sys.argv[1], tmp)
        if folders:
            md, png = os.path.join(tmp, "study.md"), os.path.join(tmp, "study.png")
            result = tool("--run", f"c={folders['contact']}", "--run", f"n={folders['none']}",
                          "--run", f"c_again={folders['contact']}", "--pair", "c:n",
                          "--pair", "c_again:n", "--out-md", md, "--out-png", png)
            if check(result.returncode == 0, "the tool runs", result.stderr[-2000:]):
                found = tables(result.stdout)
                check("plate.x, displacement (mm)" in found, "a table of plate.x", result.stdout)
                check_table(found.get("plate.x, displacement (mm)", [[]] * 2))
                check_differences(next((rows for heading, rows in found.items()
                                        if heading.startswith("differences")), []))
                with open(md) as f:
                    check(f.read() == result.stdout, "--out-md holds the printed tables")
                check_png(png)
            check_errors(tmp, folders["contact"])
    finally:
        shutil.rmtree(tmp)
    return verdict("test_contact_study")


if __name__ == "__main__":
    sys.exit(main())
