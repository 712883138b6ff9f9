#!/usr/bin/python3
"""Peer comparison of the gas solver: Sod's shock tube with our solver
(bench/gas_sod) and with OpenFOAM's rhoCentralFoam, on the same grids, in
one run; run time against the L1 error of density.

  bench/compare_rhocentralfoam.py [--cells 100 200 400 800 1600] [--reps 3]
                                  [--maxco 0.1 0.2 0.5] [--out DIR]
                                  [--gas-sod PATH] [--keep-cases]

The problem (Toro's test 1): x in [0, 1], diaphragm at 0.5, left
rho = 1, u = 0, p = 1, right rho = 0.125, u = 0, p = 0.1, gamma = 1.4,
transmissive ends, t = 0.2. Error: mean over the cells of
|rho - rho_exact(x_centre, 0.2)|, the exact solution from the Riemann
solver in this file (Toro, ch. 4), for both codes alike.

Ours: build/release/bench/gas_sod --threads 1 --reps R N (MUSCL with van
Leer's limiter, HLLC, SSP-RK2, CFL 0.8); "seconds" is the median of its time
loops.

rhoCentralFoam: the case is OpenFOAM's compressible/rhoCentralFoam/shockTube
tutorial with its schemes and solver settings unchanged (Kurganov flux,
Euler explicit in time, vanLeer/vanLeerV reconstruction of rho, U, T,
adjustable time step with maxCo), made non-dimensional so that rho, u and p
are Sod's exactly:
  * the tutorial's block scaled by 1/10 and shifted: x in [0, 1], y and z in
    [-0.1, 0.1] (one cell, empty patches), N cells in x;
  * a perfect gas with R = 1/300 (molWeight = 300 * OpenFOAM's RR), Cp = 3.5 R,
    so gamma = 1.4 exactly, Hf = 0, mu = 0 (inviscid, as the tutorial);
  * setFields as the tutorial: p = 1, T = 300 (rho = 1) left, p = 0.1,
    T = 240 (rho = 0.125) for x > 0.5;
  * endTime 0.2 (written exactly: writeControl adjustable), the first
    deltaT = maxCo * dx / sqrt(1.4).
The script checks the tutorial's fvSchemes/fvSolution against its own when
the tutorial is installed, the initial pressure cell by cell, and the gas
constant the solver used (p / (rho T) at the end).

Courant numbers: rhoCentralFoam's own is 0.5 dt sum_faces(amaxSf) / V with
amaxSf the central scheme's largest |aphiv|, which for Kurganov's flux is
about half of dt (|u| + c)_max / dx (at rest: c/2 per face), the definition of
our CFL; so its maxCo 0.4 steps like our CFL 0.8. Both are reported, and
"cfl_standard" = (the exact solution's largest |u| + c) * (0.2 / steps) / dx
measures the mean step of both codes alike. The default maxCo values: 0.1,
the tutorial's 0.2, and 0.5 (the largest that runs to the end; 0.6 stops
with a floating-point exception).
"seconds" is the median wall time of the rhoCentralFoam process (serial;
blockMesh and setFields are run once before and not timed); "loop_seconds"
is the median wall time of its time loop alone (from its "Starting time
loop" line to its "End" line, timed as they come through a pipe; it leaves
out loading libraries, reading the case and building the thermo), to
compare time loops with ours.
"courant_max" is the largest "Courant Number" in its log (ours: the CFL).

Writes OUT/sod_comparison.csv (code, cells, steps, seconds, l1_density,
courant, then loop_seconds, courant_max, cfl_standard), OUT/sod_comparison.md
(the table printed to stdout, with the wall-time ratios at equal error) and
OUT/sod_error_vs_time.png; the OpenFOAM cases go to
OUT/rhoCentralFoam_cases/ (deleted at the end unless --keep-cases).
OpenFOAM is Debian's `openfoam` package (v1912): without it the script says
how to install it and exits 2. Runs one solver at a time.
"""
import argparse
import csv
import datetime
import glob
import json
import math
import os
import pathlib
import platform
import re
import shutil
import statistics
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parents[1]
GAMMA = 1.4
LEFT = (1.0, 0.0, 1.0)      # rho, u, p
RIGHT = (0.125, 0.0, 0.1)
X0, T_END = 0.5, 0.2
# OpenFOAM's universal gas constant, J/(kmol K): 1e3 * NA * k, NA from
# physicoChemicalConstants.C, k from etc/controlDict (v1912: 1.38065e-23).
RR = 1e3 * 6.0221417930e23 * 1.38065e-23
T_SCALE = 300.0             # T = T_SCALE * p / rho, i.e. R = 1 / T_SCALE
R_GAS = 1.0 / T_SCALE
CP = GAMMA / (GAMMA - 1.0) * R_GAS


def fail(message, code=1):
    print(f"compare_rhocentralfoam.py: {message}", file=sys.stderr)
    sys.exit(code)


# ---------------------------------------------------------------------------
# Exact Riemann solver for the Euler equations of an ideal gas (Toro, ch. 4).

class ExactRiemann:
    def __init__(self, left, right, gamma):
        self.g = gamma
        (self.rl, self.ul, self.pl), (self.rr, self.ur, self.pr) = left, right
        self.cl = math.sqrt(gamma * self.pl / self.rl)
        self.cr = math.sqrt(gamma * self.pr / self.rr)
        if 2.0 / (gamma - 1.0) * (self.cl + self.cr) <= self.ur - self.ul:
            raise ValueError("vacuum is generated")
        self.ps, self.us = self._star()

    def _f(self, p, rk, pk, ck):
        """Toro's f_K and its derivative."""
        g = self.g
        if p > pk:  # shock
            a, b = 2.0 / ((g + 1.0) * rk), (g - 1.0) / (g + 1.0) * pk
            q = math.sqrt(a / (p + b))
            return (p - pk) * q, q * (1.0 - 0.5 * (p - pk) / (b + p))
        f = 2.0 * ck / (g - 1.0) * ((p / pk) ** ((g - 1.0) / (2.0 * g)) - 1.0)
        return f, 1.0 / (rk * ck) * (p / pk) ** (-(g + 1.0) / (2.0 * g))

    def _star(self):
        g = self.g
        # two-rarefaction guess, then Newton
        z = (g - 1.0) / (2.0 * g)
        p = ((self.cl + self.cr - 0.5 * (g - 1.0) * (self.ur - self.ul))
             / (self.cl / self.pl ** z + self.cr / self.pr ** z)) ** (1.0 / z)
        for _ in range(100):
            fl, dl = self._f(p, self.rl, self.pl, self.cl)
            fr, dr = self._f(p, self.rr, self.pr, self.cr)
            pn = max(p - (fl + fr + self.ur - self.ul) / (dl + dr), 1e-14)
            if abs(pn - p) <= 1e-15 * (pn + p):
                p = pn
                break
            p = pn
        fl, _ = self._f(p, self.rl, self.pl, self.cl)
        fr, _ = self._f(p, self.rr, self.pr, self.cr)
        return p, 0.5 * (self.ul + self.ur) + 0.5 * (fr - fl)

    def sample(self, s):
        """(rho, u, p) at x / t = s."""
        g, ps, us = self.g, self.ps, self.us
        gm, gp = (g - 1.0) / (g + 1.0), 2.0 / (g + 1.0)
        if s <= us:  # left of the contact
            rk, uk, pk, ck = self.rl, self.ul, self.pl, self.cl
            if ps > pk:  # left shock
                sk = uk - ck * math.sqrt((g + 1.0) / (2.0 * g) * ps / pk + (g - 1.0) / (2.0 * g))
                if s <= sk:
                    return rk, uk, pk
                return rk * (ps / pk + gm) / (gm * ps / pk + 1.0), us, ps
            head, tail = uk - ck, us - ck * (ps / pk) ** ((g - 1.0) / (2.0 * g))
            if s <= head:
                return rk, uk, pk
            if s >= tail:
                return rk * (ps / pk) ** (1.0 / g), us, ps
            c = gp * (ck + (g - 1.0) / 2.0 * (uk - s))
            return (rk * (c / ck) ** (2.0 / (g - 1.0)), gp * (ck + (g - 1.0) / 2.0 * uk + s),
                    pk * (c / ck) ** (2.0 * g / (g - 1.0)))
        rk, uk, pk, ck = self.rr, self.ur, self.pr, self.cr
        if ps > pk:  # right shock
            sk = uk + ck * math.sqrt((g + 1.0) / (2.0 * g) * ps / pk + (g - 1.0) / (2.0 * g))
            if s >= sk:
                return rk, uk, pk
            return rk * (ps / pk + gm) / (gm * ps / pk + 1.0), us, ps
        head, tail = uk + ck, us + ck * (ps / pk) ** ((g - 1.0) / (2.0 * g))
        if s >= head:
            return rk, uk, pk
        if s <= tail:
            return rk * (ps / pk) ** (1.0 / g), us, ps
        c = gp * (ck - (g - 1.0) / 2.0 * (uk - s))
        return (rk * (c / ck) ** (2.0 / (g - 1.0)), gp * (-ck + (g - 1.0) / 2.0 * uk + s),
                pk * (c / ck) ** (2.0 * g / (g - 1.0)))


EXACT = ExactRiemann(LEFT, RIGHT, GAMMA)
# the exact solution's largest |u| + c (the star state right of the contact)
S_MAX = max(abs(u) + math.sqrt(GAMMA * p / r)
            for r, u, p in (EXACT.sample(k / 1000.0) for k in range(-4000, 4001)))


def cfl_standard(n, steps):
    """dt max(|u| + c) / dx with the mean dt and the exact largest speed:
    one measure of the step for both codes."""
    return S_MAX * (T_END / steps) * n


def l1_density(rho):
    """Mean over the N cells of |rho - rho_exact| at the cell centres, t = 0.2."""
    n = len(rho)
    return sum(abs(r - EXACT.sample(((i + 0.5) / n - X0) / T_END)[0])
               for i, r in enumerate(rho)) / n


# ---------------------------------------------------------------------------
# Our solver

def run_ours(gas_sod, n, reps):
    r = subprocess.run([str(gas_sod), "--reps", str(reps), "--threads", "1", str(n)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{gas_sod} failed (exit {r.returncode}):\n{r.stdout}\n{r.stderr}")
    row = json.loads(r.stdout.strip().splitlines()[-1])
    if row["cells"] != n:
        fail(f"gas_sod answered for {row['cells']} cells, not {n}")
    return {"code": "ours", "cells": n, "steps": row["steps"], "seconds": row["seconds"],
            "loop_seconds": row["seconds"], "l1_density": row["l1_density"],
            "courant": row["cfl"], "courant_max": row["cfl"]}


# ---------------------------------------------------------------------------
# OpenFOAM

BASHRC_CANDIDATES = [
    "/usr/share/openfoam/etc/bashrc",              # Debian's openfoam package
    "/usr/lib/openfoam/openfoam*/etc/bashrc",      # openfoam.com packages
    "/opt/openfoam*/etc/bashrc",                   # openfoam.org packages
    "/opt/OpenFOAM*/etc/bashrc",
]
TUTORIAL_CANDIDATES = [
    "/usr/share/doc/openfoam-examples/examples/compressible/rhoCentralFoam/shockTube",
    "/usr/share/openfoam*/tutorials/compressible/rhoCentralFoam/shockTube",
    "/usr/lib/openfoam/openfoam*/tutorials/compressible/rhoCentralFoam/shockTube",
]
INSTALL_HELP = """OpenFOAM's rhoCentralFoam was not found. This comparison uses Debian's
OpenFOAM v1912 package (an optional benchmark dependency, not installed by
scripts/install_deps.sh). Install it as root with

    apt-get update && apt-get install -y openfoam

(it puts rhoCentralFoam, blockMesh and setFields in /usr/bin and the
environment in /usr/share/openfoam/etc/bashrc; the tutorials come with the
recommended openfoam-examples package), then rerun this script."""


def openfoam_env():
    """The environment of OpenFOAM's etc/bashrc (None when not installed)."""
    bashrc = None
    if os.environ.get("WM_PROJECT_DIR"):
        c = pathlib.Path(os.environ["WM_PROJECT_DIR"]) / "etc" / "bashrc"
        if c.is_file():
            bashrc = str(c)
    for pattern in BASHRC_CANDIDATES:
        if bashrc:
            break
        found = sorted(glob.glob(pattern))
        bashrc = found[-1] if found else None
    if not bashrc:
        return None, None
    r = subprocess.run(["bash", "-c", f'source "{bashrc}" >/dev/null 2>&1; env -0'],
                       capture_output=True)
    env = dict(kv.split("=", 1) for kv in r.stdout.decode().split("\0") if "=" in kv)
    if not shutil.which("rhoCentralFoam", path=env.get("PATH", "")):
        return None, bashrc
    return env, bashrc


def foam_header(cls, obj, location=None):
    loc = f'    location    "{location}";\n' if location else ""
    return ("FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
            f"    class       {cls};\n{loc}    object      {obj};\n}}\n\n")


# The tutorial's settings, unchanged (v1912 shockTube): fvSchemes,
# fvSolution, turbulenceProperties and the thermo type.
FV_SCHEMES = """fluxScheme      Kurganov;

ddtSchemes
{
    default         Euler;
}

gradSchemes
{
    default         Gauss linear;
}

divSchemes
{
    default         none;
    div(tauMC)      Gauss linear;
}

laplacianSchemes
{
    default         Gauss linear corrected;
}

interpolationSchemes
{
    default         linear;
    reconstruct(rho) vanLeer;
    reconstruct(U)  vanLeerV;
    reconstruct(T)  vanLeer;
}

snGradSchemes
{
    default         corrected;
}
"""

FV_SOLUTION = """solvers
{
    "(rho|rhoU|rhoE)"
    {
        solver          diagonal;
    }

    U
    {
        solver          smoothSolver;
        smoother        GaussSeidel;
        nSweeps         2;
        tolerance       1e-09;
        relTol          0.01;
    }

    h
    {
        $U;
        tolerance       1e-10;
        relTol          0;
    }
}
"""


def thermo_properties():
    return f"""thermoType
{{
    type            hePsiThermo;
    mixture         pureMixture;
    transport       const;
    thermo          hConst;
    equationOfState perfectGas;
    specie          specie;
    energy          sensibleInternalEnergy;
}}

mixture
{{
    specie
    {{
        molWeight       {T_SCALE * RR!r};  // R = RR / molWeight = 1/{T_SCALE:g}
    }}
    thermodynamics
    {{
        Cp              {CP!r};  // gamma R / (gamma - 1): gamma = {GAMMA}
        Hf              0;
    }}
    transport
    {{
        mu              0;
        Pr              1;
    }}
}}
"""


def block_mesh(n):
    return f"""scale   1;

vertices
(
    (0 -0.1 -0.1)
    (1 -0.1 -0.1)
    (1 0.1 -0.1)
    (0 0.1 -0.1)
    (0 -0.1 0.1)
    (1 -0.1 0.1)
    (1 0.1 0.1)
    (0 0.1 0.1)
);

blocks
(
    hex (0 1 2 3 4 5 6 7) ({n} 1 1) simpleGrading (1 1 1)
);

edges
(
);

boundary
(
    sides
    {{
        type patch;
        faces
        (
            (1 2 6 5)
            (0 4 7 3)
        );
    }}
    empty
    {{
        type empty;
        faces
        (
            (0 1 5 4)
            (5 6 7 4)
            (3 7 6 2)
            (0 3 2 1)
        );
    }}
);

mergePatchPairs
(
);
"""


def set_fields_dict():
    rl, _, pl = LEFT
    rr, _, pr = RIGHT
    return (f"defaultFieldValues\n(\n    volVectorFieldValue U (0 0 0)\n"
            f"    volScalarFieldValue T {T_SCALE * pl / rl!r}\n"
            f"    volScalarFieldValue p {pl!r}\n);\n\n"
            f"regions\n(\n    boxToCell\n    {{\n        box ({X0} -1 -1) (2 1 1);\n"
            f"        fieldValues\n        (\n"
            f"            volScalarFieldValue T {T_SCALE * pr / rr!r}\n"
            f"            volScalarFieldValue p {pr!r}\n        );\n    }}\n);\n")


def control_dict(end_time, delta_t, max_co):
    return f"""application     rhoCentralFoam;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         {end_time!r};
deltaT          {delta_t!r};
writeControl    adjustable;
writeInterval   {T_END!r};
purgeWrite      0;
writeFormat     ascii;
writePrecision  12;
writeCompression off;
timeFormat      general;
timePrecision   6;
runTimeModifiable true;
adjustTimeStep  yes;
maxCo           {max_co!r};
maxDeltaT       1;
"""


def initial_field(name, cls, dims, value):
    return foam_header(cls, name) + f"""dimensions      {dims};

internalField   uniform {value};

boundaryField
{{
    sides
    {{
        type            zeroGradient;
    }}
    empty
    {{
        type            empty;
    }}
}}
"""


def write(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def foam_run(env, case, app, log):
    """Runs an OpenFOAM application on the case, its output to case/log.
    Returns its exit status, its wall time and the wall time of its time
    loop: from its "Starting time loop" line to its "End" line, as they
    arrive through a pipe (OpenFOAM flushes each line; None without them)."""
    marks = {}
    with open(case / log, "w") as f:
        start = time.perf_counter()
        proc = subprocess.Popen([app, "-case", str(case)], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, env=env, text=True, bufsize=1)
        for line in proc.stdout:
            if line.startswith("Starting time loop") or line.startswith("End"):
                marks.setdefault(line.split()[0], time.perf_counter())
            f.write(line)
        rc = proc.wait()
        seconds = time.perf_counter() - start
    loop = marks["End"] - marks["Starting"] if len(marks) == 2 else None
    return rc, seconds, loop


def read_internal_field(path):
    text = path.read_text()
    m = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\(", text)
    if m:
        n = int(m.group(1))
        values = text[m.end():].split(")", 1)[0].split()
        if len(values) != n:
            raise ValueError(f"{path}: {len(values)} values, header says {n}")
        return [float(v) for v in values]
    m = re.search(r"internalField\s+uniform\s+([^;\s]+)\s*;", text)
    if m:
        return float(m.group(1))
    raise ValueError(f"{path}: no internalField")


def make_case(env, case, n, max_co):
    """The case directory with mesh and initial fields (blockMesh, setFields)."""
    if case.exists():
        shutil.rmtree(case)
    dx = 1.0 / n
    dt0 = max_co * dx / math.sqrt(GAMMA * LEFT[2] / LEFT[0])
    write(case / "system" / "controlDict",
          foam_header("dictionary", "controlDict", "system") + control_dict(T_END, dt0, max_co))
    write(case / "system" / "fvSchemes",
          foam_header("dictionary", "fvSchemes", "system") + FV_SCHEMES)
    write(case / "system" / "fvSolution",
          foam_header("dictionary", "fvSolution", "system") + FV_SOLUTION)
    write(case / "system" / "blockMeshDict",
          foam_header("dictionary", "blockMeshDict") + block_mesh(n))
    write(case / "system" / "setFieldsDict",
          foam_header("dictionary", "setFieldsDict", "system") + set_fields_dict())
    write(case / "constant" / "thermophysicalProperties",
          foam_header("dictionary", "thermophysicalProperties", "constant")
          + thermo_properties())
    write(case / "constant" / "turbulenceProperties",
          foam_header("dictionary", "turbulenceProperties", "constant")
          + "simulationType  laminar;\n")
    write(case / "0" / "T", initial_field("T", "volScalarField", "[0 0 0 1 0 0 0]", 1))
    write(case / "0" / "p", initial_field("p", "volScalarField", "[1 -1 -2 0 0 0 0]", 0))
    write(case / "0" / "U", initial_field("U", "volVectorField", "[0 1 -1 0 0 0 0]", "(0 0 0)"))
    for app in ("blockMesh", "setFields"):
        rc, _, _ = foam_run(env, case, app, f"log.{app}")
        if rc != 0:
            fail(f"{app} failed in {case} (exit {rc}); see {case}/log.{app}")
    # the initial state, cell by cell (blockMesh numbers the cells along x)
    p0 = read_internal_field(case / "0" / "p")
    want = [LEFT[2]] * (n // 2) + [RIGHT[2]] * (n - n // 2)
    if (not isinstance(p0, list) or len(p0) != n
            or any(abs(a - b) > 1e-12 for a, b in zip(p0, want))):
        fail(f"setFields did not give Sod's initial pressure in {case}")


def clear_results(case):
    for d in case.iterdir():
        if d.is_dir() and d.name not in ("0", "constant", "system"):
            try:
                float(d.name)
            except ValueError:
                continue
            shutil.rmtree(d)


def run_openfoam(env, cases, n, max_co, reps):
    """Median wall time of rhoCentralFoam on an N-cell tube, its error, steps."""
    case = cases / f"N{n}_Co{max_co:g}"
    make_case(env, case, n, max_co)
    walls, loops = [], []
    failed = False
    for _ in range(reps):
        clear_results(case)
        rc, seconds, loop = foam_run(env, case, "rhoCentralFoam", "log.rhoCentralFoam")
        if rc != 0 or loop is None:
            failed = True
            break
        walls.append(seconds)
        loops.append(loop)
    log = (case / "log.rhoCentralFoam").read_text(errors="replace")
    steps = len(re.findall(r"^Time = ", log, flags=re.M))
    courants = [float(c) for c in re.findall(r"Mean and max Courant Numbers = \S+ (\S+)", log)]
    row = {"code": "rhoCentralFoam", "cells": n, "steps": steps, "courant": max_co,
           "courant_max": max(courants) if courants else float("nan")}
    end_dir = case / f"{T_END:g}"
    if failed or not (end_dir / "rho").is_file():
        row.update(seconds=float("nan"), loop_seconds=float("nan"), l1_density=float("nan"),
                   failed=True)
        return row
    rho = read_internal_field(end_dir / "rho")
    p = read_internal_field(end_dir / "p")
    t = read_internal_field(end_dir / "T")
    if not all(math.isfinite(r) and r > 0 for r in rho):
        row.update(seconds=float("nan"), loop_seconds=float("nan"), l1_density=float("nan"),
                   failed=True)
        return row
    # the gas constant the solver used: p = rho R T
    r_used = statistics.fmean(pi / (ri * ti) for pi, ri, ti in zip(p, rho, t))
    if abs(r_used / R_GAS - 1.0) > 1e-8:
        fail(f"rhoCentralFoam's gas constant is {r_used}, not {R_GAS} (RR changed?)")
    wall = statistics.median(walls)
    row.update(seconds=wall, loop_seconds=statistics.median(loops),
               l1_density=l1_density(rho), failed=False)
    return row


def check_tutorial():
    """Says whether the installed tutorial's fvSchemes/fvSolution are ours."""
    def strip(text):
        text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
        text = re.sub(r"//[^\n]*", "", text)
        text = re.sub(r"FoamFile\s*\{[^}]*\}", "", text)
        return " ".join(text.split())
    for pattern in TUTORIAL_CANDIDATES:
        for d in sorted(glob.glob(pattern)):
            d = pathlib.Path(d)
            same = [strip((d / "system" / f).read_text()) == strip(ours)
                    for f, ours in (("fvSchemes", FV_SCHEMES), ("fvSolution", FV_SOLUTION))
                    if (d / "system" / f).is_file()]
            if same:
                verdict = "same fvSchemes and fvSolution" if all(same) else "DIFFERENT settings"
                return f"{d} ({verdict})"
    return "not installed (settings as in v1912's tutorial)"


# ---------------------------------------------------------------------------
# Report

def interp_time(rows, error, key):
    """Wall time at this error: log-time linear in log-error between
    consecutive grids; where several grid intervals reach the error (the
    error need not fall monotonically with the grid), the least time."""
    rows = sorted((r for r in rows if not r["failed"] and r[key] > 0 and r["l1_density"] > 0),
                  key=lambda r: r["cells"])
    le, best = math.log(error), None
    for a, b in zip(rows, rows[1:]):
        x0, y0 = math.log(a["l1_density"]), math.log(a[key])
        x1, y1 = math.log(b["l1_density"]), math.log(b[key])
        if min(x0, x1) <= le <= max(x0, x1):
            y = y0 if x1 == x0 else y0 + (le - x0) / (x1 - x0) * (y1 - y0)
            best = y if best is None else min(best, y)
    return None if best is None else math.exp(best)


def time_ratios(ours, theirs, key):
    """rhoCentralFoam's time / ours at equal error, at each error level of
    either code that both codes reach between their grids."""
    levels = sorted({r["l1_density"] for r in ours + theirs if not r["failed"]}, reverse=True)
    out = []
    for e in levels:
        a, b = interp_time(ours, e, "seconds"), interp_time(theirs, e, key)
        if a and b:
            out.append((e, b / a))
    return out


def fmt(x, digits=3):
    if isinstance(x, float) and not math.isfinite(x):
        return "failed"
    return f"{x:.{digits}g}"


def machine_facts():
    cpu = platform.processor() or "?"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"nproc": os.cpu_count(), "cpu": cpu, "os": platform.platform(),
            "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds")}


def plot(path, ours, foam_sets):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(matplotlib missing: no figure)", file=sys.stderr)
        return False
    plt.rcParams.update({"font.size": 10, "font.family": "serif", "mathtext.fontset": "dejavuserif",
                         "axes.linewidth": 0.8, "xtick.direction": "in",
                         "ytick.direction": "in", "xtick.top": True, "ytick.right": True,
                         "legend.fontsize": 8})
    fig, ax = plt.subplots(figsize=(6.4, 6.0))
    ok = [r for r in ours if not r["failed"]]
    ax.loglog([r["seconds"] for r in ok], [r["l1_density"] for r in ok], "o-", color="black",
              lw=1.8, ms=5, zorder=5,
              label=f"ours: MUSCL–HLLC, SSP-RK2, CFL {ok[0]['courant']:g} (time loop)")
    for r in ok:
        ax.annotate(f"{r['cells']}", (r["seconds"], r["l1_density"]), textcoords="offset points",
                    xytext=(3, -4), fontsize=7, ha="left", va="top")
    colours = ["tab:blue", "tab:red", "tab:orange", "tab:green", "tab:purple"]
    for k, (co, rows) in enumerate(foam_sets):
        rows = [r for r in rows if not r["failed"]]
        if not rows:
            continue
        c = colours[k % len(colours)]
        cfl = statistics.fmean(r["cfl_standard"] for r in rows)
        ax.loglog([r["seconds"] for r in rows], [r["l1_density"] for r in rows], "s-", color=c,
                  lw=1.5, ms=5,
                  label=f"rhoCentralFoam, maxCo {co:g} (CFL ≈ {cfl:.2f}): process")
        loop = [r for r in rows if r["loop_seconds"] > 0]
        ax.loglog([r["loop_seconds"] for r in loop], [r["l1_density"] for r in loop], "s--",
                  color=c, mfc="white", lw=1.0, ms=4.5,
                  label=f"rhoCentralFoam, maxCo {co:g}: time loop only")
        for r in rows:
            ax.annotate(f"{r['cells']}", (r["seconds"], r["l1_density"]),
                        textcoords="offset points", xytext=(4, 2 if k % 2 == 0 else -8),
                        fontsize=6.5, color=c)
    ax.set_xlabel("wall time on 1 core [s]")
    ax.set_ylabel(r"$L_1$ error of density, mean over cells")
    ax.set_title("Sod shock tube at t = 0.2 (point labels: cells)", fontsize=10)
    ax.grid(True, which="major", lw=0.5, alpha=0.5)
    ax.grid(True, which="minor", lw=0.25, alpha=0.3)
    ax.legend(frameon=False, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1)
    fig.tight_layout()
    fig.savefig(path, dpi=200)
    plt.close(fig)
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cells", type=int, nargs="+", default=[100, 200, 400, 800, 1600])
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--maxco", type=float, nargs="+", default=[0.1, 0.2, 0.5],
                    help="rhoCentralFoam's maxCo values (default 0.1, the tutorial's 0.2, and "
                         "0.5, the largest that runs to the end)")
    ap.add_argument("--out", type=pathlib.Path, default=REPO / "out" / "sod_comparison")
    ap.add_argument("--gas-sod", type=pathlib.Path,
                    default=REPO / "build" / "release" / "bench" / "gas_sod")
    ap.add_argument("--keep-cases", action="store_true", help="keep the OpenFOAM case folders")
    args = ap.parse_args()
    if any(n < 2 or n % 2 for n in args.cells):
        fail("--cells: even numbers of cells (the diaphragm on a face)")
    if args.reps < 1:
        fail("--reps: at least 1")

    env, bashrc = openfoam_env()
    if env is None:
        print(INSTALL_HELP, file=sys.stderr)
        if bashrc:
            print(f"(found {bashrc}, but no rhoCentralFoam on its PATH)", file=sys.stderr)
        sys.exit(2)
    if not args.gas_sod.is_file():
        fail(f"no {args.gas_sod}: build it with "
             "`cmake --build --preset release --target gas_sod`, or give --gas-sod PATH")
    args.out.mkdir(parents=True, exist_ok=True)
    cases = args.out / "rhoCentralFoam_cases"
    facts = machine_facts()
    version = env.get("WM_PROJECT_VERSION", "?")
    tutorial = check_tutorial()
    print(f"# Sod shock tube: ours vs OpenFOAM {version} rhoCentralFoam", flush=True)
    print(f"# {facts['date']}; {facts['nproc']} CPUs: {facts['cpu']}; {facts['os']}", flush=True)
    print(f"# OpenFOAM environment: {bashrc}; tutorial: {tutorial}", flush=True)

    ours, foam = [], {co: [] for co in args.maxco}
    for n in args.cells:  # one solver at a time, grid by grid (the load hits both alike)
        r = run_ours(args.gas_sod, n, args.reps)
        r["failed"] = False
        r["cfl_standard"] = cfl_standard(n, r["steps"])
        ours.append(r)
        print(f"  ours           N={n:5d}: {r['steps']:5d} steps {r['seconds']:.4g} s "
              f"L1 {r['l1_density']:.4g}", flush=True)
        for co in args.maxco:
            r = run_openfoam(env, cases, n, co, args.reps)
            r["cfl_standard"] = cfl_standard(n, r["steps"])
            foam[co].append(r)
            print(f"  rhoCentralFoam N={n:5d} maxCo {co:g}: {r['steps']:5d} steps "
                  f"{fmt(r['seconds'], 4)} s (loop {fmt(r['loop_seconds'], 4)} s) "
                  f"L1 {fmt(r['l1_density'], 4)}, its max Co {r['courant_max']:.3g}, "
                  f"CFL {r['cfl_standard']:.3g}", flush=True)
    if not args.keep_cases:
        shutil.rmtree(cases, ignore_errors=True)

    rows = ours + [r for co in args.maxco for r in foam[co]]
    fields = ["code", "cells", "steps", "seconds", "l1_density", "courant", "loop_seconds",
              "courant_max", "cfl_standard"]
    with open(args.out / "sod_comparison.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(fields)
        for r in rows:
            w.writerow([r["code"], r["cells"], r["steps"], f"{r['seconds']:.6g}",
                        f"{r['l1_density']:.6g}", f"{r['courant']:g}",
                        f"{r['loop_seconds']:.6g}", f"{r['courant_max']:.4g}",
                        f"{r['cfl_standard']:.4g}"])

    md = [f"Sod shock tube (Toro test 1, t = 0.2): ours vs OpenFOAM {version} rhoCentralFoam, "
          f"serial, median wall time of {args.reps} runs; {facts['date']}; "
          f"{facts['nproc']} CPUs: {facts['cpu']}.", ""]
    md.append("| code | Courant (own) | CFL | cells | steps | wall s | loop s | L1(rho) "
              "| wall / ours | loop / ours |")
    md.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    by_n = {r["cells"]: r for r in ours}
    for r in rows:
        o = by_n[r["cells"]]
        name = "ours" if r["code"] == "ours" else "rhoCentralFoam"
        md.append(f"| {name} | {r['courant']:g} | {r['cfl_standard']:.2f} | {r['cells']} | "
                  f"{r['steps']} | {fmt(r['seconds'])} | {fmt(r['loop_seconds'])} | "
                  f"{fmt(r['l1_density'])} | {fmt(r['seconds'] / o['seconds'])} | "
                  f"{fmt(r['loop_seconds'] / o['seconds'])} |")
    md.append("")
    md.append(
        "Courant (own): each code's limit. Ours: CFL = dt max(|u| + c) / dx. rhoCentralFoam: "
        "maxCo on its own Courant number, 0.5 dt sum_faces(max|aphiv|) / V, about half of "
        "dt max(|u| + c) / dx. CFL: the same measure for both, "
        f"{S_MAX:.4f} (the exact solution's largest |u| + c) x mean dt / dx. "
        "Ours: MUSCL/van Leer, HLLC, SSP-RK2; 'wall s' is its time loop. rhoCentralFoam: "
        "the shockTube tutorial's schemes (Kurganov flux, Euler, vanLeer on rho and T, "
        "vanLeerV on U), adjustable dt; 'wall s' is the process (no blockMesh/setFields), "
        "'loop s' its time loop alone (its log's 'Starting time loop' to 'End'). "
        "Largest Courant number rhoCentralFoam reported: " +
        ", ".join(f"maxCo {co:g}: {max((r['courant_max'] for r in foam[co]), default=0):.3g}"
                  for co in args.maxco) + ".")
    md.append("")
    md.append("Wall-time ratio rhoCentralFoam / ours at equal L1 error (log time linear in "
              "log error between consecutive grids, at each grid's error that both reach):")
    md.append("")
    for co in args.maxco:
        for key, what in (("seconds", "process"), ("loop_seconds", "time loop")):
            ratios = time_ratios(ours, foam[co], key)
            if ratios:
                gm = math.exp(statistics.fmean(math.log(q) for _, q in ratios))
                md.append(f"- maxCo {co:g}, {what}: " +
                          ", ".join(f"{q:.3g}x at {e:.3g}" for e, q in ratios) +
                          f"; geometric mean {gm:.3g}x")
            else:
                md.append(f"- maxCo {co:g}, {what}: no error level that both reach")
    text = "\n".join(md)
    print()
    print(text)
    (args.out / "sod_comparison.md").write_text(text + "\n")
    if plot(args.out / "sod_error_vs_time.png", ours, [(co, foam[co]) for co in args.maxco]):
        print(f"\nwrote {args.out / 'sod_comparison.csv'}, {args.out / 'sod_comparison.md'}, "
              f"{args.out / 'sod_error_vs_time.png'}")


if __name__ == "__main__":
    main()
