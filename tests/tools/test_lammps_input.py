#!/usr/bin/python3
"""The peer comparison's LAMMPS network (bench/lammps/make_input.py) has
mpsolid's particles and bonds: LAMMPS sets the paper's rod up (run 0), writes
its data file, and every interior atom has 12 bonds, 4 at each distance
(l0, sqrt(2) l0, 2 l0), the total equals the bond count mpsolid reports in
run.json for the same case, and the stiffnesses are k_ij / 2 of the bonds;
and the same counts for the rod in space (32 bonds per interior atom).

  test_lammps_input.py MPSOLID_EXECUTABLE

Exits 77 (ctest: skipped) when LAMMPS (`lmp`) is not installed.
"""
import collections
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parents[2]
SKIP = 77


def check(condition, message):
    if not condition:
        sys.exit(f"FAIL: {message}")


def sections(path):
    """The data file's sections as {title: [lines]}."""
    out, title = {}, None
    for line in path.read_text().splitlines():
        stripped = line.split("#")[0].strip()
        if not stripped:
            continue
        if stripped[0].isalpha():
            title = stripped
            out[title] = []
        elif title:
            out[title].append(stripped.split())
    return out


def bonds_per_atom(bonds):
    """{atom id: Counter(bond type)} of a data file's Bonds rows."""
    per_atom = collections.defaultdict(collections.Counter)
    for _, btype, a, b in bonds:
        per_atom[a][btype] += 1
        per_atom[b][btype] += 1
    return per_atom


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: test_lammps_input.py MPSOLID_EXECUTABLE")
    mpsolid = sys.argv[1]
    lmp = shutil.which("lmp")
    if lmp is None:
        print("SKIP: LAMMPS (lmp) is not installed (apt-get install lammps)")
        sys.exit(SKIP)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        summary = json.loads(subprocess.run(
            [sys.executable, REPO / "bench/lammps/make_input.py", "--out", tmp / "lmp",
             "--steps", "0", "--write-data", tmp / "lmp/after.data"],
            check=True, capture_output=True, text=True).stdout)
        subprocess.run([lmp, "-nocite", "-screen", "none", "-log", "log.lammps", "-in", "in.rod"],
                       cwd=tmp / "lmp", check=True)
        # mpsolid's bond count for the same case (one step, no outputs to speak of).
        subprocess.run([mpsolid, "run", REPO / "cases/shock_rod.toml", "--out", tmp / "ms",
                        "--threads", "1", "--set", "time.end=1e-8"],
                       check=True, capture_output=True)
        report = json.loads((tmp / "ms/run.json").read_text())

        data = sections(tmp / "lmp/after.data")
        atoms = data["Atoms"]
        bonds = data["Bonds"]
        check(len(atoms) == report["particles"] == summary["atoms"],
              f"atoms: LAMMPS {len(atoms)}, mpsolid {report['particles']}")
        check(len(bonds) == report["bonds"] == summary["bonds"],
              f"bonds: LAMMPS {len(bonds)}, mpsolid {report['bonds']}")

        per_atom = bonds_per_atom(bonds)
        full = [c for c in per_atom.values() if sum(c.values()) == 12]
        check(len(full) == summary["interior"] > 0,
              f"{len(full)} atoms with 12 bonds, {summary['interior']} interior sites")
        check(all(c == {"1": 4, "2": 4, "3": 4} for c in full),
              "an interior atom without 4 bonds at each of l0, sqrt(2) l0, 2 l0")
        check(max(sum(c.values()) for c in per_atom.values()) == 12, "an atom with > 12 bonds")

        # Bond coefficients: harmonic K = k_ij / 2, r0 = l0, sqrt 2 l0, 2 l0 (l0 = 2 mm);
        # write_data prints 6 significant digits.
        coeffs = {row[0]: (float(row[1]), float(row[2])) for row in data["Bond Coeffs"]}
        l0, mu, n0 = 0.002, 2.8e6 / (2 * 1.495), 6.539697
        for t, r in (("1", 1.0), ("2", 2 ** 0.5), ("3", 2.0)):
            k_ij = l0 * l0 * (2 / n0) * 4 * mu * (2.1 / r - 1) / (r * l0) ** 2
            K, r0 = coeffs[t]
            check(abs(K - k_ij / 2) < 1e-5 * K and abs(r0 - r * l0) < 1e-5 * r0,
                  f"bond type {t}: K = {K}, r0 = {r0}; expected {k_ij / 2}, {r * l0}")
        space = check_space(tmp, lmp, mpsolid)
    print(f"OK: {len(atoms)} atoms, {len(bonds)} bonds, {len(full)} interior atoms with 12; "
          f"in space {space}")


def check_space(tmp, lmp, mpsolid):
    """The rod in space (cases/shock_rod_3d.toml at l0 = 4 mm): mpsolid's
    particles and bonds, every interior atom with 6 + 12 + 8 + 6 bonds at
    l0, sqrt(2), sqrt(3) and 2 l0."""
    case = REPO / "cases/shock_rod_3d.toml"
    summary = json.loads(subprocess.run(
        [sys.executable, REPO / "bench/lammps/make_input.py", "--out", tmp / "lmp3",
         "--case", case, "--l0", "0.004", "--dt", "1e-8", "--steps", "0",
         "--write-data", tmp / "lmp3/after.data"],
        check=True, capture_output=True, text=True).stdout)
    subprocess.run([lmp, "-nocite", "-screen", "none", "-log", "log.lammps", "-in", "in.rod"],
                   cwd=tmp / "lmp3", check=True)
    subprocess.run([mpsolid, "run", case, "--out", tmp / "ms3", "--threads", "1", "--set",
                    "l0=0.004", "--set", "time.dt=1e-8", "--set", "time.end=1e-8"],
                   check=True, capture_output=True)
    report = json.loads((tmp / "ms3/run.json").read_text())
    data = sections(tmp / "lmp3/after.data")
    atoms, bonds = data["Atoms"], data["Bonds"]
    check(len(atoms) == report["particles"] == summary["atoms"],
          f"in space, atoms: LAMMPS {len(atoms)}, mpsolid {report['particles']}")
    check(len(bonds) == report["bonds"] == summary["bonds"],
          f"in space, bonds: LAMMPS {len(bonds)}, mpsolid {report['bonds']}")
    full = [c for c in bonds_per_atom(bonds).values() if sum(c.values()) == 32]
    check(len(full) == summary["interior"] > 0,
          f"in space, {len(full)} atoms with 32 bonds, {summary['interior']} interior sites")
    check(all(c == {"1": 6, "2": 12, "3": 8, "4": 6} for c in full),
          "in space, an interior atom without 6, 12, 8 and 6 bonds at l0, sqrt 2, sqrt 3, 2 l0")
    return f"{len(atoms)} atoms, {len(bonds)} bonds, {len(full)} interior atoms with 32"


if __name__ == "__main__":
    main()
