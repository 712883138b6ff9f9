"""mpsolid: the elastic MPS solver from Python (docs/python.md).

    import mpsolid
    case = mpsolid.Case.load("cases/shock_rod.toml").set("time.end", 1e-4)
    sim = mpsolid.Simulation(case, threads=2)
    sim.run_to(5e-5)
    sim.x, sim.diagnostics()["kinetic_energy"]

The compiled part is the extension _mpsolid; this package re-exports it.
"""
from ._mpsolid import (
    KIND_NAMES,
    PARTICLE_ARRAYS,
    PLANE_ONLY_ARRAYS,
    SPACE_ONLY_ARRAYS,
    Case,
    InputError,
    Simulation,
    __version__,
    resume,
    run,
    toml_value,
    version,
)
from ._build_paths import MPSOLID_EXECUTABLE

# --- Pure-Python parts (written on their own; add their imports here) ---
from .run_data import Run, open_run
from .study import StudyError, StudyResult, study
# --- end of the pure-Python parts ---

__all__ = [
    "Case",
    "InputError",
    "KIND_NAMES",
    "PARTICLE_ARRAYS",
    "PLANE_ONLY_ARRAYS",
    "SPACE_ONLY_ARRAYS",
    "MPSOLID_EXECUTABLE",
    "Simulation",
    "__version__",
    "resume",
    "run",
    "version",
    "toml_value",
    "open_run",
    "Run",
    "study",
    "StudyResult",
    "StudyError",
]
