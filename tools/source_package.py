"""The source tree's mpsolid package for the scripts of tools/ and bench/,
which run with Debian's /usr/bin/python3 and need no build: its pure-Python
modules (run_data, analysis, plot) import as mpsolid.NAME although the
package's __init__ loads the compiled extension. And the one line a script
prints where this Python lacks a library it needs."""
import importlib
import importlib.machinery
import importlib.util
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PACKAGE_DIR = os.path.join(ROOT, "python", "mpsolid")
DEBIAN_PACKAGES = {"numpy": "python3-numpy", "h5py": "python3-h5py",
                   "matplotlib": "python3-matplotlib"}


def mpsolid_module(name):
    """mpsolid.NAME from python/mpsolid/, without running the package's
    __init__ (it needs the build): the package is entered as a bare package
    over that folder, so that the modules' relative imports work."""
    if "mpsolid" not in sys.modules:
        spec = importlib.machinery.ModuleSpec("mpsolid", None, is_package=True)
        spec.submodule_search_locations = [PACKAGE_DIR]
        sys.modules["mpsolid"] = importlib.util.module_from_spec(spec)
    return importlib.import_module(f"mpsolid.{name}")


def require_libraries(script, names=("numpy", "h5py", "matplotlib")):
    """Exits 2 with one line, not a traceback, when this Python lacks one of
    the libraries: the Debian packages to install, or /usr/bin/python3 to
    run `script` (its path from the repository root) with."""
    missing = []
    for name in names:
        try:
            __import__(name)
        except ImportError:
            missing.append(name)
    if missing:
        packages = " and ".join(DEBIAN_PACKAGES[m] for m in missing)
        print(f"{os.path.basename(script)}: this Python ({sys.executable}) has no "
              f"{', '.join(missing)}: install {packages} (apt-get install "
              f"{packages.replace(' and ', ' ')}) or run it with Debian's /usr/bin/python3 "
              f"{script} ...", file=sys.stderr)
        sys.exit(2)
