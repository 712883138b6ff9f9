#!/usr/bin/python3
"""mpsolid.open_run (python/mpsolid/run_data.py) on a short run of the paper's
case: history, frames read lazily, run.json and the resolved case."""
import csv
import os
import subprocess
import tempfile
import unittest

import numpy as np

import mpsolid
from mpsolid.study import executable

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class OpenRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = os.path.join(cls.tmp.name, "run")
        r = subprocess.run([executable(), "run", os.path.join(ROOT, "cases", "shock_rod.toml"), "--out",
                            cls.dir, "--set", "time.end=0.0004", "--set", "output.frame_interval=0.0002"],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_history_is_the_csv(self):
        run = mpsolid.open_run(self.dir)
        h = run.history_array
        with open(os.path.join(self.dir, "history.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual(list(h.dtype.names), list(rows[0].keys()))
        self.assertEqual(len(h), len(rows))
        for name in ("t", "plate.x", "kinetic_energy"):
            self.assertTrue(np.array_equal(h[name], [float(r[name]) for r in rows]), name)
        self.assertIs(type(run.history["plate.x"]), type(h["plate.x"]))  # no pandas here: the array

    def test_frames_are_read_lazily_and_in_id_order(self):
        run = mpsolid.open_run(self.dir)
        frames = run.frames
        self.assertEqual(len(frames), 3)
        self.assertEqual([f.step for f in frames], [0, 20000, 40000])
        self.assertEqual(frames.body_names, ["plate", "rod", "wall"])
        last = frames[-1]
        self.assertEqual(last._fields, {})  # nothing read yet
        self.assertEqual(last.position.shape, (1130, 2))
        self.assertTrue(np.array_equal(last.id, np.arange(1130)))
        self.assertIn("pressure", last.fields())
        self.assertIs(frames.at_time(0.00021), frames[1])
        with self.assertRaises(KeyError):
            last["no_such_field"]
        # The plate's mean x in the last frame is the history's plate.x plus its start.
        plate = last.body == frames.body_names.index("plate")
        start = frames[0].position[plate, 0].mean()
        self.assertAlmostEqual(last.position[plate, 0].mean() - start, run.history_array["plate.x"][-1],
                               delta=1e-12)

    def test_info_and_case(self):
        run = mpsolid.open_run(self.dir)
        self.assertEqual(run.info["outcome"], "completed")
        self.assertEqual(run.outcome, "completed")
        self.assertEqual(run.case["l0"], 0.002)
        self.assertIn("completed", repr(run))
        with self.assertRaises(FileNotFoundError):
            mpsolid.open_run(os.path.join(self.dir, "nothing"))


if __name__ == "__main__":
    unittest.main(verbosity=2)
