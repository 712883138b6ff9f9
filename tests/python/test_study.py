#!/usr/bin/python3
"""`mpsolid study` and mpsolid.study (python/mpsolid/study.py): the grid, the
table, Richardson, bad input, and a study stopped half-way and resumed to
the same bits as an uninterrupted run. Needs the build tree's package on
PYTHONPATH (ctest sets it) and MPSOLID_EXECUTABLE or the package's
_build_paths."""
import csv
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import mpsolid
from mpsolid import analysis
from mpsolid.study import executable

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(ROOT, "cases", "shock_rod.toml")
EXE = executable()


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def cli(*args, **kw):
    return subprocess.run([EXE, *args], capture_output=True, text=True, **kw)


class Analysis(unittest.TestCase):
    def test_richardson_recovers_a_known_series(self):
        # f(h) = 1 + 0.5 h^2 at h = 4, 2, 1: order 2, limit 1, exactly.
        r = analysis.richardson([1 + 0.5 * h * h for h in (4, 2, 1)])
        self.assertAlmostEqual(r["order"], 2.0, places=12)
        self.assertAlmostEqual(r["value"], 1.0, places=12)
        # Ratio 3: h = 9, 3, 1 with order 1.
        r = analysis.richardson([2 + 0.1 * h for h in (9, 3, 1)], ratio=3.0)
        self.assertAlmostEqual(r["order"], 1.0, places=12)
        self.assertAlmostEqual(r["value"], 2.0, places=12)
        # Not converging steadily: no order, the finest value and its last change.
        r = analysis.richardson([1.0, 2.0, 1.5])
        self.assertNotEqual(r["order"], r["order"])  # nan
        self.assertEqual((r["value"], r["error"]), (1.5, 0.5))

    def test_first_peak_of_a_parabola(self):
        t = [0.1 * k for k in range(40)]
        x = [1 - (s - 1.234) ** 2 for s in t]
        value, when = analysis.first_peak(t, x)
        self.assertAlmostEqual(value, 1.0, places=12)
        self.assertAlmostEqual(when, 1.234, places=12)
        with self.assertRaises(ValueError):
            analysis.first_peak(t[:12], [s for s in t[:12]])  # still rising


class Study(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_grid_table_plot_and_the_same_bits_as_a_plain_run(self):
        out = os.path.join(self.dir, "s")
        r = cli("study", CASE, "--vary", "l0=0.004,0.002", "--vary", "model=paper,finite_strain",
                "--set", "time.end=0.0005", "--measure", "max:kinetic_energy", "--measure", "final:plate.x",
                "--reference", "final:plate.x=0.0004", "--jobs", "2", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr + r.stdout)
        rows = read_csv(os.path.join(out, "study.csv"))
        self.assertEqual([(x["l0"], x["model"]) for x in rows],
                         [("0.004", "paper"), ("0.004", "finite_strain"), ("0.002", "paper"),
                          ("0.002", "finite_strain")])
        for x in rows:
            self.assertEqual(x["outcome"], "completed")
            self.assertGreater(float(x["max(kinetic_energy)"]), 0)
            self.assertGreater(float(x["final(plate.x)"]), 0)
            self.assertEqual(float(x["error(final(plate.x))"]), abs(float(x["final(plate.x)"]) / 0.0004 - 1))
            self.assertGreater(float(x["wall_seconds"]), 0)
        self.assertTrue(os.path.getsize(os.path.join(out, "study.png")) > 10000)
        self.assertFalse(os.path.exists(os.path.join(out, "richardson.csv")))  # 2 spacings only
        # A point is the command line's run: the same history, byte for byte.
        plain = os.path.join(self.dir, "plain")
        r = cli("run", CASE, "--out", plain, "--set", "time.end=0.0005", "--set", "l0=0.002",
                "--set", "model=finite_strain")
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(plain, "history.csv"), "rb") as a, \
                open(os.path.join(out, "l0=0.002,model=finite_strain", "history.csv"), "rb") as b:
            self.assertEqual(a.read(), b.read())
        # The same study again runs nothing.
        r = cli("study", CASE, "--vary", "l0=0.004,0.002", "--vary", "model=paper,finite_strain",
                "--set", "time.end=0.0005", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.count("skipped"), 4, r.stdout)

    def test_from_python_with_richardson(self):
        result = mpsolid.study(CASE, vary={"l0": [0.004, 0.002, 0.001]},
                               sets=["model=finite_strain", 'time.dt="auto"', "time.end=0.004"],
                               measures=["first_peak:plate.x"], out=os.path.join(self.dir, "p"),
                               jobs=2, log=lambda *_: None)
        self.assertEqual(result.status, 0)
        self.assertEqual(len(result.rows), 3)
        (est,) = [e for e in result.richardson if e["measure"] == "first_peak(plate.x)"]
        peaks = [r["first_peak(plate.x)"] for r in result.rows]
        # The coarse-to-fine changes shrink: a positive order, an estimate
        # beyond the finest value in the direction of the changes.
        self.assertGreater(est["observed_order"], 0.5)
        self.assertLess(abs(est["extrapolated"] - peaks[-1]), abs(peaks[-1] - peaks[-2]))
        self.assertGreater(est["error_bar"], 0)
        for r in result.rows:
            self.assertIn("error(first_peak(plate.x))", r)
        self.assertTrue(os.path.isfile(os.path.join(result.folder, "richardson.csv")))
        # study.md: the equivalent command and both tables, the values as in study.csv.
        with open(os.path.join(result.folder, "study.md")) as f:
            md = f.read()
        self.assertIn("mpsolid study ", md)
        self.assertIn("--vary l0=0.004,0.002,0.001", md)
        self.assertIn("--measure first_peak:plate.x", md)
        self.assertIn(f"| {est['observed_order']:.3g} | {est['extrapolated']:.7g} |", md)
        self.assertIn(f"| 0.002 | completed | 1130 |", md)
        self.assertIn(f"{peaks[1]:.6g}", md)

    def test_bad_input_is_refused_before_anything_runs(self):
        out = os.path.join(self.dir, "bad")
        r = cli("study", CASE, "--vary", "l0=0.002,-1", "--set", "time.end=0.0005", "--out", out)
        self.assertEqual(r.returncode, 2)
        plain = cli("run", CASE, "--set", "l0=-1", "--out", os.path.join(self.dir, "x"))
        self.assertEqual(plain.returncode, 2)
        self.assertIn(plain.stderr.strip().split("mpsolid: error: ")[1], r.stderr)
        self.assertFalse(os.path.exists(out))
        for args, words in ((["--vary", "l0"], "expected KEY=VALUE1"),
                            (["--vary", "l0=0.002", "--measure", "peak:plate.x"], "KIND:COLUMN"),
                            (["--vary", "l0=0.002,0.002"], "listed twice"),
                            (["--vary", "l0=0.002", "--jobs", "0"], "at least 1"),
                            (["--vary", "l0=0.002", "--measure", "final:plate.x", "--reference",
                              "final:plate.x=abc"], "KIND:COLUMN=VALUE"),
                            (["--vary", "l0=0.002", "--measure", "final:plate.x", "--reference",
                              "max:plate.x=1"], "not one of the measures")):
            r = cli("study", CASE, *args, "--out", out)
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(words, r.stderr)
        with self.assertRaises(mpsolid.InputError):
            mpsolid.study(CASE, vary={"no_such_key": [1, 2]}, out=out)

    def test_stopped_half_way_and_resumed(self):
        out = os.path.join(self.dir, "r")
        args = ["study", CASE, "--vary", "l0=0.004,0.0005", "--set", "model=finite_strain",
                "--set", 'time.dt="auto"', "--set", "time.end=0.002", "--threads", "1",
                "--measure", "final:plate.x", "--out", out]
        child = subprocess.Popen([EXE, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        second = os.path.join(out, "l0=0.0005", "checkpoint.h5")
        deadline = time.monotonic() + 60
        while not os.path.exists(second) and child.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)  # the second point has written its first checkpoint
        child.send_signal(signal.SIGINT)
        stdout, stderr = child.communicate(timeout=60)
        self.assertEqual(child.returncode, 4, stdout + stderr)
        rows = read_csv(os.path.join(out, "study.csv"))
        self.assertEqual(rows[0]["outcome"], "completed")
        self.assertEqual(rows[1]["outcome"], "stopped by SIGINT")
        first_mtime = os.path.getmtime(os.path.join(out, "l0=0.004", "run.json"))

        r = subprocess.run([EXE, *args], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("l0=0.004: skipped", r.stdout)
        self.assertEqual(os.path.getmtime(os.path.join(out, "l0=0.004", "run.json")), first_mtime)
        rows = read_csv(os.path.join(out, "study.csv"))
        self.assertEqual([x["outcome"] for x in rows], ["completed", "completed"])
        # Resumed to the same bits as a run that never stopped.
        plain = os.path.join(self.dir, "plain")
        p = cli("run", CASE, "--out", plain, "--threads", "1", "--set", "model=finite_strain",
                "--set", 'time.dt="auto"', "--set", "time.end=0.002", "--set", "l0=0.0005")
        self.assertEqual(p.returncode, 0, p.stderr)
        with open(os.path.join(plain, "history.csv"), "rb") as a, \
                open(os.path.join(out, "l0=0.0005", "history.csv"), "rb") as b:
            self.assertEqual(a.read(), b.read())


if __name__ == "__main__":
    unittest.main(verbosity=2)
