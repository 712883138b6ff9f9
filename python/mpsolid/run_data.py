"""A run folder read back: history.csv as a numpy structured array (a pandas
DataFrame when pandas is installed), the frames of frames.h5 read lazily,
run.json and case.resolved.toml as dicts. Reads only; a run in progress can
be read while it writes (every file is replaced atomically)."""
import json
import os
import tomllib

import numpy as np


class Frame:
    """One frame of frames.h5: `step`, `time`, and each field read on first
    access as a numpy array in id order (`id`, `kind`, `body`, `position`,
    `velocity` (N x 2), `rotation`, `angular_velocity`, `volumetric_strain`,
    `pressure`)."""

    def __init__(self, path, name, step, time):
        self._path, self._name = path, name
        self.step, self.time = step, time
        self._fields = {}

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
    field is asked for. `body_names` and `kind_names` index `body` and `kind`."""

    def __init__(self, path):
        import h5py
        self._path = path
        with h5py.File(path, "r") as f:
            names = sorted(f["frames"].keys())
            self._frames = [Frame(path, n, int(f["frames"][n].attrs["step"]),
                                  float(f["frames"][n].attrs["time"])) for n in names]
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


def read_history(path):
    """history.csv as a numpy structured array, one float64 field per column."""
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if data.size == 0:
        data = np.empty((0, len(header)))
    return np.rec.fromarrays([data[:, k] for k in range(len(header))], names=header)


class Run:
    """A run folder. `history` is a pandas DataFrame when pandas is installed,
    else the numpy structured array `history_array` (columns by name either
    way: run.history["plate.x"]); `frames` the lazily read frames; `info` is
    run.json, `case` case.resolved.toml."""

    def __init__(self, folder):
        self.folder = os.fspath(folder)
        if not os.path.isfile(os.path.join(self.folder, "run.json")):
            raise FileNotFoundError(f"{self.folder}: not a run folder (no run.json)")
        self._history = None
        self._frames = None

    @property
    def info(self):
        with open(os.path.join(self.folder, "run.json")) as f:
            return json.load(f)

    @property
    def case(self):
        with open(os.path.join(self.folder, "case.resolved.toml"), "rb") as f:
            return tomllib.load(f)

    @property
    def history_array(self):
        if self._history is None:
            self._history = read_history(os.path.join(self.folder, "history.csv"))
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
            self._frames = Frames(os.path.join(self.folder, "frames.h5"))
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
