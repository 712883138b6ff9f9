"""A run folder read back: history.csv as a numpy structured array (a pandas
DataFrame when pandas is installed) or as columns, the frames of frames.h5
read lazily, run.json and case.resolved.toml as dicts. Reads only; a run in
progress can be read while it writes (every file is replaced atomically).
Every script that reads a run folder reads it through here, so that the
files' layout is known in one place."""
import json
import os
import tomllib
import warnings

import numpy as np

RUN_JSON = "run.json"
CASE_TOML = "case.resolved.toml"
HISTORY_CSV = "history.csv"
FRAMES_H5 = "frames.h5"
CHECKPOINT_H5 = "checkpoint.h5"

_REQUIRED = object()   # read_info/read_case without a default: errors raise


class Frame:
    """One frame of frames.h5: `step`, `time`, and each field read on first
    access as a numpy array in id order (`id`, `kind`, `body`, `position`,
    `velocity` (N x 2), `rotation`, `angular_velocity`, `volumetric_strain`,
    `pressure`, `surface` (1 on a body's surface), `normal` (its outward unit
    normal, N x 2)); in space the vectors are N x 3, `rotation` the rotation
    vector and `orientation` the quaternion (w, x, y, z; N x 4); with a gas,
    `gas(field)` on the gas's grid."""

    def __init__(self, path, name, step, time, gas_shape=None):
        self._path, self._name = path, name
        self.step, self.time = step, time
        self._fields = {}
        self._gas_shape = gas_shape  # (ny, nx) with a gas

    def gas(self, field):
        """A gas field of this frame on its grid: `density`, `pressure`
        (ny x nx, NaN inside a body), `velocity` (ny x nx x 2) or `solid`
        (1 inside a body); row j is y = y0 + (j + 1/2) cell (Frames.gas_grid)."""
        if self._gas_shape is None:
            raise KeyError(f"{self._path}: the run has no gas")
        values = self["gas_" + field]
        ny, nx = self._gas_shape
        return values.reshape((ny, nx, 2) if field == "velocity" else (ny, nx))

    def fields(self):
        """The field names of this frame."""
        import h5py
        with h5py.File(self._path, "r") as f:
            return sorted(f["frames"][self._name].keys())

    def __getitem__(self, field):
        if field not in self._fields:
            import h5py
            with h5py.File(self._path, "r") as f:
                group = f["frames"][self._name]
                if field not in group:
                    raise KeyError(f"{self._path}: frame {self._name} has no field '{field}' "
                                   f"(it has {', '.join(sorted(group.keys()))})")
                self._fields[field] = group[field][()]
        return self._fields[field]

    def __getattr__(self, field):
        if field.startswith("_"):
            raise AttributeError(field)
        try:
            return self[field]
        except KeyError as e:
            raise AttributeError(str(e)) from None

    def __repr__(self):
        return f"Frame(step={self.step}, time={self.time:g})"


class Frames:
    """The frames of frames.h5 as a sequence; nothing is read until a frame's
    field is asked for. `body_names` and `kind_names` index `body` and `kind`;
    `gas_grid` (None without a gas) is the gas's grid: nx, ny, x0, y0, cell."""

    def __init__(self, path):
        import h5py
        self._path = path
        with h5py.File(path, "r") as f:
            names = sorted(f["frames"].keys())
            self.gas_grid = None
            if "gas_nx" in f.attrs:
                self.gas_grid = {k: f.attrs["gas_" + k].item()
                                 for k in ("nx", "ny", "x0", "y0", "cell")}
            shape = (self.gas_grid["ny"], self.gas_grid["nx"]) if self.gas_grid else None
            self._frames = [Frame(path, n, int(f["frames"][n].attrs["step"]),
                                  float(f["frames"][n].attrs["time"]), shape) for n in names]
            self.body_names = [b.decode() for b in f["body_names"][()]]
            self.kind_names = [k.decode() for k in f["kind_names"][()]]
            self.attrs = {k: (v.item() if hasattr(v, "item") else v) for k, v in f.attrs.items()}

    def __len__(self):
        return len(self._frames)

    def __getitem__(self, k):
        return self._frames[k]

    def __iter__(self):
        return iter(self._frames)

    @property
    def times(self):
        return np.array([fr.time for fr in self._frames])

    def at_time(self, t):
        """The frame closest to time t."""
        return min(self._frames, key=lambda fr: abs(fr.time - t))


def _read_file(folder, name, load, mode, default):
    """load(file) of FOLDER/NAME; `default` instead when it is absent or
    unreadable, if one is given (a run not yet started, or killed before
    writing it, is then no error)."""
    try:
        with open(os.path.join(os.fspath(folder), name), mode) as f:
            return load(f)
    except (OSError, ValueError):
        if default is _REQUIRED:
            raise
        return default


def read_info(folder, default=_REQUIRED):
    """run.json of a run folder as a dict (outcome, wall time, diagnosis, ...).
    Raises OSError or ValueError when it is absent or not JSON, unless a
    `default` is given, which is returned instead."""
    return _read_file(folder, RUN_JSON, json.load, "r", default)


def read_case(folder, default=_REQUIRED):
    """case.resolved.toml of a run folder as a dict (every default filled in).
    Raises as read_info does, unless a `default` is given."""
    return _read_file(folder, CASE_TOML, tomllib.load, "rb", default)


def read_history(path):
    """history.csv as a numpy structured array, one float64 field per column
    (the values are the file's bits: numpy parses as float() does). A file
    with only its header (a run that has just started) gives no rows."""
    with open(path) as f:
        header = f.readline().strip().split(",")
        with warnings.catch_warnings():   # no rows yet: no warning, an empty table
            warnings.simplefilter("ignore", UserWarning)
            data = np.loadtxt(f, delimiter=",", ndmin=2)
    if data.size == 0:
        data = np.empty((0, len(header)))
    return np.rec.fromarrays([data[:, k] for k in range(len(header))], names=header)


def read_history_columns(folder):
    """history.csv of a run folder as {column: float64 array}, in the file's
    column order: what scripts that do arithmetic on whole columns want."""
    table = read_history(os.path.join(os.fspath(folder), HISTORY_CSV))
    return {name: np.array(table[name], dtype=float) for name in table.dtype.names}


class Run:
    """A run folder. `history` is a pandas DataFrame when pandas is installed,
    else the numpy structured array `history_array` (columns by name either
    way: run.history["plate.x"]); `frames` the lazily read frames; `info` is
    run.json, `case` case.resolved.toml."""

    def __init__(self, folder):
        self.folder = os.fspath(folder)
        if not os.path.isfile(os.path.join(self.folder, RUN_JSON)):
            raise FileNotFoundError(f"{self.folder}: not a run folder (no run.json)")
        self._history = None
        self._frames = None

    @property
    def info(self):
        return read_info(self.folder)

    @property
    def case(self):
        return read_case(self.folder)

    @property
    def history_array(self):
        if self._history is None:
            self._history = read_history(os.path.join(self.folder, HISTORY_CSV))
        return self._history

    @property
    def history(self):
        try:
            import pandas
        except ImportError:
            return self.history_array
        return pandas.DataFrame.from_records(self.history_array)

    @property
    def frames(self):
        if self._frames is None:
            self._frames = Frames(os.path.join(self.folder, FRAMES_H5))
        return self._frames

    @property
    def outcome(self):
        return self.info["outcome"]

    def __repr__(self):
        info = self.info
        return (f"Run('{self.folder}': {info['case']}, {info['model']}, {info['outcome']} "
                f"at t = {info['simulated_time']:g} s)")


def open_run(folder):
    """The run in `folder` (see Run)."""
    return Run(folder)
