#!/usr/bin/python3
"""Cache lines crossing between the threads per time step when every thread
works on shared per-particle and per-slot arrays (advance_steps in
src/solver/step.hpp), for the paper model on the shock_rod lattice.

  bench/team_crossing.py [--l0 0.002 0.001] [--threads 2] [--conservative] [--json]

The lattice, storage order and bonds are rebuilt here from
cases/shock_rod.toml: sites at (k + 1/2) l0, bodies stored walls, elastic,
rigid, each row by row (x fastest), a bond for every pair closer than
re = 2.1 l0 (the lattice and bonds of bench/lammps/make_input.py). Slots
follow kernels/bond_slots.cpp: a direction per offset used by at least
n / 8 bonds, slot d * n + i, then the extra slots by owner.

A step is three team loops, each over one static block per thread:
  slots    bond kinematics by owner over [0, n)
  strain   strain and pressure gather over [0, n)
  forces   force gather fused with loads, kick, drift, half angles and the
           rigid-body projection, over the moving particles
A line crosses when a thread touches it after another thread wrote it and
before that thread writes it again (once per line and thread fetching it);
a line two threads write in one loop counts once and ends with the lower
thread (which reaches the shared block boundary last). Steady state: the
last of three steps. Each
array starts on a cache line (the slot buffer as one aligned buffer with its
stagger); no chunk is taken over by another thread, and nothing is
prefetched (the slot data stay under 24 MiB). Lines of the barrier and
chunk counters are reported apart, as an estimate.
"""
import argparse
import json
import pathlib
import sys
import tomllib

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent / "lammps"))
from make_input import bond_offsets, lattice_span  # noqa: E402  (the same lattice and bonds)

REPO = pathlib.Path(__file__).resolve().parents[1]
CASE = REPO / "cases" / "shock_rod.toml"
LINE_DOUBLES = 8  # 64-byte lines
GROUP = {"wall": 0, "elastic": 1, "rigid": 2}
PARTICLE_ARRAYS = ["x", "y", "vx", "vy", "theta", "omega", "half_cos", "half_sin", "strain",
                   "pressure", "fx", "fy", "torque", "inv_mass", "inv_inertia", "lambda"]
SLOT_FIELDS = ["R0x", "R0y", "StrainCoef", "SpringCoef", "PressureCoef", "Rx", "Ry", "Ux", "Uy",
               "InvLen", "StrainTerm", "Extension"]  # kFields: all 12 are allocated
PASSES = ["slots", "strain", "forces"]


def span(lo, hi, l0):
    """Lattice indices [first, end) with (k + 1/2) l0 in [lo, hi)."""
    first, last = lattice_span(lo, hi, l0)
    return first, last + 1


def lattice(l0):
    """Sites (k, m) in storage order, and the kind ranges and rigid bodies."""
    bodies = tomllib.loads(CASE.read_text())["bodies"]
    order = sorted(bodies, key=lambda name: GROUP[bodies[name]["kind"]])  # stable
    sites, kinds, rigid = [], [], []
    for name in order:
        b = bodies[name]
        (k0, k1), (m0, m1) = span(*b["x"], l0), span(*b["y"], l0)
        first = len(sites)
        sites += [(k, m) for m in range(m0, m1) for k in range(k0, k1)]
        kinds += [GROUP[b["kind"]]] * (len(sites) - first)
        if b["kind"] == "rigid":
            rigid.append((first, len(sites)))
    kinds = np.array(kinds)
    return np.array(sites), int((kinds == 0).sum()), int((kinds <= 1).sum()), rigid


def bonds(sites):
    """Every bond entry (i, j), both ends, for pairs closer than re."""
    lo = sites.min(axis=0) - 2
    grid = -np.ones(tuple(sites.max(axis=0) - lo + 3), dtype=np.int64)
    grid[tuple((sites - lo).T)] = np.arange(len(sites))
    i_all, j_all = [], []
    for dk, dm in bond_offsets():
        j = grid[sites[:, 0] - lo[0] + dk, sites[:, 1] - lo[1] + dm]
        i_all.append(np.flatnonzero(j >= 0))
        j_all.append(j[j >= 0])
    return np.concatenate(i_all), np.concatenate(j_all)


def bond_slots(n, ei, ej):
    """Directions, and the slot of each bond entry (kernels/bond_slots.cpp)."""
    own = ei < ej
    offset, count = np.unique(ej[own] - ei[own], return_counts=True)
    directions = offset[count * 8 >= n]
    lo, hi = np.minimum(ei, ej), np.maximum(ei, ej)
    d = np.searchsorted(directions, hi - lo)
    dense = (d < len(directions)) & (directions[np.minimum(d, len(directions) - 1)] == hi - lo)
    extra = np.unique(lo[~dense] * n + hi[~dense])  # sorted by owner, then partner
    slot = np.where(dense, d * n + lo, len(directions) * n + np.searchsorted(extra, lo * n + hi))
    return directions, slot, extra // n, extra % n


class Lines:
    """Global cache-line ids: each particle array and the slot buffer aligned."""

    def __init__(self, n, slot_count):
        per_array = -(-n // LINE_DOUBLES)
        self.base = {a: k * per_array for k, a in enumerate(PARTICLE_ARRAYS)}
        self.slot_base = len(PARTICLE_ARRAYS) * per_array
        self.stride = -(-slot_count // 512) * 512 + 40  # SlotArrays: 5 lines of stagger
        self.count = self.slot_base + len(SLOT_FIELDS) * self.stride // LINE_DOUBLES
        self.names = [a for a in PARTICLE_ARRAYS for _ in range(per_array)]
        self.names += [f"slot {f}" for f in SLOT_FIELDS for _ in range(self.stride // LINE_DOUBLES)]

    def of(self, array, index):
        if array in self.base:
            return self.base[array] + np.asarray(index) // LINE_DOUBLES
        field = SLOT_FIELDS.index(array)
        return self.slot_base + (field * self.stride + np.asarray(index)) // LINE_DOUBLES


def accesses(l0, threads, conservative):
    """Per pass and thread: (lines read, lines written) in one step."""
    sites, walls_end, elastic_end, rigid = lattice(l0)
    n = len(sites)
    ei, ej = bonds(sites)
    directions, entry_slot, extra_owner, extra_partner = bond_slots(n, ei, ej)
    dense_slots = len(directions) * n
    lines = Lines(n, dense_slots + len(extra_owner))
    kinematics = ["Rx", "Ry", "Ux", "Uy", "InvLen", "StrainTerm"] + conservative * ["Extension"]
    motion = ["x", "y", "half_cos", "half_sin"]
    forces_in = ["SpringCoef", "PressureCoef", "Rx", "Ry", "Ux", "Uy", "InvLen"]
    forces_in += conservative * ["Extension"]

    def block(begin, end, r):
        return begin + (end - begin) * r // threads, begin + (end - begin) * (r + 1) // threads

    def touch(out, arrays, index):
        out.extend(lines.of(a, index) for a in arrays)

    passes = {p: [] for p in PASSES}
    for r in range(threads):
        rd, wr = [], []
        # slots: the bonds owned in the block, but those between two walls.
        b, e = block(0, n, r)
        for d, o in enumerate(directions):
            owner = np.arange(max(b, walls_end - o if walls_end > o else 0), min(e, n - o))
            touch(rd, motion, np.concatenate([owner, owner + o]))
            touch(rd, ["R0x", "R0y", "StrainCoef"], d * n + owner)
            touch(wr, kinematics, d * n + owner)
        k = np.flatnonzero((extra_owner >= b) & (extra_owner < e) & (extra_partner >= walls_end))
        touch(rd, motion, np.concatenate([extra_owner[k], extra_partner[k]]))
        touch(rd, ["R0x", "R0y", "StrainCoef"], dense_slots + k)
        touch(wr, kinematics, dense_slots + k)
        passes["slots"].append((rd, wr))
        # strain: each particle's bonds' strain terms.
        rd, wr = [], []
        mine = (ei >= b) & (ei < e)
        touch(rd, ["StrainTerm"], entry_slot[mine])
        touch(rd, ["lambda"], np.arange(b, e))
        touch(wr, ["strain", "pressure"], np.arange(b, e))
        passes["strain"].append((rd, wr))
        # forces, loads, kick, drift, half angles (integrate_block), projection.
        rd, wr = [], []
        b, e = block(walls_end, n, r)
        own, mine = np.arange(b, e), (ei >= b) & (ei < e)
        touch(rd, ["pressure"], np.concatenate([own, ej[mine]]))
        touch(rd, forces_in, entry_slot[mine])
        touch(wr, ["fx", "fy", "torque"], own)
        touch(rd, ["fx", "fy", "torque", "inv_mass", "inv_inertia"], own)
        drift = np.arange(b, min(e, elastic_end))
        touch(rd, ["vx", "vy", "x", "y", "omega", "theta"], drift)
        touch(wr, ["vx", "vy", "x", "y", "omega", "theta", "half_cos", "half_sin"], drift)
        kicked = np.arange(max(b, elastic_end), e)
        touch(rd, ["vx", "vy", "omega"], kicked)
        touch(wr, ["vx", "vy", "omega"], kicked)
        for first, last in rigid:
            if b <= last - 1 < e:  # this thread kicks the body's last particles
                body = np.arange(first, last)
                touch(rd, ["inv_mass", "inv_inertia", "omega", "vx", "vy", "x", "y"], body)
                touch(wr, ["x", "y", "vx", "vy", "theta", "omega", "half_cos", "half_sin"], body)
        passes["forces"].append((rd, wr))
    facts = {"l0": l0, "particles": n, "bonds": len(ei) // 2, "directions": directions.tolist(),
             "extra_slots": len(extra_owner)}
    return passes, lines, facts


def crossings(passes, lines, threads, steps=3):
    """Lines crossing per pass in the last of `steps` steps (the first warms up)."""
    masks = {}
    for p in PASSES:
        acc = np.zeros(lines.count, dtype=np.int64)
        wr = np.zeros(lines.count, dtype=np.int64)
        for r, (rd_lines, wr_lines) in enumerate(passes[p]):
            for group in rd_lines + wr_lines:
                acc[group] |= 1 << r
            for group in wr_lines:
                wr[group] |= 1 << r
        masks[p] = acc, wr
    popcount = lambda m: sum((m >> r) & 1 for r in range(threads))
    holders = np.full(lines.count, (1 << threads) - 1, dtype=np.int64)  # warm, clean caches
    totals = []
    for _ in range(steps):
        counted = {}
        for p in PASSES:
            acc, wr = masks[p]
            fetches = popcount(acc & ~holders)
            fetches = np.where(popcount(wr) >= 2, np.maximum(fetches, 1), fetches)
            counted[p] = fetches
            holders = np.where(wr != 0, wr & -wr, holders | acc)
        totals.append([int(counted[p].sum()) for p in PASSES])
    assert totals[-1] == totals[-2], "no steady state"
    per_array = {p: {} for p in PASSES}
    for p in PASSES:
        for at in np.flatnonzero(counted[p]):
            name = lines.names[at]
            per_array[p][name] = per_array[p].get(name, 0) + int(counted[p][at])
    return {p: int(counted[p].sum()) for p in PASSES}, per_array


def sync_estimate(threads, loops=len(PASSES)):
    """Barrier and chunk-counter lines per step (src/core/parallel.cpp): per
    loop, each thread's increment of the arrival line and its look at each
    other block's chunk counter, the release line read by the others, and each
    thread clearing its own counter of the other parity."""
    per_loop = threads + threads * (threads - 1) + (threads - 1) + threads
    return loops * per_loop


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--l0", type=float, nargs="+", default=[0.002, 0.001])
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--conservative", action="store_true",
                        help="paper_conservative (adds the extension slots)")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    results = []
    for l0 in args.l0:
        passes, lines, facts = accesses(l0, args.threads, args.conservative)
        per_pass, per_array = crossings(passes, lines, args.threads)
        results.append({**facts, "threads": args.threads, "per_pass": per_pass,
                        "total": sum(per_pass.values()), "per_array": per_array,
                        "sync_estimate": sync_estimate(args.threads)})
    if args.json:
        print(json.dumps(results, indent=2))
        return
    for res in results:
        print(f"l0 = {res['l0'] * 1e3:g} mm: {res['particles']} particles, {res['bonds']} bonds,"
              f" directions {res['directions']}, {res['extra_slots']} extra slots,"
              f" {res['threads']} threads")
        print(f"  {'pass':<8} {'lines/step':>10}  arrays")
        for p in PASSES:
            arrays = ", ".join(f"{a} {c}" for a, c in sorted(res["per_array"][p].items(),
                                                             key=lambda kv: -kv[1]))
            print(f"  {p:<8} {res['per_pass'][p]:>10}  {arrays}")
        print(f"  {'total':<8} {res['total']:>10}")
        print(f"  {'sync':<8} {res['sync_estimate']:>10}  (barrier, chunk counters: estimate)\n")


if __name__ == "__main__":
    main()
