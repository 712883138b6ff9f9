#!/usr/bin/python3
"""The Python module mpsolid (python/, docs/python.md) against the command line.

    PYTHONPATH=build/release/python /usr/bin/python3 tests/python/test_bindings.py

(ctest `python_bindings` sets PYTHONPATH.) Run from the repository root or
anywhere: cases are found relative to this file. The cases are shortened
shock_rod runs (l0 = 4 mm, 290 particles, or the case's 2 mm, 1130).
"""
import gc
import json
import os
import pathlib
import signal
import subprocess
import sys
import tempfile
import textwrap
import threading
import time
import unittest

import h5py
import numpy as np

import mpsolid

ROOT = pathlib.Path(__file__).resolve().parents[2]
CASE = str(ROOT / "cases" / "shock_rod.toml")
EXE = mpsolid.MPSOLID_EXECUTABLE
STATE = ["x", "y", "vx", "vy", "theta", "omega", "pressure", "strain", "fx", "fy", "torque"]
# Every array of the particle table is a view; these are the documented ones.
# The arrays of a 2D simulation: every row but the third components.
VIEWS = [n for n in mpsolid.PARTICLE_ARRAYS if n not in mpsolid.SPACE_ONLY_ARRAYS]
assert set(STATE + ["x0", "y0", "ids", "bodies", "materials", "kinds"]) <= set(VIEWS)


def coarse_case(end=1e-4):
    return mpsolid.Case.load(CASE).set("l0", 0.004).set("time.end", end)


def cli(*args, cwd=None):
    """The command line's exit code, stdout and stderr."""
    env = dict(os.environ, OMP_WAIT_POLICY="PASSIVE")
    p = subprocess.run([EXE, *args], capture_output=True, text=True, cwd=cwd, env=env)
    return p.returncode, p.stdout, p.stderr


def cli_error(*args):
    """What the command line prints after 'mpsolid: error: ' (it must exit 2)."""
    code, _, err = cli(*args)
    assert code == 2, (code, err)
    line = next(l for l in err.splitlines() if l.startswith("mpsolid: error: "))
    return line[len("mpsolid: error: "):]


def state_in_id_order(sim):
    order = np.argsort(sim.ids)
    return {name: getattr(sim, name)[order] for name in STATE}


def child(script, *args):
    """A Python child process running `script` with the module importable."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path), OMP_WAIT_POLICY="PASSIVE")
    return subprocess.Popen([sys.executable, "-c", textwrap.dedent(script), *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)


class TempDirTest(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="mpsolid_py.")
        self.tmp = pathlib.Path(self._tmp.name)

    def tearDown(self):
        self._tmp.cleanup()


class ZeroCopyViews(unittest.TestCase):
    def test_views_are_the_store(self):
        sim = mpsolid.Simulation(coarse_case(), threads=1)
        for name in VIEWS:
            a = getattr(sim, name)
            self.assertEqual(a.__array_interface__["data"][0], sim._address(name), name)
            self.assertEqual(a.shape, (sim.particle_count,), name)
            self.assertFalse(a.flags.writeable, name)
            self.assertFalse(a.flags.owndata, name)
            self.assertIs(a.base, sim, name)
        self.assertEqual(sim.x.dtype, np.float64)
        self.assertEqual(sim.ids.dtype, np.int32)
        self.assertEqual(sim.kinds.dtype, np.int8)
        with self.assertRaises(ValueError):
            sim.x[0] = 1.0
        self.assertLessEqual({"z", "vz", "z0", "fz", "qw", "omega_x"},
                             set(mpsolid.SPACE_ONLY_ARRAYS))
        self.assertLessEqual({"theta", "half_cos"}, set(mpsolid.PLANE_ONLY_ARRAYS))
        for name in mpsolid.SPACE_ONLY_ARRAYS:
            with self.assertRaisesRegex(AttributeError, f"2D simulation has no {name}"):
                getattr(sim, name)

    def test_views_follow_the_state_and_keep_it_alive(self):
        sim = mpsolid.Simulation(coarse_case(), threads=1)
        x, pressure = sim.x, sim.pressure
        before = x.copy()
        sim.advance(300)
        self.assertFalse(np.array_equal(x, before))  # the same view, new values
        self.assertTrue(np.array_equal(pressure, sim.pressure))
        self.assertTrue(np.any(pressure != 0))  # fields refreshed after stepping
        after = x.copy()
        del sim
        gc.collect()
        self.assertTrue(np.array_equal(x, after))  # the store lives while the view does

    def test_every_state_array_reaches_the_checkpoint(self):
        """The table's state arrays are what a checkpoint holds, and each
        one read from the file is the view of a Simulation at that step."""
        state = [n for n, role in mpsolid.PARTICLE_ARRAYS.items()
                 if role == "state" and n not in mpsolid.SPACE_ONLY_ARRAYS]
        self.assertLessEqual({"x", "y", "vx", "vy", "theta", "omega"}, set(state))
        with tempfile.TemporaryDirectory(prefix="mpsolid_py.") as tmp:
            code, _, err = cli("run", CASE, "--set", "l0=0.004", "--set", "time.end=2e-05",
                               "--threads", "1", "--out", tmp)
            self.assertEqual(code, 0, err)
            with h5py.File(pathlib.Path(tmp) / "checkpoint.h5") as f:
                stored = {n: f["particles"][n][()] for n in f["particles"] if n != "_order"}
        self.assertEqual(set(stored), set(state))
        sim = mpsolid.Simulation(coarse_case(2e-5), threads=1)
        sim.run_to(2e-5)
        order = np.argsort(sim.ids)
        for name in state:
            self.assertTrue(np.array_equal(getattr(sim, name)[order], stored[name]), name)

    def test_ids_kinds_bodies(self):
        sim = mpsolid.Simulation(coarse_case(), threads=1)
        self.assertTrue(np.array_equal(np.sort(sim.ids), np.arange(sim.particle_count)))
        self.assertEqual(mpsolid.KIND_NAMES, {0: "wall", 1: "elastic", 2: "rigid"})
        for kind, (begin, end) in sim.ranges.items():
            names = {mpsolid.KIND_NAMES[int(k)] for k in sim.kinds[begin:end]}
            self.assertLessEqual(names, {kind})
        self.assertEqual(sorted(sim.body_names), ["plate", "rod", "wall"])
        rod = sim.body_names.index("rod")
        self.assertEqual(int(np.sum(sim.bodies == rod)), 25 * 10)


class SameBits(TempDirTest):
    def test_simulation_matches_the_command_line(self):
        end = "2e-05"
        code, _, err = cli("run", CASE, "--set", f"time.end={end}", "--threads", "1",
                           "--out", str(self.tmp / "cli"))
        self.assertEqual(code, 0, err)
        with h5py.File(self.tmp / "cli" / "frames.h5") as f:
            frame = f["frames"][sorted(f["frames"])[-1]]
            step = int(frame.attrs["step"])
            ids = frame["id"][:]
            cli_state = {"x": frame["position"][:, 0], "y": frame["position"][:, 1],
                         "vx": frame["velocity"][:, 0], "vy": frame["velocity"][:, 1],
                         "theta": frame["rotation"][:], "omega": frame["angular_velocity"][:],
                         "pressure": frame["pressure"][:], "strain": frame["volumetric_strain"][:]}
        self.assertTrue(np.array_equal(ids, np.arange(len(ids))))
        self.assertEqual(step, 2000)
        case = mpsolid.Case.load(CASE).set("time.end", float(end))
        for threads in (1, 2):
            sim = mpsolid.Simulation(case, threads=threads)
            sim.advance(step)
            mine = state_in_id_order(sim)
            for name, values in cli_state.items():
                self.assertTrue(np.array_equal(mine[name], values), f"{name}, {threads} threads")

    def test_run_matches_the_command_line(self):
        code, _, err = cli("run", CASE, "--set", "l0=0.004", "--set", "time.end=0.0001",
                           "--threads", "1", "--out", str(self.tmp / "cli"))
        self.assertEqual(code, 0, err)
        out = self.tmp / "py"
        self.assertEqual(mpsolid.run(coarse_case(), out=out, threads=1, progress=False), 0)
        for name in ("history.csv", "case.resolved.toml"):
            self.assertEqual((out / name).read_bytes(), (self.tmp / "cli" / name).read_bytes(), name)
        report = json.loads((out / "run.json").read_text())
        self.assertEqual(report["overrides"], ["l0=0.004", "time.end=0.0001"])
        self.assertTrue(report["command_line"].startswith("python: mpsolid.run("))
        # A second run into the same folder is refused with the command line's words.
        with self.assertRaises(mpsolid.InputError) as e:
            mpsolid.run(coarse_case(), out=out, threads=1)
        self.assertEqual(str(e.exception),
                         cli_error("run", CASE, "--set", "l0=0.004", "--set", "time.end=0.0001",
                                   "--out", str(out)))

    def test_batches_and_threads_change_no_bit(self):
        case = coarse_case()
        whole = mpsolid.Simulation(case, threads=1)
        whole.advance(2500)
        pieces = mpsolid.Simulation(case, threads=2)
        for steps in (1, 999, 0, 1000, 500):
            pieces.advance(steps)
        self.assertEqual(pieces.step, 2500)
        for name in STATE:
            self.assertTrue(np.array_equal(getattr(whole, name), getattr(pieces, name)), name)
        self.assertEqual(whole.diagnostics(), pieces.diagnostics())

    def test_contact_shows_in_the_diagnostics(self):
        case = mpsolid.Case.load(str(ROOT / "cases" / "colliding_blocks.toml")).set("time.end", 2e-3)
        sim = mpsolid.Simulation(case, threads=2)
        start = sim.diagnostics()
        self.assertEqual(start["contact_energy"], 0.0)
        self.assertAlmostEqual(start["contact_min_distance"], 5 ** 0.5 * 1e-3, places=12)
        touched = 0.0
        while sim.time < 1.5e-3:  # the blocks meet near 1 ms
            sim.advance(20)
            touched = max(touched, sim.diagnostics()["contact_energy"])
        self.assertGreater(touched, 0.0)
        no_contact = mpsolid.Simulation(coarse_case(), threads=1)
        self.assertEqual(no_contact.diagnostics()["contact_energy"], 0.0)

    def test_run_to(self):
        sim = mpsolid.Simulation(coarse_case(), threads=1)
        sim.run_to(1.5e-6 + 1e-12)  # 150.0001 steps of 10 ns: the first step at or after is 151
        self.assertEqual(sim.step, 151)
        sim.run_to(sim.time)
        self.assertEqual(sim.step, 151)
        with self.assertRaises(ValueError):
            sim.run_to(1e-6)
        with self.assertRaises(ValueError):
            sim.advance(-1)
        sim.run_to(2e-4)  # past the case's end (1e-4 s) is allowed
        self.assertEqual(sim.step, 20000)


class Errors(unittest.TestCase):
    def test_messages_are_the_command_lines(self):
        for key, value, text in [("l0", -1, "l0=-1"), ("bogus.key", 1, "bogus.key=1"),
                                 ("model", "nope", 'model="nope"')]:
            case = mpsolid.Case.load(CASE).set("time.end", 1e-05)
            with self.assertRaises(mpsolid.InputError) as e:
                case.set(key, value)
            self.assertEqual(str(e.exception),
                             cli_error("run", CASE, "--set", "time.end=1e-05", "--set", text))
            self.assertEqual(case.overrides, ["time.end=1e-05"])  # unchanged
            self.assertEqual(case.end_time, 1e-05)
        missing = str(ROOT / "cases" / "no_such_case.toml")
        with self.assertRaises(mpsolid.InputError) as e:
            mpsolid.Case.load(missing)
        self.assertEqual(str(e.exception), cli_error("run", missing))
        self.assertTrue(issubclass(mpsolid.InputError, ValueError))

    def test_bad_values(self):
        case = coarse_case()
        with self.assertRaises(TypeError):
            case.set("l0", object())
        with self.assertRaises(mpsolid.InputError):
            mpsolid.Simulation(case, threads=0)
        with self.assertRaises(mpsolid.InputError):
            mpsolid.Case.from_text("l0 = [", name="broken.toml")


class CaseValues(unittest.TestCase):
    def test_python_values_become_toml(self):
        case = mpsolid.Case.load(CASE)
        case.set("time.end", 1e-05).set("l0", np.float64(0.004))
        case.set("bodies.rod.x", (0.0, 0.05)).set("name", 'rod "short"\t\\')
        case.set("numerics.flush_subnormals", True).set("stability.check_interval", np.int64(250))
        self.assertEqual(case.overrides,
                         ["time.end=1e-05", "l0=0.004", "bodies.rod.x=[0.0, 0.05]",
                          'name="rod \\"short\\"\\u0009\\\\"', "numerics.flush_subnormals=true",
                          "stability.check_interval=250"])
        resolved = case.resolved()
        self.assertEqual(resolved["bodies"]["rod"]["x"], [0.0, 0.05])
        self.assertEqual(resolved["name"], 'rod "short"\t\\')
        self.assertEqual(case.name, 'rod "short"\t\\')
        self.assertEqual((case.l0, case.end_time, case.dt, case.model), (0.004, 1e-05, 1e-08, "paper"))
        again = mpsolid.Case.from_text(case.resolved_toml(), name="resolved.toml")
        self.assertEqual(again.resolved(), resolved)
        self.assertIn("overrides=", repr(case))
        with self.assertRaises(mpsolid.InputError):
            case.set("time.end", float("inf"))  # valid TOML, refused by the reader

    def test_shapes_and_histories_from_python(self):
        # A disk with a hole, a polygon, and a ramped load, all set as Python values.
        case = coarse_case()
        case.set("bodies.ball", {"kind": "elastic", "material": "rubber", "shape": "circle",
                                 "center": [0.2, 0.0], "radius": 0.012,
                                 "holes": [{"shape": "circle", "center": [0.2, 0.0],
                                            "radius": 0.004}]})
        case.set("bodies.wedge", {"kind": "rigid", "material": "rubber", "shape": "polygon",
                                  "vertices": [(0.3, 0.0), (0.34, 0.0), (0.3, 0.03)]})
        case.set("loads.shock", {"type": "step", "body": "plate", "force": [11200.0, 0.0],
                                 "history": "ramp", "rise_time": 1e-6})
        resolved = case.resolved()
        self.assertEqual(resolved["bodies"]["ball"]["shape"], "circle")
        self.assertEqual(resolved["bodies"]["ball"]["holes"][0]["radius"], 0.004)
        self.assertEqual(resolved["bodies"]["wedge"]["vertices"][1], [0.34, 0.0])
        self.assertEqual(resolved["loads"]["shock"]["history"], "ramp")
        plain = mpsolid.Simulation(coarse_case(), threads=1)
        sim = mpsolid.Simulation(case, threads=1)
        self.assertGreater(sim.particle_count, plain.particle_count)
        with self.assertRaises(mpsolid.InputError):  # a bow tie
            case.copy().set("bodies.wedge.vertices", [(0.3, 0.0), (0.34, 0.03), (0.34, 0.0),
                                                      (0.3, 0.03)]).resolved()

    def test_pressure_damping_and_motion_from_python(self):
        # A pressure on the plate's face, damping, and a driven wall, as Python values.
        case = coarse_case()
        case.set("loads.shock", {"type": "pressure", "body": "plate", "pressure": 1.8e5,
                                 "face": "left", "history": "ramp", "rise_time": 1e-6})
        case.set("damping", {"coefficient": 1000.0, "end": 5e-6})
        case.set("bodies.wall.motion", {"velocity": [-0.5, 0.0]})
        resolved = case.resolved()
        self.assertEqual(resolved["loads"]["shock"]["face"], "left")
        self.assertEqual(resolved["damping"]["end"], 5e-6)
        self.assertEqual(resolved["bodies"]["wall"]["kind"], "rigid")  # a driven wall
        self.assertEqual(resolved["bodies"]["wall"]["motion"]["velocity"], [-0.5, 0.0])
        again = mpsolid.Case.from_text(case.resolved_toml(), name="resolved.toml")
        self.assertEqual(again.resolved(), resolved)
        sim = mpsolid.Simulation(case, threads=1)
        sim.advance(200)
        self.assertGreater(sim.diagnostics()["external_work"], 0.0)
        with self.assertRaises(mpsolid.InputError):  # a rectangle has no such face
            case.copy().set("loads.shock.face", "front").resolved()

    def test_copy_is_independent(self):
        case = coarse_case()
        other = case.copy().set("l0", 0.002)
        self.assertEqual((case.l0, other.l0), (0.004, 0.002))


class Threads(unittest.TestCase):
    def test_gil_released_while_stepping(self):
        sim = mpsolid.Simulation(mpsolid.Case.load(CASE), threads=1)  # 1130 particles
        counter = [0]
        done = threading.Event()
        seen = {}

        def step():
            start = counter[0]
            begun = time.monotonic()
            sim.advance(5000)
            seen.update(ticks=counter[0] - start, seconds=time.monotonic() - begun)
            done.set()

        worker = threading.Thread(target=step)
        worker.start()
        while not done.is_set():
            counter[0] += 1
            time.sleep(0.001)
        worker.join()
        # Holding the GIL, advance would let this loop run once at most.
        self.assertGreater(seen["ticks"], 10, seen)

    def test_ctrl_c_stops_advance_at_a_batch(self):
        script = """
            import sys, time
            import numpy as np
            import mpsolid
            case = mpsolid.Case.load(sys.argv[1]).set("l0", 0.004)
            sim = mpsolid.Simulation(case, threads=1)
            print("started", flush=True)
            try:
                sim.advance(10**12)
            except KeyboardInterrupt:
                caught = time.monotonic()
                ref = mpsolid.Simulation(case, threads=1)
                ref.advance(sim.step)
                same = all(np.array_equal(getattr(sim, n), getattr(ref, n))
                           for n in ("x", "y", "vx", "vy", "theta", "omega", "pressure"))
                print("interrupted", sim.step, sim.batch_steps, same, caught, flush=True)
        """
        p = child(script, CASE)
        try:
            self.assertEqual(p.stdout.readline().strip(), "started")
            time.sleep(0.5)  # well inside advance
            sent = time.monotonic()
            p.send_signal(signal.SIGINT)
            out, err = p.communicate(timeout=60)
        finally:
            p.kill()
        self.assertEqual(p.returncode, 0, err)
        word, step, batch, same, caught = out.split()
        self.assertEqual(word, "interrupted")
        self.assertEqual(int(step) % int(batch), 0)
        self.assertGreater(int(step), 0)
        self.assertEqual(same, "True")  # a consistent state, on the step grid
        self.assertLess(float(caught) - sent, 5.0)

    def test_ctrl_c_stops_run_and_resume_finishes_it(self):
        script = """
            import json, os, pathlib, signal, sys, time
            import mpsolid
            out = pathlib.Path(sys.argv[2])
            case = mpsolid.Case.load(sys.argv[1]).set("l0", 0.004).set("time.end", 1.0)
            code = mpsolid.run(case, out=out, threads=1, progress=False)
            print("code", code, flush=True)
            try:  # Python's handler is back: a SIGINT is a KeyboardInterrupt again
                os.kill(os.getpid(), signal.SIGINT)
                time.sleep(5)
                print("no KeyboardInterrupt", flush=True)
            except KeyboardInterrupt:
                print("handler restored", flush=True)
            stopped = json.loads((out / "run.json").read_text())
            print("stopped", stopped["outcome"], stopped["final_step"], flush=True)
            end = (stopped["final_step"] + 500) * stopped["dt"]
            print("resumed", mpsolid.resume(out, threads=1, end_time=end, progress=False),
                  json.loads((out / "run.json").read_text())["final_step"], flush=True)
        """
        with tempfile.TemporaryDirectory(prefix="mpsolid_py.") as tmp:
            out = pathlib.Path(tmp) / "run"
            p = child(script, CASE, str(out))
            try:
                deadline = time.monotonic() + 60
                while not (out / "checkpoint.h5").exists():  # the stop handlers are in place
                    self.assertLess(time.monotonic(), deadline, "no checkpoint.h5")
                    self.assertIsNone(p.poll(), p.stderr.read() if p.poll() is not None else "")
                    time.sleep(0.05)
                time.sleep(0.3)
                p.send_signal(signal.SIGINT)
                stdout, stderr = p.communicate(timeout=60)
            finally:
                p.kill()
            self.assertEqual(p.returncode, 0, stderr)
            # The run's own summary (C stdout) comes first on the same pipe.
            lines = [l for l in stdout.split("\n") if not l.startswith(("mpsolid:", "  "))]
            self.assertEqual(lines[0], "code 4", stdout + stderr)
            self.assertEqual(lines[1], "handler restored")
            word, *outcome, final = lines[2].split()
            self.assertEqual(" ".join(outcome), "stopped by SIGINT")
            self.assertIn("mpsolid resume", stderr)
            self.assertEqual(lines[3].split(), ["resumed", "0", str(int(final) + 500)])


class Gas(TempDirTest):
    """The gas's views and figures, and open_run's gas fields, against the
    command line's run of the same case (the Giordano panel, coarse, the
    shock started 2 mm from the panel)."""

    SETS = {"gas.cell": 0.001, "gas.shock.x": -0.002, "time.end": 2e-5,
            "output.frame_interval": 1e-5}

    def case(self):
        case = mpsolid.Case.load(str(ROOT / "cases" / "giordano_panel.toml"))
        for key, value in self.SETS.items():
            case = case.set(key, value)
        return case

    def test_views_fields_and_figures_match_the_command_line(self):
        sim = mpsolid.Simulation(self.case(), threads=1)
        self.assertIsNone(mpsolid.Simulation(coarse_case(), threads=1).gas_fields())
        sim.run_to(2e-5)
        q = sim.gas_conserved
        self.assertEqual(q["rho"].shape, (65 + 4, 300 + 4))
        self.assertFalse(q["rho"].flags.writeable)
        fields = sim.gas_fields()
        rho = fields["density"]
        self.assertEqual(rho.shape, (65, 300))
        gas_cells = fields["solid"] == 0
        # The views hold the same gas: interior cells, ghosts stripped.
        np.testing.assert_array_equal(q["rho"][2:-2, 2:-2][gas_cells], rho[gas_cells])
        self.assertTrue(np.isnan(rho[fields["solid"] == 1]).all())
        d = sim.diagnostics()["gas"]
        self.assertGreater(d["steps"], 0)
        self.assertIn("top_wall_10mm_upstream", d["probes"])
        # The command line's last frame and history row are the same bits.
        out = os.path.join(self.tmp, "gas")
        args = [f"{k}={v}" for k, v in self.SETS.items()]
        code, _, err = cli("run", str(ROOT / "cases" / "giordano_panel.toml"), "--out", out,
                           "--threads", "1", *sum((["--set", a] for a in args), []))
        self.assertEqual(code, 0, err)
        run = mpsolid.open_run(out)
        last = run.frames[-1]
        np.testing.assert_array_equal(last.gas("density"), rho)
        self.assertEqual(last.gas("velocity").shape, (65, 300, 2))
        self.assertEqual(run.frames.gas_grid["nx"], 300)
        self.assertEqual(run.history_array["gas.energy"][-1], d["energy"])


class Version(unittest.TestCase):
    def test_version_is_the_command_lines(self):
        code, out, _ = cli("--version")
        self.assertEqual(code, 0)
        v = mpsolid.version()
        self.assertEqual(v["text"], out.strip())
        self.assertEqual(v["version"], mpsolid.__version__)


if __name__ == "__main__":
    unittest.main()
