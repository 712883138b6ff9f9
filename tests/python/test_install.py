#!/usr/bin/python3
"""cmake --install: the installed executable finds the installed package for
`mpsolid study` (src/app/study_launcher.cpp) with no PYTHONPATH set, and the
installed package finds the installed executable (_build_paths.py).
Usage: test_install.py BUILD_DIR (ctest passes it)."""
import glob
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASE = os.path.join(ROOT, "cases", "shock_rod.toml")
BUILD = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(ROOT, "build", "release")


class Installed(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.prefix = os.path.join(cls.tmp.name, "prefix")
        r = subprocess.run(["cmake", "--install", BUILD, "--prefix", cls.prefix],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stdout + r.stderr
        cls.exe = os.path.join(cls.prefix, "bin", "mpsolid")
        (study_py,) = glob.glob(os.path.join(cls.prefix, "**", "mpsolid", "study.py"), recursive=True)
        cls.site = os.path.dirname(os.path.dirname(study_py))
        # Nothing from the build tree: no PYTHONPATH, no executable override.
        cls.env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MPSOLID_EXECUTABLE")}

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_the_package_lands_where_the_interpreter_looks_below_the_prefix(self):
        self.assertTrue(self.site.startswith(self.prefix + os.sep))
        self.assertTrue(glob.glob(os.path.join(self.site, "mpsolid", "_mpsolid*.so")))

    def test_the_installed_package_runs_the_installed_executable(self):
        r = subprocess.run([sys.executable, "-c", "import mpsolid; print(mpsolid.MPSOLID_EXECUTABLE)"],
                           capture_output=True, text=True, env={**self.env, "PYTHONPATH": self.site},
                           cwd=self.tmp.name)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.strip(), self.exe)

    def test_installed_study_without_pythonpath(self):
        out = os.path.join(self.tmp.name, "study")
        r = subprocess.run([self.exe, "study", CASE, "--vary", "l0=0.004", "--set", "time.end=0.0002",
                            "--measure", "final:plate.x", "--out", out],
                           capture_output=True, text=True, env=self.env, cwd=self.tmp.name)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertTrue(os.path.isfile(os.path.join(out, "study.csv")))
        with open(os.path.join(out, "l0=0.004", "run.json")) as f:
            self.assertIn("completed", f.read())
        # The installed package ran it, with the installed executable.
        with open(os.path.join(out, "study.json")) as f:
            provenance = json.load(f)
        self.assertEqual(provenance["package"], os.path.join(self.site, "mpsolid"))
        self.assertEqual(provenance["executable"], self.exe)


if __name__ == "__main__":
    unittest.main()
