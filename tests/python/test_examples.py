#!/usr/bin/python3
"""Each script in examples/ runs, on a shortened case, and writes what it says."""
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLES = os.path.join(ROOT, "examples")


def example(name, *args, cwd):
    r = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), *args], capture_output=True,
                       text=True, cwd=cwd)
    assert r.returncode == 0, f"{name}: exit {r.returncode}\n{r.stdout}\n{r.stderr}"
    return r.stdout


class Examples(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_paper_case_and_its_outline(self):
        out = os.path.join(self.dir, "paper")
        text = example("paper_case.py", "--end", "0.0005", "--out", out, cwd=self.dir)
        self.assertIn("no first peak yet", text)  # 0.5 ms: still rising
        self.assertTrue(os.path.getsize(os.path.join(out, "plate.png")) > 5000)
        text = example("deformed_outline.py", out, "--time", "0.0005", cwd=self.dir)
        self.assertIn("136 boundary particles", text)  # 50 x 20 rod: 2 (50 + 20) - 4
        self.assertTrue(os.path.isfile(os.path.join(out, "outline.png")))

    def test_compare_models(self):
        out = os.path.join(self.dir, "models")
        text = example("compare_models.py", "--end", "0.0004", "--out", out, cwd=self.dir)
        for model in ("paper", "paper_conservative", "finite_strain"):
            self.assertIn(model, text)
            self.assertTrue(os.path.isfile(os.path.join(out, model, "history.csv")))
        self.assertTrue(os.path.isfile(os.path.join(out, "models.png")))

    def test_resolution_study(self):
        out = os.path.join(self.dir, "study")
        text = example("resolution_study.py", "--l0", "0.004", "0.002", "0.001", "--end", "0.004",
                       "--jobs", "2", "--out", out, cwd=self.dir)
        self.assertIn("observed order", text)
        self.assertTrue(os.path.isfile(os.path.join(out, "study.csv")))


if __name__ == "__main__":
    unittest.main(verbosity=2)
