#!/usr/bin/python3
"""Compares two mpsolid output folders bit for bit.

    /usr/bin/python3 tests/tools/compare_runs.py DIR_A DIR_B

history.csv byte for byte; every frame of frames.h5 (same frame names, the
`step` and `time` attributes and every dataset, its shape, type and bytes);
and the final state in checkpoint.h5 (step, particle arrays, rigid bodies,
loads). Datasets that only DIR_B holds (fields a newer build adds, e.g. DIR_A
from an older build) are listed but are no difference; every dataset of
DIR_A must be in DIR_B, identical (a checkpoint's list of particle arrays,
`_order`, may gain names). Exits 0 if they are identical, 1 with the first
differences if not.
"""
import sys

import h5py
import numpy as np


def same_dataset(a, b):
    return a.shape == b.shape and a.dtype == b.dtype and a[()].tobytes() == b[()].tobytes()


def compare(dir_a, dir_b):
    """(differences, datasets only dir_b holds)."""
    problems, added = [], set()
    with open(f"{dir_a}/history.csv", "rb") as fa, open(f"{dir_b}/history.csv", "rb") as fb:
        if fa.read() != fb.read():
            problems.append("history.csv differs")
    with h5py.File(f"{dir_a}/frames.h5", "r") as fa, h5py.File(f"{dir_b}/frames.h5", "r") as fb:
        names_a, names_b = sorted(fa["frames"]), sorted(fb["frames"])
        if names_a != names_b:
            problems.append(f"frames differ: {names_a} vs {names_b}")
        for name in sorted(set(names_a) & set(names_b)):
            ga, gb = fa["frames"][name], fb["frames"][name]
            for attr in ("step", "time"):
                if ga.attrs[attr] != gb.attrs[attr]:
                    problems.append(f"frame {name}: {attr} {ga.attrs[attr]} vs {gb.attrs[attr]}")
            if not set(ga) <= set(gb):
                problems.append(f"frame {name}: datasets {sorted(ga)} vs {sorted(gb)}")
            added.update(f"frames: {field}" for field in set(gb) - set(ga))
            for field in sorted(set(ga) & set(gb)):
                if not same_dataset(ga[field], gb[field]):
                    problems.append(f"frame {name}: {field} differs")
    with h5py.File(f"{dir_a}/checkpoint.h5", "r") as ca, \
            h5py.File(f"{dir_b}/checkpoint.h5", "r") as cb:
        for attr in ("step", "frames", "history_bytes", "bond_hash"):
            if ca.attrs[attr] != cb.attrs[attr]:
                problems.append(f"checkpoint: {attr} {ca.attrs[attr]} vs {cb.attrs[attr]}")
        for group in ("particles", "rigid_bodies", "loads"):
            if not set(ca[group]) <= set(cb[group]):
                problems.append(f"checkpoint: /{group} holds {sorted(ca[group])} vs {sorted(cb[group])}")
                continue
            added.update(f"checkpoint /{group}: {field}" for field in set(cb[group]) - set(ca[group]))
            for field in sorted(ca[group]):
                if field == "_order":  # the names, in order; B may have more
                    names_a = [n.decode() if isinstance(n, bytes) else n for n in ca[group][field][()]]
                    names_b = [n.decode() if isinstance(n, bytes) else n for n in cb[group][field][()]]
                    if [n for n in names_b if n in names_a] != names_a:
                        problems.append(f"checkpoint: /{group}/_order {names_a} vs {names_b}")
                    continue
                if not same_dataset(ca[group][field], cb[group][field]):
                    problems.append(f"checkpoint: /{group}/{field} differs")
    return problems, sorted(added)


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    problems, added = compare(sys.argv[1], sys.argv[2])
    if added:
        print(f"compare_runs: only in {sys.argv[2]}: {', '.join(added)}")
    for p in problems[:20]:
        print(f"compare_runs: {p}")
    if problems:
        print(f"compare_runs: {sys.argv[1]} and {sys.argv[2]} differ ({len(problems)} differences)")
        return 1
    with h5py.File(f"{sys.argv[1]}/frames.h5", "r") as f:
        frames = len(f["frames"])
    print(f"compare_runs: identical ({frames} frames, history.csv, final state)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
