#!/usr/bin/python3
"""Writes a LAMMPS input for the peer comparison: a fixed harmonic
bond network on exactly mpsolid's lattice sites for a case (default
cases/shock_rod.toml), i.e. the same particle count and the same bonds (every
pair closer than 2.1 l0: in the plane 4 at l0, 4 at sqrt(2) l0, 4 at 2 l0,
so 12 per interior particle; in space, a case with dimension = 3 whose
bodies are boxes, 6 + 12 + 8 + 6 = 32 at l0, sqrt(2), sqrt(3) and 2 l0).

  bench/lammps/make_input.py --out DIR [--l0 M] [--steps N] [--case FILE]

writes DIR/in.rod (LAMMPS commands) and DIR/rod.data (atoms only; LAMMPS
makes the bonds itself with create_bonds many) and prints a JSON summary
(atoms, the bonds mpsolid's rule gives, interior particles, steps) on stdout.

What LAMMPS runs: atom_style bond, bond_style harmonic with a bond type per
distance (three in the plane, four in space) whose stiffness is mpsolid's
spring constant of that bond (E = K (r - r0)^2 with K = k_ij / 2), units
si, dimension 2 (fix enforce2d) or 3, the wall's
columns clamped (left out of fix nve: zero velocity, never moved), the
case's step force shared by the plate's atoms (fix addforce), fix nve on the
rod and plate, pair_style zero (no pair forces; it only gives create_bonds
its neighbour list), and the neighbour list built once (neigh_modify once
yes): the bond network never changes, as in mpsolid.
The plate is part of the spring network here, not a rigid body.
"""
import argparse
import json
import math
import pathlib
import sys
import tomllib

REPO = pathlib.Path(__file__).resolve().parents[2]
RADIUS = 2.1  # re / l0, as mpsolid's kRadiusOverSpacing
SLACK = 1e-9  # as mpsolid's lattice_span: absorbs decimal round-off


def fail(message):
    sys.exit(f"make_input.py: {message}")


def lattice_span(lo, hi, l0):
    # Mirrors src/geometry.cpp: sites at (k + 1/2) l0 inside [lo, hi).
    first = math.ceil(lo / l0 - 0.5 - SLACK)
    last = math.ceil(hi / l0 - 0.5 - SLACK) - 1
    return first, last


def bond_offsets(dimension):
    """Lattice offsets closer than re: the 12 bonds of an interior site in the
    plane ((dk, dm, 0)), the 32 in space."""
    reach = int(RADIUS)
    span = range(-reach, reach + 1)
    third = span if dimension == 3 else (0,)
    return [(dk, dm, dn) for dk in span for dm in span for dn in third
            if (dk, dm, dn) != (0, 0, 0) and dk * dk + dm * dm + dn * dn < RADIUS * RADIUS]


def read_case(path, l0_override):
    try:
        with open(path, "rb") as f:
            case = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        fail(f"cannot read case {path}: {e}")
    l0 = l0_override if l0_override is not None else case["l0"]
    if case.get("model", "paper") not in ("paper", "paper_conservative", "finite_strain"):
        fail(f"{path}: unknown model")
    return case, l0


def lame_mu(material):
    return material["E"] / (2.0 * (1.0 + material["nu"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, type=pathlib.Path, help="folder for in.rod, rod.data")
    ap.add_argument("--case", default=REPO / "cases" / "shock_rod.toml", type=pathlib.Path)
    ap.add_argument("--l0", type=float, help="lattice spacing (m); default: the case's")
    ap.add_argument("--steps", type=int, default=1000, help="time steps to run (default 1000)")
    ap.add_argument("--dt", type=float, help="time step (s); default: the case's time.dt")
    ap.add_argument("--write-data", type=pathlib.Path,
                    help="also write LAMMPS's data file (with its bonds) here after set-up "
                         "(for tests)")
    args = ap.parse_args()
    if args.steps < 0:
        fail("--steps must be >= 0")

    case, l0 = read_case(args.case, args.l0)
    if not l0 > 0:
        fail(f"l0 must be > 0, got {l0}")
    dt = args.dt if args.dt is not None else case["time"]["dt"]
    dimension = case.get("dimension", 2)
    if dimension not in (2, 3):
        fail(f"{args.case}: dimension must be 2 or 3")
    # A particle's volume: l0^2 times the depth in the plane, l0^3 in space.
    volume = l0 ** 3 if dimension == 3 else l0 * l0 * case.get("depth", 1.0)
    materials = case["materials"]
    bodies = case["bodies"]

    # Sites body by body in name order (mpsolid's id order); atom type per kind.
    kind_type = {"elastic": 1, "rigid": 2, "wall": 3}
    sites = {}  # (k, m, n) -> atom type (n = 0 in the plane)
    masses = set()
    mus = set()
    for name in sorted(bodies):
        body = bodies[name]
        kind = body.get("kind", "elastic")
        if kind not in kind_type:
            fail(f"body {name}: unknown kind {kind!r}")
        mat = materials[body["material"]]
        masses.add(mat["rho"] * volume)
        mus.add(lame_mu(mat))
        k0, k1 = lattice_span(body["x"][0], body["x"][1], l0)
        m0, m1 = lattice_span(body["y"][0], body["y"][1], l0)
        if dimension == 3 and body.get("shape", "box") != "box":
            fail(f"body {name}: this generator fills boxes only in space")
        n0_, n1_ = lattice_span(body["z"][0], body["z"][1], l0) if dimension == 3 else (0, 0)
        for n in range(n0_, n1_ + 1):  # layer by layer, as mpsolid fills a box
            for m in range(m0, m1 + 1):
                for k in range(k0, k1 + 1):
                    if (k, m, n) in sites:
                        fail(f"body {name} overlaps another body at site ({k}, {m}, {n})")
                    sites[(k, m, n)] = kind_type[kind]
    if len(masses) != 1 or len(mus) != 1:
        fail("this generator supports one material (one mass, one mu) for all bodies")
    mass, mu = masses.pop(), mus.pop()
    if not sites:
        fail("the case has no particles")

    # mpsolid's bonds: every pair closer than re, counted once.
    offsets = bond_offsets(dimension)
    full = 32 if dimension == 3 else 12
    assert len(offsets) == full
    bonds = 0
    interior = 0
    for (k, m, n) in sites:
        count = sum((k + dk, m + dm, n + dn) in sites for dk, dm, dn in offsets)
        bonds += count
        interior += count == full
    bonds //= 2

    # Stiffness per bond distance (in l0): k_ij = V (d / n0) 4 mu w0 / |r0|^2 as
    # src/bonds.hpp, and LAMMPS's harmonic E = K (r - r0)^2 means K = k_ij / 2.
    d = float(dimension)
    n0 = sum(RADIUS / math.sqrt(dk * dk + dm * dm + dn * dn) - 1.0 for dk, dm, dn in offsets)
    # 1, sqrt 2, 2 (and sqrt 3 in space), rounded so that equal lengths merge.
    distances = sorted({round(math.sqrt(dk * dk + dm * dm + dn * dn), 12)
                        for dk, dm, dn in offsets})
    bond_types = []
    for r in distances:
        w0 = RADIUS / r - 1.0
        k_ij = volume * (d / n0) * 4.0 * mu * w0 / (r * l0) ** 2
        bond_types.append((r * l0, k_ij / 2.0))

    # Step loads: a force shared by a body's particles.
    loads = []
    for name, load in sorted(case.get("loads", {}).items()):
        body = bodies.get(load["body"])
        if body is None:
            fail(f"load {name}: no body {load['body']}")
        if load.get("start", 0.0) != 0.0:
            fail(f"load {name}: only loads from t = 0 are supported")
        loads.append((load["body"], kind_type[body.get("kind", "elastic")], load["force"]))

    args.out.mkdir(parents=True, exist_ok=True)
    xs = [k for k, _, _ in sites]
    ys = [m for _, m, _ in sites]
    zs = [n for _, _, n in sites]
    # A generous box: fixed boundaries, and the bodies move and bulge (the
    # neighbour list is never rebuilt, so atoms are never re-binned).
    span = max(max(xs) - min(xs), max(ys) - min(ys), max(zs) - min(zs)) + 1
    lo_x, hi_x = (min(xs) - span) * l0, (max(xs) + 1 + span) * l0
    lo_y, hi_y = (min(ys) - span) * l0, (max(ys) + 1 + span) * l0
    lo_z, hi_z = ((min(zs) - span) * l0, (max(zs) + 1 + span) * l0) if dimension == 3 else (
        -0.5 * l0, 0.5 * l0)
    data = args.out / "rod.data"
    with open(data, "w") as f:
        f.write(f"mpsolid lattice sites of {args.case.name} at l0 = {l0!r} m\n\n")
        f.write(f"{len(sites)} atoms\n3 atom types\n{len(bond_types)} bond types\n\n")
        f.write(f"{lo_x!r} {hi_x!r} xlo xhi\n{lo_y!r} {hi_y!r} ylo yhi\n")
        f.write(f"{lo_z!r} {hi_z!r} zlo zhi\n\nAtoms # bond\n\n")
        for i, ((k, m, n), t) in enumerate(sites.items(), start=1):
            # atom-ID molecule-ID atom-type x y z
            z = (n + 0.5) * l0 if dimension == 3 else 0.0
            f.write(f"{i} 1 {t} {(k + 0.5) * l0!r} {(m + 0.5) * l0!r} {z!r}\n")

    # Bond-type windows half-way between the distances (in l0: 1, 1.414, 2).
    cuts = [0.5] + [(a + b) / 2 for a, b in zip(distances, distances[1:])] + [RADIUS]
    skin = 0.3 * l0
    lines = [
        f"# Generated by bench/lammps/make_input.py from {args.case.name} at l0 = {l0!r} m:",
        f"# {len(sites)} atoms, {bonds} bonds ({full} per interior atom), {args.steps} steps.",
        "units si",
        f"dimension {dimension}",
        "boundary f f f" if dimension == 3 else "boundary f f p",
        "atom_style bond",
        "atom_modify map array",
        # 12 (32) bonds per atom; special lists stay 1-2 only (weights below).
        f"read_data rod.data extra/bond/per/atom {full} extra/special/per/atom {full + 2}",
        "special_bonds lj/coul 0.0 1.0 1.0",
        f"mass * {mass!r}",
        # No pair forces; pair zero's cutoff gives create_bonds its neighbour list.
        f"pair_style zero {RADIUS * l0!r}",
        "pair_coeff * *",
        "bond_style harmonic",
    ]
    for t, (r0, K) in enumerate(bond_types, start=1):
        lines.append(f"bond_coeff {t} {K!r} {r0!r}")
    lines += [f"neighbor {skin!r} bin", "neigh_modify once yes"]
    # Ghost atoms must reach every bond partner under MPI, however the bonds
    # stretch: LAMMPS asks for 1.5 x the longest bond (2 l0) + skin; a margin on top.
    lines.append(f"comm_modify cutoff {3.5 * l0!r}")
    for t, _ in enumerate(bond_types, start=1):
        lines.append(f"create_bonds many all all {t} {cuts[t - 1] * l0!r} {cuts[t] * l0!r}")
    lines += [
        "group wall type 3",
        "group mobile type 1 2",
    ]
    for n, (body, t, force) in enumerate(loads):
        count = sum(1 for v in sites.values() if v == t)
        if sum(1 for b in bodies.values() if kind_type[b.get("kind", "elastic")] == t) != 1:
            fail(f"load on {body}: its kind is shared by several bodies")
        lines += [f"group load{n} type {t}",
                  f"fix load{n} load{n} addforce {force[0] / count!r} {force[1] / count!r} "
                  f"{(force[2] if len(force) > 2 else 0.0) / count!r}"]
    lines += [
        "fix step mobile nve",  # the wall is not integrated: clamped
        *(["fix plane all enforce2d"] if dimension == 2 else []),
        f"timestep {dt!r}",
        "thermo_style custom step atoms bonds ke",
        "thermo 0",  # thermo output only at the start and the end of the run
    ]
    if args.write_data:
        lines.append(f"write_data {args.write_data.resolve()}")
    lines.append(f"run {args.steps}")
    (args.out / "in.rod").write_text("\n".join(lines) + "\n")
    print(json.dumps({"atoms": len(sites), "bonds": bonds, "interior": interior,
                      "steps": args.steps, "l0": l0, "dt": dt,
                      "input": str(args.out / "in.rod")}))


if __name__ == "__main__":
    main()
