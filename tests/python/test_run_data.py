#!/usr/bin/python3
"""mpsolid.open_run (python/mpsolid/run_data.py) on a short run of the paper's
case: history, frames read lazily, run.json and the resolved case; and the
module's functions the scripts read run folders with (read_info, read_case,
read_history_columns)."""
import csv
import json
import os
import shutil
import subprocess
import tempfile
import unittest
import warnings

import numpy as np

import mpsolid
from mpsolid import run_data
from mpsolid.study import executable

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class ShortRun(unittest.TestCase):
    """A short run of the paper's case in a temporary folder, for the class."""

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


class OpenRun(ShortRun):

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


class ReadFunctions(ShortRun):
    """run_data's functions of a run folder."""

    def test_read_info_and_read_case_are_the_files(self):
        with open(os.path.join(self.dir, "run.json")) as f:
            self.assertEqual(run_data.read_info(self.dir), json.load(f))
        self.assertEqual(run_data.read_info(self.dir), mpsolid.open_run(self.dir).info)
        case = run_data.read_case(self.dir)
        self.assertEqual((case["l0"], case["model"]), (0.002, "paper"))

    def test_a_missing_file_raises_unless_a_default_is_given(self):
        empty = os.path.join(self.tmp.name, "empty")
        os.makedirs(empty, exist_ok=True)
        with self.assertRaises(FileNotFoundError):
            run_data.read_info(empty)
        with self.assertRaises(FileNotFoundError):
            run_data.read_case(empty)
        self.assertIsNone(run_data.read_info(empty, default=None))
        self.assertEqual(run_data.read_case(empty, default={}), {})
        # A run.json cut short (a run killed while starting) counts as absent too.
        with open(os.path.join(empty, "run.json"), "w") as f:
            f.write('{"outcome": "comp')
        with self.assertRaises(ValueError):
            run_data.read_info(empty)
        self.assertEqual(run_data.read_info(empty, default={}), {})

    def test_history_columns_are_the_csv_bits_in_its_order(self):
        columns = run_data.read_history_columns(self.dir)
        with open(os.path.join(self.dir, "history.csv"), newline="") as f:
            rows = list(csv.reader(f))
        self.assertEqual(list(columns), rows[0])
        for k, name in enumerate(rows[0]):
            expected = np.array([float(r[k]) for r in rows[1:]])
            self.assertEqual(columns[name].dtype, np.float64)
            self.assertEqual(columns[name].tobytes(), expected.tobytes(), name)

    def test_a_history_with_only_its_header_has_no_rows(self):
        started = os.path.join(self.tmp.name, "started")
        os.makedirs(started, exist_ok=True)
        with open(os.path.join(self.dir, "history.csv")) as f:
            header = f.readline()
        with open(os.path.join(started, "history.csv"), "w") as f:
            f.write(header)
        with warnings.catch_warnings():
            warnings.simplefilter("error")   # and no warning about it
            columns = run_data.read_history_columns(started)
        self.assertEqual(list(columns), header.strip().split(","))
        self.assertTrue(all(c.size == 0 for c in columns.values()))
        shutil.rmtree(started)


class SpaceRun(unittest.TestCase):
    """A short run in space (cases/spinning_cube.toml, paper model): its frames'
    vectors have three components and the orientation is a unit quaternion."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = os.path.join(cls.tmp.name, "cube")
        r = subprocess.run([executable(), "run", os.path.join(ROOT, "cases", "spinning_cube.toml"),
                            "--out", cls.dir, "--set", "l0=0.008", "--set", 'model="paper"',
                            "--set", "time.end=0.02", "--set", "output.frame_interval=0.01"],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_frames_hold_vectors_in_space_and_unit_quaternions(self):
        run = mpsolid.open_run(self.dir)
        self.assertEqual(run.info["dimension"], 3)
        last = run.frames[-1]
        n = 1000
        for name in ("position", "velocity", "rotation", "angular_velocity", "normal"):
            self.assertEqual(last[name].shape, (n, 3), name)
        q = last.orientation
        self.assertEqual(q.shape, (n, 4))
        self.assertLess(np.abs(np.linalg.norm(q, axis=1) - 1).max(), 1e-14)
        # The rotation vector is the quaternion's angle times its axis.
        angle = 2 * np.arctan2(np.linalg.norm(q[:, 1:], axis=1), q[:, 0])
        axis = q[:, 1:] / np.linalg.norm(q[:, 1:], axis=1)[:, None]
        self.assertLess(np.abs(last.rotation - angle[:, None] * axis).max(), 1e-12)
        # Every particle turned with the body at its spin, about (3, 4, 12) rad/s.
        w = np.array([3.0, 4.0, 12.0])
        self.assertLess(np.abs(angle - np.linalg.norm(w) * last.time).max(), 0.01 * angle.max())
        # A 10^3 cube's surface: all but the 8^3 inside, each with a unit normal.
        surface = last.surface == 1
        self.assertEqual(int(surface.sum()), n - 8 ** 3)
        self.assertLess(np.abs(np.linalg.norm(last.normal[surface], axis=1) - 1).max(), 1e-12)
        self.assertTrue(np.all(last.normal[~surface] == 0))

    def test_pictures_of_a_run_in_space_are_projections_along_z(self):
        from mpsolid import plot
        drawn = plot.plot_run(self.dir, color="strain", frames=3)
        for name in ("frames.png", "history.png"):
            with open(os.path.join(self.dir, name), "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n", name)
        self.assertEqual(len(drawn["frames"]["panels"]), 3)
        # A section: the layer nearest z = 0 (sites at +-4 mm), 10 x 10 particles.
        drawn = plot.plot_run(self.dir, frames=2, section=0.0)
        self.assertAlmostEqual(drawn["frames"]["section_z_m"], -0.004, delta=1e-15)
        with self.assertRaises(plot.PlotError):
            plot.plot_run(self.dir, section=0.5)
        # Across x: the layer nearest x = 1 mm (sites at +-4 mm), drawn in y and z.
        drawn = plot.plot_run(self.dir, frames=2, section="x=0.001")
        self.assertEqual(drawn["frames"]["section"], {"axis": "x", "at_m": 0.004})
        self.assertIsNone(drawn["frames"]["section_z_m"])
        self.assertIn(drawn["frames"]["orientation"], ("y down the page", "y across the page"))
        for bad in ("w=0.0", "x=", "y=abc", "x=0.5"):
            with self.assertRaises(plot.PlotError):
                plot.plot_run(self.dir, section=bad)

    def test_a_blow_up_in_space_names_the_particle_in_three_coordinates(self):
        from mpsolid import plot
        folder = os.path.join(self.tmp.name, "blowup")
        r = subprocess.run([executable(), "run", os.path.join(ROOT, "cases", "spinning_cube.toml"),
                            "--out", folder, "--set", "l0=0.008", "--set", "time.dt=2e-4",
                            "--set", "time.end=0.02", "--set", "stability.check_interval=1"],
                           capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("initial position (", r.stderr + r.stdout)
        info = mpsolid.open_run(folder).info
        self.assertEqual(info["outcome"], "unstable")
        diagnosis = info["diagnosis"]
        self.assertEqual(len(diagnosis["initial_position"]), 3)
        self.assertEqual(len(diagnosis["position"]), 3)
        # The ring goes where the section's axes put the particle.
        drawn = plot.plot_run(folder, frames=2, section="y=0.0")
        ring = drawn["frames"]["panels"][-1].get("ring_mm")
        self.assertIsNotNone(ring)
        self.assertAlmostEqual(ring[0], 1e3 * diagnosis["position"][0], places=9)  # x
        self.assertAlmostEqual(ring[1], 1e3 * diagnosis["position"][2], places=9)  # z

    def test_history_has_the_vector_momenta_and_the_probe_in_space(self):
        run = mpsolid.open_run(self.dir)
        h = run.history_array
        for name in ("momentum_z", "angular_momentum_x", "angular_momentum_y",
                     "angular_momentum_z", "cube.zmin", "cube.zmax", "probe.corner.z"):
            self.assertIn(name, h.dtype.names)
        self.assertNotIn("angular_momentum", h.dtype.names)
        for axis in "xyz":
            column = h["angular_momentum_" + axis]
            self.assertLess(np.abs(column - column[0]).max(), 1e-12 * np.abs(column[0]))
        # The probe is the corner particle (the highest id), as the frame has it.
        last = run.frames[-1]
        corner = last.position[-1]
        for k, axis in enumerate("xyz"):
            self.assertEqual(h["probe.corner." + axis][-1], corner[k])


class RigidSpaceRun(unittest.TestCase):
    """The tumbling brick (cases/tumbling_brick.toml) through its first flip:
    its history's pose columns, the frames at its pose, and history.png's
    panel of the body-axes rates."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = os.path.join(cls.tmp.name, "brick")
        r = subprocess.run([executable(), "run", os.path.join(ROOT, "cases", "tumbling_brick.toml"),
                            "--out", cls.dir, "--set", "time.end=2.5",
                            "--set", "output.frame_interval=0.5"],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_history_holds_the_pose_and_the_flip(self):
        from mpsolid import plot
        run = mpsolid.open_run(self.dir)
        h = run.history_array
        for name in ("brick.x", "brick.y", "brick.z", "brick.qw", "brick.qx", "brick.qy",
                     "brick.qz", "brick.omega_x", "brick.omega_y", "brick.omega_z"):
            self.assertIn(name, h.dtype.names)
        self.assertNotIn("brick.theta", h.dtype.names)
        q = np.stack([h["brick.q" + a] for a in "wxyz"], axis=1)
        self.assertLess(np.abs(np.linalg.norm(q, axis=1) - 1).max(), 1e-14)
        # In its own axes the spin about y goes from +10 to -10 rad/s.
        columns = {c: h[c] for c in h.dtype.names}
        _, about_y, _ = plot.body_axes_rates(columns, "brick")
        self.assertAlmostEqual(about_y[0], 10.0, delta=1e-9)
        self.assertLess(about_y[-1], -9.9)
        # The last frame's particles sit at the pose: the quaternion of every
        # particle is the body's, and their centroid the body's.
        last = run.frames[-1]
        self.assertLess(np.abs(last.orientation - q[-1]).max(), 1e-15)
        self.assertLess(np.abs(last.position.mean(axis=0)).max(), 1e-15)
        drawn = plot.plot_run(self.dir, frames=2)
        names = [p["name"] for p in drawn["history"]["panels"]]
        self.assertIn("spin", names)
        self.assertNotIn("rigid", names)  # it does not move


if __name__ == "__main__":
    unittest.main(verbosity=2)
