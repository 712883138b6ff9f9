"""Builds the package mpsolid with CMake for `pip install .` (pyproject.toml).

CMake builds the extension _mpsolid and the mpsolid executable for the
interpreter that runs pip, then installs the package, with the executable
inside it (MPSOLID_PYTHON_BUNDLE_EXECUTABLE), into a staging folder; that
package is what the wheel holds. MPSOLID_CMAKE_ARGS adds configure options,
e.g. MPSOLID_CMAKE_ARGS=-DMPSOLID_ARCH=x86-64-v3 for a portable build.
"""
import os
import pathlib
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        temp = pathlib.Path(self.build_temp).resolve()
        build, stage = temp / "cmake", temp / "stage"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}",
            "-DMPSOLID_BUILD_TESTS=OFF", "-DMPSOLID_BUILD_BENCH=OFF",
            "-DMPSOLID_PYTHON_BUNDLE_EXECUTABLE=ON",
            "-DMPSOLID_PYTHON_INSTALL_DIR=python",
            f"-DCMAKE_INSTALL_PREFIX={stage}",
            *shlex.split(os.environ.get("MPSOLID_CMAKE_ARGS", "")),
        ]
        subprocess.run(configure, check=True)
        jobs = str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build), "-j", jobs], check=True)
        shutil.rmtree(stage, ignore_errors=True)
        subprocess.run(["cmake", "--install", str(build)], check=True)
        package = pathlib.Path(self.get_ext_fullpath(ext.name)).parent
        shutil.copytree(stage / "python" / "mpsolid", package, dirs_exist_ok=True)


setup(
    packages=["mpsolid"],
    package_dir={"mpsolid": "python/mpsolid"},
    ext_modules=[Extension("mpsolid._mpsolid", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)
