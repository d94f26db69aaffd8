#!/usr/bin/env python3
"""Frontier study: accuracy against wall time for feps's solution settings.

    python3 scripts/study_tradeoff.py --quick             # a tiny subset (about a minute)
    python3 scripts/study_tradeoff.py                     # block, interface, FE1, model C
    python3 scripts/study_tradeoff.py --scenes block interface
    python3 scripts/study_tradeoff.py --plots-only        # redo plots and tables from the CSVs

For each scene it runs feps over a grid of settings (solution preset --method, number of steps
STEPS=, tolerance DELTA1= in the STAGE record, element type and mesh density, --solver) and
records the wall time (elapsed, median of the repeats), iterations, refactorizations, cut-backs,
peak memory (/usr/bin/time -f %M, kB) and the relative error of the result against a reference:

    block      thesis 2.4.3 Matsuoka-Nakai block in uniaxial compression; the final sigma_z
               against the closed-form plateau fc = 2 c cos(phi) / (1 - sin(phi)) = 15.7112 MPa
    interface  thesis 2.3.4a; the final interface shear tau at u = 0.2 against the closed form
               tau_y + ks kn t^2 / (ks + kn t^2) (0.2 - u_y), t = tan(26.57 deg) (133.3573; the
               thesis's 133.33 is the same formula with t = 1/2 exactly)
    fe1        model B FE1 (input/modelB.dat); /summary rotation_deflection_deg against the
               finest run (most steps, tightest tolerance); Richardson extrapolation as a check
    modelc     model C C_G300_nu0.4_b0.27 with 6 deg elements beyond theta = 12 (make_model_c.py
               --theta-step 6; 21864 DOFs); sigma_max, the joint's edge stress of thesis 7.4.3 read
               from the interface (scripts/postprocess_model_c.py), against the finest run
    ch9        chapter 9 CR (Matsuoka-Nakai concrete at its tensile cap, 4810 DOFs) under the
               thesis's tension rule and under TENSION=closest-point (the "mesh" column names the
               rule); the largest principal stress against the finest run

feps is fpm's release build (built if needed, as the campaign scripts do) unless --feps names an
executable. Every feps process runs under `nice -n 5`, one at a time. Runs that take less than
--repeat-below seconds are repeated --repeats times and the median time is kept. Results go to
OUT/<scene>.csv (one row per setting; existing rows are reused with --resume), plots to
OUT/<scene>_pareto.png and OUT/fe1_steps.png, tables to OUT/tables.md.

A setting whose run stops with feps's clear message that a step does not converge is a result
(status "failed: ..." in the CSV, listed in the tables). Any other failure (feps crashed, refused
the deck, could not write its results) is an error: the outputs are written all the same and the
exit status is 1.
"""
import argparse
import csv
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from feps_cli import Error, feps_option, guard  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRESETS = ["euler", "modified-euler", "newton-raphson", "modified-newton-raphson", "initial-stiffness"]
# full Newton (not in the thesis) joins the model B FE1 and model C plans only
ALL_METHODS = PRESETS + ["full-newton-raphson"]
SHORT = {"euler": "E", "modified-euler": "ME", "newton-raphson": "NR",
         "modified-newton-raphson": "MNR", "initial-stiffness": "IS", "full-newton-raphson": "FNR"}
ITERATIVE = ("newton-raphson", "modified-newton-raphson", "initial-stiffness", "full-newton-raphson")
ALL_STEPS = [10, 25, 50, 100, 250, 500, 1000]
ERROR_FLOOR = 1e-12          # errors below this are plotted on the floor (exact to round-off)
MODEL_C = "C_G300_nu0.4_b0.27"   # with 6 deg elements beyond theta = 12, the mesh of this study
SCENES = ["block", "interface", "fe1", "modelc", "ch9"]

FIELDS = ["scene", "mesh", "element", "dofs", "method", "steps", "tol", "solver", "status",
          "wall_s", "wall_runs", "feps_wall_s", "iterations", "factorizations", "cutbacks",
          "peak_kb", "value", "reference", "reference_kind", "rel_error"]


# ----------------------------------------------------------------------------------------------
# closed forms
# ----------------------------------------------------------------------------------------------
def block_plateau():
    """Uniaxial compressive strength of the modified Matsuoka-Nakai surface (it meets
    Mohr-Coulomb on the compression meridian): M = ft/2 (1 + 1/sin phi), c = M tan phi."""
    phi = math.radians(26.57)
    apex = 6.0 / 2.0 * (1.0 + 1.0 / math.sin(phi))
    c = apex * math.tan(phi)
    return -2.0 * c * math.cos(phi) / (1.0 - math.sin(phi))


def interface_tau(u=0.2, phi_deg=26.57, kn=2000.0, ks=1000.0, sigma0=200.0):
    """Sliding with dilation psi = phi against a held top (thesis 2.3.4a)."""
    t = math.tan(math.radians(phi_deg))
    tau_y = sigma0 * t
    u_y = tau_y / ks
    if u <= u_y:
        return ks * u
    return tau_y + ks * kn * t * t / (ks + kn * t * t) * (u - u_y)


# ----------------------------------------------------------------------------------------------
# deck generators
# ----------------------------------------------------------------------------------------------
def _fmt(x):
    return f"{x:.10g}" + ("." if float(x).is_integer() else "")


def block_deck(element, n, steps, tol, method):
    """The 10 mm Matsuoka-Nakai block of input/verification/sec2_4_3_compression.dat with
    n x n x n/2 elements (n even; n = 2 is the thesis's four-element block). hex20 uses a
    (2n+1)-node lattice like test/data/patch_hex20.dat (face and body centres unused)."""
    nx, ny, nz = n, n, max(1, n // 2)
    lines = [f"TITLE, tradeoff study: Matsuoka-Nakai block {element} {nx}x{ny}x{nz}"]
    if element == "hex8":
        lx, ly = nx + 1, ny + 1
        lxy = lx * ly
        lines += ["A, 2, 0., 0., 0.,",
                  f"%, {nx + 1}, {_fmt(10.0 / nx)}, 0., 0.,",
                  f"%, {ny + 1}, 0., {_fmt(10.0 / ny)}, 0.,",
                  f"%, {nz + 1}, 0., 0., {_fmt(10.0 / nz)},",
                  "E,",
                  "GROUP, block, TYPE=hex8, MATERIAL=concrete",
                  f"A, 8, 1, 2, {2 + lx}, {1 + lx}, {1 + lxy}, {2 + lxy}, {2 + lx + lxy}, {1 + lx + lxy},",
                  f"%, {nx}, *, 8, 1,", f"%, {ny}, *, 8, {lx},", f"%, {nz}, *, 8, {lxy},",
                  "E,", "E,"]
    else:
        lx, ly = 2 * nx + 1, 2 * ny + 1
        lxy = lx * ly

        def idx(i, j, k):
            return 1 + i + j * lx + k * lxy
        corners = [(0, 0), (2, 0), (2, 2), (0, 2)]
        mids = [(1, 0), (2, 1), (1, 2), (0, 1)]
        conn = ([idx(i, j, 0) for i, j in corners] + [idx(i, j, 2) for i, j in corners]
                + [idx(i, j, 0) for i, j in mids] + [idx(i, j, 2) for i, j in mids]
                + [idx(i, j, 1) for i, j in corners])
        lines += ["A, 2, 0., 0., 0.,",
                  f"%, {lx}, {_fmt(5.0 / nx)}, 0., 0.,",
                  f"%, {ly}, 0., {_fmt(5.0 / ny)}, 0.,",
                  f"%, {2 * nz + 1}, 0., 0., {_fmt(5.0 / nz)},",
                  "E,",
                  "GROUP, block, TYPE=hex20, MATERIAL=concrete",
                  "A, 20, " + ", ".join(map(str, conn[:10])) + ",",
                  ", ".join(map(str, conn[10:])) + ",",
                  f"%, {nx}, *, 20, 2,", f"%, {ny}, *, 20, {2 * lx},", f"%, {nz}, *, 20, {2 * lxy},",
                  "E,", "E,"]
    lines += ["MATERIAL, concrete, MATSUOKA, E=10000., NU=0.2, PHI=26.57, PSI=26.57, FT=6.",
              "NSET, base, Z=0.", "NSET, corner, X=0., Y=0., Z=0.", "NSET, edge, X=10., Y=0., Z=0.",
              "NSET, top, Z=10.", "FIX, base, Z", "FIX, corner, X, Y", "FIX, edge, Y",
              f"STAGE, load, STEPS={steps}, METHOD={method}, DELTA1={tol:g}",
              "DISPLACE, top, Z=-0.04"]
    return "\n".join(lines) + "\n"


def interface_deck(element, n, steps, tol, method):
    """input/verification/sec2_3_4a.dat with n x n elements in plan per block (one through the
    height) and n x n interface elements; hex20 blocks take interface-quad8 (lattice nodes)."""
    lines = [f"TITLE, tradeoff study: sec2.3.4a {element} {n}x{n}"]
    if element == "hex8":
        lx = n + 1
        lxy = lx * lx
        nblock = 2 * lxy
        for z0 in (0.0, 10.0):
            lines += [f"A, 2, 0., 0., {_fmt(z0)},", f"%, {lx}, {_fmt(10.0 / n)}, 0., 0.,",
                      f"%, {lx}, 0., {_fmt(10.0 / n)}, 0.,", "%, 2, 0., 0., 10.,", "E,"]
        base = [1, 2, 2 + lx, 1 + lx]
        for name, off in (("lower", 0), ("upper", nblock)):
            conn = [off + b for b in base] + [off + lxy + b for b in base]
            lines += [f"GROUP, {name}, TYPE=hex8, MATERIAL=rigid",
                      "A, 8, " + ", ".join(map(str, conn)) + ",",
                      f"%, {n}, *, 8, 1,", f"%, {n}, *, 8, {lx},", "E,"]
        conn = [lxy + b for b in base] + [nblock + b for b in base]
        lines += ["GROUP, joint, TYPE=interface-quad4, MATERIAL=contact",
                  "A, 8, " + ", ".join(map(str, conn)) + ",",
                  f"%, {n}, *, 8, 1,", f"%, {n}, *, 8, {lx},", "E,", "E,"]
    else:
        lx = 2 * n + 1
        lxy = lx * lx
        nblock = 3 * lxy

        def idx(i, j, k, off=0):
            return off + 1 + i + j * lx + k * lxy
        corners = [(0, 0), (2, 0), (2, 2), (0, 2)]
        mids = [(1, 0), (2, 1), (1, 2), (0, 1)]
        for z0 in (0.0, 10.0):
            lines += [f"A, 2, 0., 0., {_fmt(z0)},", f"%, {lx}, {_fmt(5.0 / n)}, 0., 0.,",
                      f"%, {lx}, 0., {_fmt(5.0 / n)}, 0.,", "%, 3, 0., 0., 5.,", "E,"]
        for name, off in (("lower", 0), ("upper", nblock)):
            conn = ([idx(i, j, 0, off) for i, j in corners] + [idx(i, j, 2, off) for i, j in corners]
                    + [idx(i, j, 0, off) for i, j in mids] + [idx(i, j, 2, off) for i, j in mids]
                    + [idx(i, j, 1, off) for i, j in corners])
            lines += [f"GROUP, {name}, TYPE=hex20, MATERIAL=rigid",
                      "A, 20, " + ", ".join(map(str, conn[:10])) + ",", ", ".join(map(str, conn[10:])) + ",",
                      f"%, {n}, *, 20, 2,", f"%, {n}, *, 20, {2 * lx},", "E,"]
        conn = ([idx(i, j, 2) for i, j in corners] + [idx(i, j, 2) for i, j in mids]
                + [idx(i, j, 0, nblock) for i, j in corners] + [idx(i, j, 0, nblock) for i, j in mids])
        lines += ["GROUP, joint, TYPE=interface-quad8, MATERIAL=contact",
                  "A, 16, " + ", ".join(map(str, conn[:8])) + ",", ", ".join(map(str, conn[8:])) + ",",
                  f"%, {n}, *, 16, 2,", f"%, {n}, *, 16, {2 * lx},", "E,", "E,"]
    lines += ["MATERIAL, rigid, ELASTIC, E=1.0e11, NU=0.",
              "MATERIAL, contact, INTERFACE, KN=2000., KS=1000., PHI=26.57, PSI=26.57, C=0.",
              "NSET, base, Z=0.", "NSET, top, Z=20.", "NSET, left_top, X=0., Z=20.",
              "NSET, everything, Z=0.:20.", "FIX, base, ALL", "FIX, everything, Y",
              f"STAGE, compress, STEPS=1, METHOD={method}, DELTA1={tol:g}",
              "DISPLACE, top, Z=-0.1",
              f"STAGE, shear, STEPS={steps}, METHOD={method}, DELTA1={tol:g}",
              "DISPLACE, left_top, X=0.2"]
    return "\n".join(lines) + "\n"


def rewrite_stages(text, steps, tol):
    """A deck with STEPS= of every multi-step STAGE record set to `steps` and DELTA1= of every
    STAGE record set to `tol`; OUTPUT= dropped (only each stage's last step is written)."""
    out = []
    for line in text.splitlines():
        body, bang, comment = line.partition("!")
        if re.match(r"\s*STAGE\s*,", body, re.IGNORECASE):
            fields = [f.strip() for f in body.split(",")]
            fields = [f for f in fields if f and not re.match(r"OUTPUT\s*=", f, re.IGNORECASE)]
            new = []
            for f in fields:
                m = re.match(r"STEPS\s*=\s*(\d+)", f, re.IGNORECASE)
                if m and int(m.group(1)) > 1 and steps is not None:
                    f = f"STEPS={steps}"
                if re.match(r"DELTA1\s*=", f, re.IGNORECASE):
                    continue
                new.append(f)
            if tol is not None:
                new.append(f"DELTA1={tol:g}")
            line = ", ".join(new)
        elif re.match(r"\s*OUTPUT\s*,", body, re.IGNORECASE):
            continue
        elif re.match(r"\s*INCLUDE\s*,", body, re.IGNORECASE):
            name = body.split(",", 1)[1].strip()
            line = f"INCLUDE, {name}"          # made absolute by the caller
        out.append(line)
    return "\n".join(out) + "\n"


def model_c_deck(case):
    """The model C case with the mesh this study was made with: 6 deg elements beyond theta = 12
    (21 864 DOFs; input/modelC now uses 3 deg, docs/verification.md, model C mesh sensitivity)."""
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import make_model_c
    G, nu, beta, soil_E, psi = make_model_c.parse_case(case)
    src = make_model_c.deck(G, nu, beta, theta_step=6.0, soil_E=soil_E, psi=psi)

    def make(element, n, steps, tol, method):
        return rewrite_stages(src, steps, tol)
    return make


def file_deck(path):
    src = open(path).read()

    def make(element, n, steps, tol, method):
        text = rewrite_stages(src, steps, tol)
        folder = os.path.dirname(os.path.abspath(path))
        return re.sub(r"(?im)^INCLUDE, (.+)$",
                      lambda m: "INCLUDE, " + os.path.join(folder, m.group(1).strip()), text)
    return make


# ----------------------------------------------------------------------------------------------
# quantities
# ----------------------------------------------------------------------------------------------
def last_step(f):
    return f["steps"][sorted(f["steps"].keys(), key=int)[-1]]   # by number: names have 4 or more digits


def q_block(f):
    return float(np.mean(last_step(f)["stress/block"][:, 2]))


def q_interface(f):
    return float(np.mean(last_step(f)["interface/joint"][:, 0]))


def q_sigma_max(f):
    # sigma_max as the interface's normal stress (the reading these studies were made with; Table
    # 7.4 reads the packing's szz, a few per cent lower: docs/verification.md, model C)
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import postprocess_model_c as pmc
    step = last_step(f)
    return float(pmc.edge_stress(f["mesh/coordinates"][...], f["mesh/groups/joint/connectivity"][...],
                                 step["interface/joint"][...])[0])


def q_max_s1(f):
    return float(np.max(last_step(f)["principal/pipe"][:, 0]))


def ch9_deck():
    """input/chapter9/CR.dat; n = 1 selects TENSION=closest-point (n = 0: the thesis's rule)."""
    src = open(os.path.join(ROOT, "input", "chapter9", "CR.dat")).read()

    def make(element, n, steps, tol, method):
        text = rewrite_stages(src, steps, tol)
        if n == 1:
            text, count = re.subn(r"(MATSUOKA,.*FT=5\.)", r"\1, TENSION=closest-point", text)
            assert count == 1
        return text
    return make


def q_rotation(f):
    attrs = f["summary"].attrs
    names = sorted(k for k in attrs if k.startswith("rotation_") and k.endswith("_deg"))
    if "rotation_deflection_deg" in names:
        return float(attrs["rotation_deflection_deg"])
    return float(attrs[names[0]])


# ----------------------------------------------------------------------------------------------
# running feps
# ----------------------------------------------------------------------------------------------
class Runner:
    def __init__(self, feps, workdir, repeats, repeat_below, nice):
        self.feps, self.workdir = feps, workdir
        self.repeats, self.repeat_below, self.nice = repeats, repeat_below, nice
        self.spent = 0.0
        self.errors = []          # failures other than feps's clear "does not converge" stop

    def once(self, deck, method, solver, quantity):
        h5 = os.path.join(self.workdir, "run.h5")
        mem = os.path.join(self.workdir, "mem.txt")
        for p in (h5, mem):
            if os.path.exists(p):
                os.remove(p)
        cmd = ["nice", "-n", str(self.nice), "/usr/bin/time", "-f", "%M", "-o", mem,
               self.feps, deck, "--output", h5, "--quiet", "--method", method, "--solver", solver]
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True)
        elapsed = time.perf_counter() - t0
        self.spent += elapsed
        res = {"elapsed": elapsed, "status": "ok" if proc.returncode == 0 else f"rc{proc.returncode}"}
        try:
            res["peak_kb"] = int(open(mem).read().split()[-1])
        except (OSError, ValueError, IndexError):
            res["peak_kb"] = ""
        if proc.returncode != 0:
            msg = (proc.stderr.strip().splitlines() or ["?"])[-1]
            res["status"] = "failed: " + msg[:120].replace(",", ";")
            if not (proc.returncode == 1 and "does not converge" in msg):
                self.errors.append(f"exit {proc.returncode}: {msg}")
            return res
        with h5py.File(h5, "r") as f:
            a = f["summary"].attrs
            res.update(feps_wall=float(a["wall_time"]), iterations=int(a["iterations"]),
                       factorizations=int(a["factorizations"]), cutbacks=int(a["cutbacks"]),
                       dofs=int(a["dofs"]), value=quantity(f))
        return res

    def run(self, deck_text, method, solver, quantity):
        deck = os.path.join(self.workdir, "deck.dat")
        with open(deck, "w") as fh:
            fh.write(deck_text)
        runs = [self.once(deck, method, solver, quantity)]
        if runs[0]["status"] == "ok" and runs[0]["elapsed"] < self.repeat_below:
            runs += [self.once(deck, method, solver, quantity) for _ in range(self.repeats - 1)]
        ok = [r for r in runs if r["status"] == "ok"]
        out = dict(runs[0] if not ok else ok[0])
        times = [r["elapsed"] for r in (ok or runs)]
        out["wall_s"] = statistics.median(times)
        out["wall_runs"] = ";".join(f"{t:.3f}" for t in times)
        if ok:
            out["feps_wall"] = statistics.median(r["feps_wall"] for r in ok)
            out["peak_kb"] = max(r["peak_kb"] for r in ok if r["peak_kb"] != "") if any(
                r["peak_kb"] != "" for r in ok) else ""
        return out


# ----------------------------------------------------------------------------------------------
# plans
# ----------------------------------------------------------------------------------------------
def grid(meshes, solvers, methods, steps, tols):
    """All combinations; the one-iteration Euler presets ignore DELTA1 and run once (tol 0)."""
    for element, n in meshes:
        for solver in solvers:
            for method in methods:
                for s in steps:
                    for tol in (tols if method in ITERATIVE else [0.0]):
                        yield element, n, method, s, tol, solver


def plans(quick, check=False):
    if check:
        # a small subset to compare builds (e.g. --feps of `fpm build --profile release`)
        return {
            "block": list(grid([("hex8", 2)], ["cholmod", "skyline"], PRESETS, [10, 100], [1e-6]))
            + list(grid([("hex8", 8)], ["cholmod", "skyline"], ["modified-euler", "modified-newton-raphson"],
                        [10], [1e-6])),
            "interface": list(grid([("hex8", 1), ("hex8", 16)], ["cholmod", "skyline"],
                                   ["modified-euler", "modified-newton-raphson"], [10], [1e-6])),
            "fe1": [("hex8", 0, "initial-stiffness", 50, 1e-4, "cholmod"),
                    ("hex8", 0, "initial-stiffness", 100, 1e-4, "skyline"),
                    ("hex8", 0, "initial-stiffness", 400, 1e-4, "cholmod")],
            "modelc": [], "ch9": []}
    if quick:
        fast = list(grid([("hex8", 2)], ["cholmod"], ["modified-euler", "initial-stiffness"],
                         [10, 100], [1e-6]))
        return {
            "block": fast + list(grid([("hex20", 2)], ["skyline"], ["newton-raphson"], [10], [1e-6])),
            "interface": list(grid([("hex8", 1)], ["cholmod"], ["euler", "modified-newton-raphson"],
                                   [10, 100], [1e-3])),
            "fe1": [], "modelc": [], "ch9": []}
    # coarse meshes: the full grid; finer meshes and hex20: fewer steps (the error of these
    # homogeneous scenes does not depend on the mesh; the finer meshes show the cost)
    block = []
    block += grid([("hex8", 2)], ["cholmod"], PRESETS, ALL_STEPS, [1e-3, 1e-6])
    block += grid([("hex8", 2)], ["skyline"], PRESETS, [10, 100, 1000], [1e-6])
    block += grid([("hex20", 2), ("hex8", 4)], ["cholmod", "skyline"], PRESETS, [10, 100], [1e-6])
    block += grid([("hex20", 4), ("hex8", 8)], ["cholmod", "skyline"],
                  ["modified-euler", "modified-newton-raphson", "initial-stiffness"], [10], [1e-6])
    inter = []
    inter += grid([("hex8", 1)], ["cholmod"], PRESETS, ALL_STEPS, [1e-3, 1e-6])
    inter += grid([("hex8", 1)], ["skyline"], PRESETS, [10, 100, 1000], [1e-6])
    inter += grid([("hex20", 1), ("hex8", 4)], ["cholmod", "skyline"], PRESETS, [10, 100], [1e-6])
    inter += grid([("hex20", 4), ("hex8", 16)], ["cholmod", "skyline"],
                  ["modified-euler", "modified-newton-raphson", "initial-stiffness"], [10], [1e-6])
    # FE1 (15049 DOFs, 15-120 s a run): few runs; the deck's own tolerance 1e-4, one run at 1e-6
    fe1 = list(grid([("hex8", 0)], ["cholmod"], ["initial-stiffness", "modified-newton-raphson"],
                    [50, 100, 200, 400], [1e-4]))
    fe1 += [("hex8", 0, "initial-stiffness", 100, 1e-4, "skyline"),
            ("hex8", 0, "modified-newton-raphson", 400, 1e-6, "cholmod"),
            ("hex8", 0, "initial-stiffness", 25, 1e-4, "cholmod"),
            ("hex8", 0, "full-newton-raphson", 100, 1e-6, "cholmod")]
    # the converged answer in few steps: full Newton in 1-10 steps (issue 28 item 4)
    fe1 += [("hex8", 0, "full-newton-raphson", s, 1e-6, "cholmod") for s in (1, 2, 5, 10)]
    # model C (21864 DOFs, 1-10 min a run on the shared machine): stage 2's steps (stage s3, the
    # equilibrium stage, gets the same number); initial stiffness below 250 steps stops in s3
    modelc = [("hex8", 0, "initial-stiffness", 50, 1e-4, "cholmod"),
              ("hex8", 0, "initial-stiffness", 100, 1e-4, "cholmod"),
              ("hex8", 0, "initial-stiffness", 250, 1e-4, "cholmod"),
              ("hex8", 0, "initial-stiffness", 500, 1e-4, "cholmod"),
              ("hex8", 0, "modified-newton-raphson", 100, 1e-4, "cholmod"),
              ("hex8", 0, "modified-newton-raphson", 250, 1e-4, "cholmod"),
              ("hex8", 0, "newton-raphson", 50, 1e-4, "cholmod"),
              ("hex8", 0, "newton-raphson", 100, 1e-4, "cholmod"),
              ("hex8", 0, "full-newton-raphson", 50, 1e-6, "cholmod"),
              ("hex8", 0, "full-newton-raphson", 100, 1e-6, "cholmod")]
    # chapter 9 CR (4810 DOFs, 1-160 s a run): the thesis's rule with its method at several step
    # counts and full Newton at 10 steps (it cycles across the rule's jump); the continuous rule
    # under full Newton from 2 steps and with the thesis's method at 400
    ch9 = [("hex8", 0, "modified-newton-raphson", s, 1e-6, "cholmod") for s in (50, 100, 200, 400, 1000)]
    ch9 += [("hex8", 0, "full-newton-raphson", 10, 1e-6, "cholmod")]
    ch9 += [("hex8", 1, "full-newton-raphson", s, 1e-6, "cholmod") for s in (2, 5, 10, 50, 400)]
    ch9 += [("hex8", 1, "modified-newton-raphson", 400, 1e-6, "cholmod")]
    return {"block": block, "interface": inter, "fe1": fe1, "modelc": modelc, "ch9": ch9}


def scenes():
    return {
        "block": dict(deck=block_deck, quantity=q_block, reference=block_plateau(),
                      reference_kind="closed form", title="sec2.4.3 Matsuoka-Nakai block, final sigma_z"),
        "interface": dict(deck=interface_deck, quantity=q_interface, reference=interface_tau(),
                          reference_kind="closed form", title="sec2.3.4a interface, tau at u = 0.2"),
        "fe1": dict(deck=file_deck(os.path.join(ROOT, "input", "modelB.dat")), quantity=q_rotation,
                    reference=None, reference_kind="finest run", title="model B FE1, rotation_deflection_deg"),
        "modelc": dict(deck=model_c_deck(MODEL_C), quantity=q_sigma_max, reference=None, reference_kind="finest run",
                       title="model C G_p = 300, nu_p = 0.4, beta = 0.27, sigma_max (MPa)"),
        "ch9": dict(deck=ch9_deck(), quantity=q_max_s1, reference=None, reference_kind="finest run",
                    title="chapter 9 CR, max s1 (MPa), by tension rule"),
    }


def mesh_name(scene, element, n):
    if scene == "block":
        return f"{element} {n}x{n}x{max(1, n // 2)}"
    if scene == "interface":
        return f"{element} {n}x{n}"
    if scene == "ch9":
        return "TENSION=closest-point" if n == 1 else "thesis tension rule"
    return "deck"


# ----------------------------------------------------------------------------------------------
# CSV, references, Pareto, plots, tables
# ----------------------------------------------------------------------------------------------
def key(row):
    return (row["mesh"], row["method"], str(int(float(row["steps"]))), f"{float(row['tol']):g}", row["solver"])


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        return list(csv.DictReader(fh))


def write_csv(path, rows):
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in FIELDS})


def apply_reference(rows, reference, kind):
    """Fill reference and rel_error. Without a closed form: the finest run (most steps, then the
    tightest tolerance, then Newton-type methods first) is the reference."""
    ok = [r for r in rows if r["status"] == "ok"]
    if reference is None and ok:
        finest = max(ok, key=lambda r: (int(float(r["steps"])), -float(r["tol"]),
                                        r["method"] == "modified-newton-raphson"))
        reference = float(finest["value"])
        kind = f"finest run ({SHORT[finest['method']]} {finest['steps']} steps tol {float(finest['tol']):g})"
    for r in rows:
        r["reference"] = reference if reference is not None else ""
        r["reference_kind"] = kind
        if r["status"] == "ok" and reference is not None:
            r["rel_error"] = abs(float(r["value"]) - reference) / abs(reference)
        else:
            r["rel_error"] = ""
    return reference, kind


def pareto(rows):
    """Non-dominated runs (no other run is both faster and more accurate), fastest first. A run
    counts as more accurate only if its error is at least 1 % smaller (differences in the last
    digits of equal answers are not accuracy)."""
    pts = sorted(((float(r["wall_s"]), max(float(r["rel_error"]), ERROR_FLOOR), r) for r in rows
                  if r["status"] == "ok" and r["rel_error"] != ""), key=lambda p: (p[0], p[1]))
    front, best = [], math.inf
    for t, e, r in pts:
        if e < 0.99 * best:
            front.append(r)
            best = e
    return front


def label(r):
    tol = "" if r["method"] not in ITERATIVE else f" tol {float(r['tol']):g}"
    return f"{SHORT[r['method']]} {int(float(r['steps']))} steps{tol}, {r['mesh']}, {r['solver']}"


def plot_scene(path, title, rows, front, reference_kind):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colors = dict(zip(ALL_METHODS, ["tab:red", "tab:orange", "tab:blue", "tab:green", "tab:purple", "tab:brown"]))
    meshes = sorted({r["mesh"] for r in rows})
    markers = dict(zip(meshes, ["o", "s", "^", "D", "v", "P", "X", "*"]))
    fig, ax = plt.subplots(figsize=(8.6, 4.8), dpi=85)
    for r in rows:
        if r["status"] != "ok" or r["rel_error"] == "":
            continue
        e = max(float(r["rel_error"]), ERROR_FLOOR)
        filled = r["solver"] == "cholmod"
        ax.scatter(float(r["wall_s"]), e, s=10 + 4 * math.log(float(r["steps"])) ** 2,
                   marker=markers[r["mesh"]], alpha=0.75,
                   facecolors=colors[r["method"]] if filled else "none", edgecolors=colors[r["method"]])
    if front:
        ax.step([float(r["wall_s"]) for r in front], [max(float(r["rel_error"]), ERROR_FLOOR) for r in front],
                where="post", color="k", lw=1.2, label="Pareto front")
    for level in (1e-2, 1e-3):
        ax.axhline(level, color="grey", ls=":", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per run (s, median of repeats, nice 5, 2 shared cores)")
    ax.set_ylabel(f"relative error against {reference_kind.split(' (')[0]}")
    ax.set_title(title, fontsize=10)
    handles = [plt.Line2D([], [], color=colors[m], marker="o", ls="", label=SHORT[m]) for m in ALL_METHODS
               if any(r["method"] == m for r in rows)]
    handles += [plt.Line2D([], [], color="k", marker=markers[m], ls="", mfc="none", label=m) for m in meshes]
    handles += [plt.Line2D([], [], color="k", lw=1.2, label="Pareto front")]
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0),
              title="filled: cholmod\nhollow: skyline\nsize: steps", title_fontsize=7)
    if any(float(r["rel_error"]) < ERROR_FLOOR for r in rows if r["rel_error"] != ""):
        ax.text(0.01, 0.01, f"points on {ERROR_FLOOR:g}: exact to round-off", transform=ax.transAxes, fontsize=7)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_steps(path, title, rows, reference):
    """The quantity against the number of steps for each preset and tolerance (does it settle?)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    fig, ax = plt.subplots(figsize=(6.0, 4.0), dpi=85)
    styles = iter(["o-", "s--", "^:", "D-.", "v-"])
    for method in ALL_METHODS:
        for tol in sorted({float(r["tol"]) for r in rows if r["method"] == method}):
            sel = sorted((int(float(r["steps"])), float(r["value"])) for r in rows
                         if r["method"] == method and float(r["tol"]) == tol and r["status"] == "ok"
                         and r["solver"] == "cholmod")
            if sel:
                ax.semilogx([s for s, _ in sel], [v for _, v in sel], next(styles, "x-"), ms=5,
                            label=f"{SHORT[method]} tol {tol:g}")
    ax.axhline(reference, color="grey", ls=":", lw=0.8, label="reference (finest run)")
    ticks = sorted({int(float(r["steps"])) for r in rows})
    ax.set_xticks(ticks)
    ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("steps")
    ax.set_ylabel("quantity")
    ax.set_title(title, fontsize=10)
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def richardson(rows):
    """Observed order and extrapolated value from the three finest step counts (ratio 2)."""
    out = []
    for method in ALL_METHODS:
        for tol in sorted({float(r["tol"]) for r in rows if r["method"] == method}):
            sel = dict((int(float(r["steps"])), float(r["value"])) for r in rows
                       if r["method"] == method and float(r["tol"]) == tol and r["status"] == "ok"
                       and r["solver"] == "cholmod")
            ns = sorted(sel)
            for a, b, c in zip(ns, ns[1:], ns[2:]):
                if b == 2 * a and c == 2 * b:
                    d1, d2 = sel[a] - sel[b], sel[b] - sel[c]
                    if d2 != 0 and d1 / d2 > 0:
                        p = math.log2(d1 / d2)
                        # p <= 0: the differences do not shrink, no extrapolation
                        q = sel[c] + d2 / (2 ** p - 1) if p > 0 else math.nan
                        out.append((method, tol, (a, b, c), p, q))
    return out


def fmt_err(e):
    return "exact" if e < ERROR_FLOOR else f"{e:.2e}"


def tables(scene, title, rows, front, reference, kind):
    lines = [f"### {scene}: {title}", "", f"Reference: {reference:.10g} ({kind}).", ""]
    ok = [r for r in rows if r["status"] == "ok"]
    failed = [r for r in rows if r["status"] != "ok"]
    lines += [f"{len(rows)} settings, {len(failed)} failed.", ""]
    lines += ["Pareto front (fastest first):", "",
              "| setting | wall s | iterations | refact. | cut-backs | peak MB | rel. error |",
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in front:
        lines.append(f"| {label(r)} | {float(r['wall_s']):.3f} | {r['iterations']} | {r['factorizations']} | "
                     f"{r['cutbacks']} | {int(r['peak_kb']) / 1024:.0f} | {fmt_err(float(r['rel_error']))} |")
    lines += ["", "Fastest setting reaching each accuracy:", "",
              "| target | setting | wall s | rel. error |", "| --- | --- | ---: | ---: |"]
    for target in (1e-2, 1e-3, 1e-4):
        cand = [r for r in ok if r["rel_error"] != "" and float(r["rel_error"]) <= target]
        if cand:
            r = min(cand, key=lambda r: float(r["wall_s"]))
            lines.append(f"| {target:g} | {label(r)} | {float(r['wall_s']):.3f} | {fmt_err(float(r['rel_error']))} |")
        else:
            lines.append(f"| {target:g} | none of the runs | | |")
    lines += ["", "All runs on the coarsest mesh with cholmod (error / wall s / iterations / refactorizations):", ""]
    coarse = sorted({r["mesh"] for r in rows}, key=lambda m: min(int(r["dofs"] or 10 ** 9) for r in rows
                                                                   if r["mesh"] == m))[0]
    steps = sorted({int(float(r["steps"])) for r in rows})
    lines += ["| preset | tol | " + " | ".join(str(s) for s in steps) + " |",
              "| --- | --- | " + " | ".join("---" for _ in steps) + " |"]
    for method in ALL_METHODS:
        for tol in sorted({float(r["tol"]) for r in rows if r["method"] == method}):
            cells = []
            for s in steps:
                hit = [r for r in rows if r["method"] == method and float(r["tol"]) == tol and r["mesh"] == coarse
                       and r["solver"] == "cholmod" and int(float(r["steps"])) == s]
                if not hit:
                    cells.append("")
                elif hit[0]["status"] != "ok":
                    cells.append("failed")
                else:
                    r = hit[0]
                    cells.append(f"{fmt_err(float(r['rel_error']))} / {float(r['wall_s']):.2f} / "
                                 f"{r['iterations']} / {r['factorizations']}")
            if any(cells):
                lines.append(f"| {SHORT[method]} | {'-' if method not in ITERATIVE else f'{tol:g}'} | "
                             + " | ".join(cells) + " |")
    lines += ["", f"Coarsest mesh: {coarse}.", ""]
    meshes = sorted({(r["mesh"], r["solver"]) for r in rows})
    if len(meshes) > 1:
        lines += ["Meshes and solvers (median wall s at 100 steps; tol 1e-6 where run, else the loosest):", "",
                  "| mesh | dofs | solver | " + " | ".join(SHORT[m] for m in PRESETS) + " | peak MB |",
                  "| --- | ---: | --- | " + " | ".join("---:" for _ in PRESETS) + " | ---: |"]
        for mesh, solver in meshes:
            sel = [r for r in rows if r["mesh"] == mesh and r["solver"] == solver and r["status"] == "ok"
                   and int(float(r["steps"])) == 100]
            sel.sort(key=lambda r: (float(r["tol"]) not in (0.0, 1e-6), -float(r["tol"])))
            if not sel:
                continue
            cells = []
            for m in PRESETS:
                hit = [r for r in sel if r["method"] == m]
                cells.append(f"{float(hit[0]['wall_s']):.3f}" if hit else "")
            lines.append(f"| {mesh} | {sel[0]['dofs']} | {solver} | " + " | ".join(cells) +
                         f" | {max(int(r['peak_kb']) for r in sel) / 1024:.0f} |")
        lines.append("")
    if failed:
        lines += ["Failed runs:", ""] + [f"- {label(r)}: {r['status']}" for r in failed] + [""]
    if kind.startswith("finest"):
        rich = richardson(rows)
        if rich:
            lines += ["Richardson (three finest step counts, ratio 2):", "",
                      "| preset | tol | steps | observed order | extrapolated | vs reference |",
                      "| --- | --- | --- | ---: | ---: | ---: |"]
            for method, tol, ns, p, q in rich:
                if math.isnan(q):
                    lines.append(f"| {SHORT[method]} | {tol:g} | {ns} | {p:.2f} | not in the asymptotic "
                                 f"range (differences grow) | |")
                else:
                    lines.append(f"| {SHORT[method]} | {tol:g} | {ns} | {p:.2f} | {q:.6g} | "
                                 f"{(q - reference) / reference:+.2e} |")
            lines.append("")
    return "\n".join(lines)


def compare_builds(base_dir, other_dir, names):
    """Markdown table: the same settings timed with two builds (OUT/<scene>.csv against
    DIR/check_<scene>.csv)."""
    if not os.path.isdir(other_dir):
        raise Error(f"--compare: no folder {other_dir}", 2)
    found = [n for n in names if os.path.exists(os.path.join(other_dir, f"check_{n}.csv"))]
    if not found:
        raise Error(f"--compare: no check_<scene>.csv in {other_dir} for the scenes {', '.join(names)} "
                    "(study_tradeoff.py --check --out DIR writes them)")
    lines = []
    for name in found:
        base = {key(r): r for r in read_csv(os.path.join(base_dir, f"{name}.csv")) if r["status"] == "ok"}
        for r in read_csv(os.path.join(other_dir, f"check_{name}.csv")):
            b = base.get(key(r))
            if b is None or r["status"] != "ok":
                continue
            tb, to = float(b["wall_s"]), float(r["wall_s"])
            lines.append(f"| {name} | {label(r)} | {r['dofs']} | {tb:.3f} | {to:.3f} | {tb / to:.1f} |")
    if not lines:
        raise Error(f"--compare: no finished setting of {other_dir}/check_*.csv is among the finished runs "
                    f"of {base_dir}/<scene>.csv")
    print("| scene | setting | dofs | base s | other s | base / other |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    print("\n".join(lines))
    return 0


# ----------------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--feps", help="feps executable (default: fpm's release build, built if needed)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "tradeoff"))
    ap.add_argument("--scenes", nargs="+", choices=SCENES, default=SCENES, metavar="SCENE",
                    help=f"scenes to run, of {', '.join(SCENES)} (default: all)")
    ap.add_argument("--quick", action="store_true", help="a tiny subset (writes OUT/quick_*)")
    ap.add_argument("--check", action="store_true",
                    help="a small subset for comparing builds (writes OUT/check_*)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--repeat-below", type=float, default=5.0,
                    help="repeat runs faster than this many seconds (default 5)")
    ap.add_argument("--nice", type=int, default=5)
    ap.add_argument("--resume", action="store_true", help="keep rows already in the CSVs")
    ap.add_argument("--plots-only", action="store_true")
    ap.add_argument("--compare", metavar="DIR",
                    help="print wall times of OUT's runs beside the same settings in DIR/check_*.csv "
                         "(another build) and exit")
    args = ap.parse_args()
    if args.compare:
        return compare_builds(args.out, args.compare, args.scenes)
    if args.plots_only:
        feps = None
        if not os.path.isdir(args.out):
            raise Error(f"--plots-only: no folder {args.out}", 2)
    else:
        feps = feps_option(args.feps)

    os.makedirs(args.out, exist_ok=True)
    prefix = "quick_" if args.quick else ("check_" if args.check else "")
    allplans, allscenes = plans(args.quick, args.check), scenes()
    report = [f"<!-- written by scripts/study_tradeoff.py {('--' + prefix[:-1] + ' ') if prefix else ''}"
              f"on {time.strftime('%Y-%m-%d %H:%M')} -->", ""]
    found = 0
    with tempfile.TemporaryDirectory(prefix="tradeoff_") as work:
        runner = Runner(feps, work, args.repeats, args.repeat_below, args.nice)
        for name in args.scenes:
            sc = allscenes[name]
            csv_path = os.path.join(args.out, f"{prefix}{name}.csv")
            rows = read_csv(csv_path) if (args.resume or args.plots_only) else []
            if not args.plots_only:
                done = {key(r) for r in rows}
                todo = allplans[name]
                for i, (element, n, method, steps, tol, solver) in enumerate(todo):
                    row = dict(scene=name, mesh=mesh_name(name, element, n), element=element, method=method,
                               steps=steps, tol=tol, solver=solver)
                    if key(row) in done:
                        continue
                    res = runner.run(sc["deck"](element, n, steps, tol if tol > 0 else 1e-6, method),
                                     method, solver, sc["quantity"])
                    row.update(status=res["status"], wall_s=f"{res['wall_s']:.4f}", wall_runs=res["wall_runs"],
                               feps_wall_s=f"{res.get('feps_wall', float('nan')):.4f}",
                               iterations=res.get("iterations", ""), factorizations=res.get("factorizations", ""),
                               cutbacks=res.get("cutbacks", ""), peak_kb=res.get("peak_kb", ""),
                               dofs=res.get("dofs", ""), value=repr(res["value"]) if "value" in res else "")
                    rows.append(row)
                    print(f"[{name} {i + 1}/{len(todo)}] {label(row)}: {row['status']} {row['wall_s']} s "
                          f"value {row['value']} (total {runner.spent:.0f} s)", flush=True)
                    write_csv(csv_path, rows)
            if not rows:
                continue
            found += 1
            reference, kind = apply_reference(rows, sc["reference"], sc["reference_kind"])
            write_csv(csv_path, rows)
            ok_rows = [r for r in rows if r["status"] == "ok"]
            front = pareto(rows)
            plot_scene(os.path.join(args.out, f"{prefix}{name}_pareto.png"), sc["title"], rows, front, kind)
            if name in ("fe1", "modelc") and ok_rows:
                plot_steps(os.path.join(args.out, f"{prefix}{name}_steps.png"), sc["title"], ok_rows, reference)
            report += [tables(name, sc["title"], rows, front, reference, kind), ""]
        print(f"feps compute this invocation: {runner.spent:.0f} s")
    if args.plots_only and not found:
        raise Error(f"--plots-only: no {prefix}<scene>.csv of the scenes {', '.join(args.scenes)} in {args.out}")
    with open(os.path.join(args.out, f"{prefix}tables.md"), "w") as fh:
        fh.write("\n".join(report) + "\n")
    print("tables:", os.path.join(args.out, f"{prefix}tables.md"))
    if runner.errors:
        raise Error(f"{len(runner.errors)} run(s) failed other than by a step that does not converge, "
                    f"the first: {runner.errors[0]}")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
