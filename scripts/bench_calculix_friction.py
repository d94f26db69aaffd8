#!/usr/bin/env python3
"""feps's frictional interface against CalculiX's penalty contact with Coulomb friction.

  python3 scripts/bench_calculix_friction.py                    # both cases, default mesh
  python3 scripts/bench_calculix_friction.py --cases gauss --nx 40
  python3 scripts/bench_calculix_friction.py --feps build/.../feps --outdir /tmp/fric
  python3 scripts/bench_calculix_friction.py --cases nodal --e-lower 1e6   # the sharpest check
  python3 scripts/bench_calculix_friction.py --family plane-strain          # tri6 + interface-line3
  python3 scripts/bench_calculix_friction.py --family plane-strain --cases gauss --e-lower 1e6

With nodal points on both sides and a stiff lower block (so that ccx's contact frame, which
follows the deformed master surface, hardly rotates) the two codes discretize the same model
the same way, and their pull forces agree to about 5e-7 at every increment. The results of
the default runs and what remains different are discussed in the report of this benchmark
(docs/verification.md, "feps's frictional interface against CalculiX").

The model (both codes, the same mesh, node numbers and supports): two elastic blocks, hex8
(C3D8 in ccx), E = 10000 MPa, nu = 0.2, half of a symmetric joint (y = 0 held in y).
  lower block 105 x 10 x 20 (z = 0 .. 20), base z = 0 held in x, y, z (it reaches one
  element beyond the upper block's pulled end, so that the end stays over ccx's master surface);
  upper block 100 x 10 x 10 (z = 20 .. 30), joined to it by a zero-thickness interface
  (feps: interface elements, c = 0, phi = 30 deg, psi = 0, Kn = 1e5, Ks = 5e4 MPa/mm;
  ccx: contact pair, *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR with slope Kn and
  *FRICTION with mu = tan(phi) and stick slope Ks).
Stage/step 1: a pressure p = 1 MPa on the top face z = 30, the upper block's end face x = 100
held in x. Stage/step 2: that end face pulled by ux = --pull (default 0.06 mm) in --steps equal
increments. The interface shear is concentrated at the pulled end: slip starts there and
spreads towards x = 0 until the whole joint slides at F = mu N = tan(30) * 1000 N = 577.35 N.

feps runs full Newton-Raphson with its line search (LINESEARCH=energy), as ccx runs with its own;
without it (--no-line-search) full Newton cycles at the slip front and needs cut-backs.

Cases (--cases, default both):
  gauss  feps interface-quad4 (2x2 Gauss points) against ccx TYPE=SURFACE TO SURFACE (ccx's
         face-to-face penalty contact: the slave face is integrated at many points, 7 per
         triangle of the slave/master overlap polygons; truly bilinear pressure-overclosure)
  nodal  feps interface-quad4-nodal (points at the nodes, weight a quarter of each face)
         against ccx node-to-surface contact (SMALL SLIDING; a spring per slave node with a
         quarter of each adjacent face as its area; quasi-bilinear normal law with a tension
         sigma_inf = --sigma-inf for large clearances)

Printed per case: the pull force in both codes against mu N; the interface's total normal and
shear force (feps: its point tractions times their weights; ccx: *CONTACT PRINT CF for
face-to-face, the .frd's spring stresses times their areas for node-to-surface); the
node-by-node displacement difference of all nodes; the slipped fraction of the joint (feps: the
area of its sliding points; ccx: the slave nodes whose |shear| reached mu p in its .frd
extrapolation, weighted by their tributary area; and, for both alike, the node pairs whose
relative displacement passes the stick limit Ks |gamma| > mu Kn |eps_n|); and the slip and
shear stress along the joint (y = 0) at a few load levels. Writes feps.dat, ccx.inp, the runs'
output and summary.md into --outdir (default results/calculix-friction-<date>, git-ignored).
Installs calculix-ccx from Debian when ccx is missing (as scripts/bench_calculix.sh does).

--family plane-strain: the same model in the x-y plane (y up; no symmetry plane, forces per mm of
thickness), tri6 blocks with each quad cell of 5 x 5 mm split along a diagonal (as the chapter 3
joint model, scripts/make_joint_2d.py), interface-line3 / interface-line3-nodal, against ccx's
CPE6. ccx expands each CPE6 into a 15-node wedge of the *SOLID SECTION thickness (1 mm here) and
ties the in-plane displacements through the thickness, so that its forces are those of the 1 mm
slice, i.e. feps's per mm. Contact is defined on the triangles' edges, which become 8-node faces
of the wedges. mu N = tan(30) * 100 N/mm = 57.735 N/mm.
  gauss  interface-line3 (3-point Gauss) against face-to-face contact: both integrate the
         stuck state exactly; an apples-to-apples check apart from the slip-front element.
  nodal  interface-line3-nodal (Simpson: L/6, L/6, 2L/3) against node-to-surface contact, whose
         spring areas on those faces are NOT Simpson's: 1/100 of the face at each of its 4 corner
         nodes and 24/100 at each of its 4 middle nodes (ccx manual), i.e. 26/100 of the line at
         each end and 48/100 at the middle. The joint's nodal stiffness is distributed
         differently, and ccx's contact pressure alternates between the end and middle nodes
         (the consistent load of a quadratic edge is Simpson's); a comparison of totals and
         sliding, not of the nodal tractions. The interface totals of ccx use its spring areas.
The .frd is written with OUTPUT=3D: ccx gives node-to-surface results at the expanded nodes,
which are mapped back to the 2D nodes by their x, y.
"""
import argparse
import datetime
import math
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from feps_cli import feps_option  # noqa: E402
from feps_results import point_weights  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

L, W, H1, H2 = 100.0, 10.0, 20.0, 10.0
E, NU = 10000.0, 0.2
KN, KS, PHI = 1.0e5, 5.0e4, 30.0
P = 1.0
MU = math.tan(math.radians(PHI))
N_TOTAL = P * L * W          # the interface's normal force, by equilibrium of the upper block
F_SLIDE = MU * N_TOTAL       # closed form: the pull force once the whole joint slides

# What differs between the element families. plane-strain: forces per mm of thickness (feps's
# plane strain; ccx's expanded CPE6 with the *SOLID SECTION thickness 1 mm gives the same numbers).
FAMILIES = {
    "solid": dict(vert=2, npair=4, i_sn=2, i_state=3, area=L * W, n_total=N_TOTAL, f_slide=F_SLIDE,
                  itypes={"gauss": "interface-quad4", "nodal": "interface-quad4-nodal"}),
    "plane-strain": dict(vert=1, npair=3, i_sn=1, i_state=2, area=L, n_total=P * L, f_slide=MU * P * L,
                         itypes={"gauss": "interface-line3", "nodal": "interface-line3-nodal"}),
}


# ------------------------------------------------------------------------------ feps deck

def feps_deck(nx, ny, nz1, nz2, steps, pull, itype, method, e_lower):
    dx, dy = L / nx, W / ny
    # The lower block reaches one element beyond the pulled end (x = L .. L + dx): a slave node
    # of ccx's contact that slides past the end of the master surface loses its contact, which
    # feps's node pairs never do; with the extension the upper block's end stays over it.
    rowl, layl = nx + 2, (nx + 2) * (ny + 1)
    rowu, layu = nx + 1, (nx + 1) * (ny + 1)
    n1 = layl * (nz1 + 1)         # nodes of the lower block; the upper block's follow
    top = layl * nz1              # last layer of the lower block: the interface's lower layer

    def nodes(z0, n, nz, h):
        return (f"A, 2, 0., 0., {z0:.1f},\n%, {n}, {dx!r}, 0., 0.,\n%, {ny + 1}, 0., {dy!r}, 0.,\n"
                f"%, {nz + 1}, 0., 0., {h / nz!r},\nE,\n")

    def hexes(b, row, lay, n, nz):
        return (f"A, 8, {b + 1}, {b + 2}, {b + 2 + row}, {b + 1 + row}, {b + 1 + lay}, {b + 2 + lay}, "
                f"{b + 2 + row + lay}, {b + 1 + row + lay},\n%, {n}, *, 8, 1,\n%, {ny}, *, 8, {row},\n"
                f"%, {nz}, *, 8, {lay},\nE,\n")

    # one element block per row along x: the two layers' rows differ in length
    joint = "".join(f"A, 8, {top + j * rowl + 1}, {top + j * rowl + 2}, {top + (j + 1) * rowl + 2}, "
                    f"{top + (j + 1) * rowl + 1}, {n1 + j * rowu + 1}, {n1 + j * rowu + 2}, "
                    f"{n1 + (j + 1) * rowu + 2}, {n1 + (j + 1) * rowu + 1},\n%, {nx}, *, 8, 1,\nE,\n"
                    for j in range(ny))
    return "".join([
        "! Written by scripts/bench_calculix_friction.py: a block pulled over another through a\n",
        "! frictional interface (c = 0, psi = 0), the same model as the script's ccx.inp.\n",
        f"TITLE, friction benchmark against CalculiX ({itype})\n",
        nodes(0.0, nx + 2, nz1, H1), nodes(H1, nx + 1, nz2, H2),
        "GROUP, lower, TYPE=hex8, MATERIAL=base\n", hexes(0, rowl, layl, nx + 1, nz1),
        "GROUP, upper, TYPE=hex8, MATERIAL=block\n", hexes(n1, rowu, layu, nx, nz2),
        f"GROUP, joint, TYPE={itype}, MATERIAL=contact\n", joint, "E,\n",
        f"MATERIAL, base, ELASTIC, E={e_lower!r}, NU={NU!r}\n",
        f"MATERIAL, block, ELASTIC, E={E!r}, NU={NU!r}\n",
        f"MATERIAL, contact, INTERFACE, KN={KN!r}, KS={KS!r}, PHI={PHI!r}, PSI=0., C=0.\n",
        "NSET, base, Z=0.\nNSET, sym, Y=0.\nFIX, base, ALL\nFIX, sym, Y\n",
        f"NSET, pull, GROUP=upper, X={L!r}\n",
        f"FSET, top, GROUP=upper, Z={H1 + H2!r}\n",
        "FIELDS, all, nodal_interface\n",
        f"STAGE, press, STEPS=1, {method}, OUTPUT=1\n",
        f"PRESSURE, top, VALUE={P!r}\n",
        f"STAGE, pull, STEPS={steps}, {method}, OUTPUT=1\n",
        f"DISPLACE, pull, X={pull!r}\n",
    ])


def feps_deck_2d(nx, ny1, ny2, steps, pull, itype, method, e_lower):
    """The same model in plane strain (x along the joint, y up): tri6 blocks, each quad cell split
    along its lower-left/upper-right diagonal as in scripts/make_joint_2d.py, line3 interfaces."""
    dx = L / nx

    def lattice(y0, nxe, nye, dy):
        return (f"A, 1, 0., {y0!r},\n%, {2 * nxe + 1}, {dx / 2!r}, 0.,\n%, {2 * nye + 1}, 0., {dy / 2!r},\n"
                "E,\n")

    def tris(o, nxe, nye):
        r = 2 * nxe + 1
        a = [o + 1, o + 3, o + 2 * r + 3, o + 2, o + r + 3, o + r + 2]
        b = [o + 1, o + 2 * r + 3, o + 2 * r + 1, o + r + 2, o + 2 * r + 2, o + r + 1]
        return "".join("A, 6, " + ", ".join(map(str, t)) + f",\n%, {nxe}, *, 6, 2,\n%, {nye}, *, 6, {2 * r},\nE,\n"
                       for t in (a, b))

    rowl = 2 * (nx + 1) + 1       # nodes in a row of the lower block (one element longer, as in 3D)
    n1 = rowl * (2 * ny1 + 1)     # nodes of the lower block; the upper block's follow
    lo0 = 2 * ny1 * rowl + 1      # first node of the lower block's top row
    joint = ("A, 6, " + ", ".join(map(str, [lo0, lo0 + 2, lo0 + 1, n1 + 1, n1 + 3, n1 + 2]))
             + f",\n%, {nx}, *, 6, 2,\nE,\n")
    return "".join([
        "! Written by scripts/bench_calculix_friction.py --family plane-strain: a block pulled over\n",
        "! another through a frictional interface (c = 0, psi = 0), the same model as the script's ccx.inp.\n",
        f"TITLE, friction benchmark against CalculiX, plane strain ({itype})\n",
        lattice(0.0, nx + 1, ny1, H1 / ny1), lattice(H1, nx, ny2, H2 / ny2),
        "GROUP, lower, TYPE=tri6, MATERIAL=base\n", tris(0, nx + 1, ny1),
        "GROUP, upper, TYPE=tri6, MATERIAL=block\n", tris(n1, nx, ny2),
        f"GROUP, joint, TYPE={itype}, MATERIAL=contact\n", joint, "E,\n",
        f"MATERIAL, base, ELASTIC, E={e_lower!r}, NU={NU!r}\n",
        f"MATERIAL, block, ELASTIC, E={E!r}, NU={NU!r}\n",
        f"MATERIAL, contact, INTERFACE, KN={KN!r}, KS={KS!r}, PHI={PHI!r}, PSI=0., C=0.\n",
        "NSET, base, Y=0.\nFIX, base, X, Y\n",
        f"NSET, pull, GROUP=upper, X={L!r}\n",
        f"FSET, top, GROUP=upper, Y={H1 + H2!r}\n",
        "FIELDS, all, nodal_interface\n",
        f"STAGE, press, STEPS=1, {method}, OUTPUT=1\n",
        f"PRESSURE, top, VALUE={P!r}\n",
        f"STAGE, pull, STEPS={steps}, {method}, OUTPUT=1\n",
        f"DISPLACE, pull, X={pull!r}\n",
    ])


# ------------------------------------------------------------------------------ ccx input

def nset_lines(name, nodes):
    out = [f"*NSET, NSET={name}"]
    nodes = sorted(int(n) for n in nodes)
    out += [", ".join(map(str, nodes[i:i + 10])) for i in range(0, len(nodes), 10)]
    return out


def ccx_elements(x, lo, up, ccx_type, ndim):
    """*NODE and the two blocks' *ELEMENT lines (feps's node and element numbers)."""
    out = ["*NODE"]
    out += [f"{n}, " + ", ".join(f"{float(v)!r}" for v in x[n - 1, :ndim]) for n in range(1, len(x) + 1)]
    out.append(f"*ELEMENT, TYPE={ccx_type}, ELSET=LOWER")
    out += [f"{i}, " + ", ".join(map(str, c)) for i, c in enumerate(lo, 1)]
    out.append(f"*ELEMENT, TYPE={ccx_type}, ELSET=UPPER")
    out += [f"{i}, " + ", ".join(map(str, c)) for i, c in enumerate(up, len(lo) + 1)]
    return out


def ccx_joint_and_steps(case, sigma_inf, tol, steps, pull, e_lower, thickness, supports, file_prints):
    """Materials, the contact pair with friction, supports and the two steps (pressure, pull),
    the same in both families but for the sections' thickness line, the supports and the
    .frd output."""
    out = ["*MATERIAL, NAME=BASE", "*ELASTIC", f"{e_lower!r}, {NU!r}",
           "*MATERIAL, NAME=BLOCK", "*ELASTIC", f"{E!r}, {NU!r}",
           "*SOLID SECTION, ELSET=LOWER, MATERIAL=BASE", *thickness,
           "*SOLID SECTION, ELSET=UPPER, MATERIAL=BLOCK", *thickness,
           "*SURFACE INTERACTION, NAME=JOINT", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR"]
    if case == "gauss":
        out += [f"{KN!r}", "*FRICTION", f"{MU!r}, {KS!r}",
                "*CONTACT PAIR, INTERACTION=JOINT, TYPE=SURFACE TO SURFACE", "SSLAVE, SMASTER"]
    else:
        out += [f"{KN!r}, {sigma_inf!r}", "*FRICTION", f"{MU!r}, {KS!r}",
                "*CONTACT PAIR, INTERACTION=JOINT, TYPE=NODE TO SURFACE, SMALL SLIDING", "SSLAVE, SMASTER"]
    out += ["*BOUNDARY"] + supports + ["PULL, 1, 1, 0."]
    # ccx's default tolerances (0.5% of the average force) are far looser than feps's; both
    # are tightened so that the comparison sees the models, not the iteration ends.
    controls = ["*CONTROLS, PARAMETERS=FIELD", f"{tol!r}, {tol!r}, , , {tol!r}"]
    prints = ["*NODE PRINT, NSET=NALL", "U", "*NODE PRINT, NSET=PULL, TOTALS=ONLY", "RF"]
    if case == "gauss":
        # the pair's total force (CF) exists for face-to-face contact only (ccx 2.20 crashes on
        # it with node-to-surface contact); there the .frd's spring stresses times areas give it
        prints += ["*CONTACT PRINT, SLAVE=SSLAVE, MASTER=SMASTER", "CF"]
    prints += file_prints
    out += ["*STEP, INC=1000"] + controls + ["*STATIC", "1., 1.", "*DLOAD", f"STOP, P2, {P!r}"] + prints + ["*END STEP"]
    out += (["*STEP, INC=1000"] + controls + ["*STATIC, DIRECT", f"{1.0 / steps!r}, 1.", "*BOUNDARY",
                                              f"PULL, 1, 1, {pull!r}"] + prints + ["*END STEP"])
    return out


def ccx_input(h5path, steps, pull, case, sigma_inf, tol, e_lower):
    h = h5py.File(h5path, "r")
    x = h["mesh/coordinates"][...]
    lo = h["mesh/groups/lower/connectivity"][...]
    up = h["mesh/groups/upper/connectivity"][...]
    z = x[:, 2]
    out = ["*HEADING", f"friction benchmark against feps ({case}), written by scripts/bench_calculix_friction.py"]
    # feps's hex8 node order is Abaqus's: C3D8 face S1 is nodes 1-2-3-4 (here z = min), S2 5-8.
    out += ccx_elements(x, lo, up, "C3D8", 3)
    lon, upn = np.unique(lo), np.unique(up)
    out += nset_lines("NALL", range(1, len(x) + 1))
    out += nset_lines("BASE", [n for n in lon if abs(z[n - 1]) < 1e-9])
    out += nset_lines("SYM", [n for n in range(1, len(x) + 1) if abs(x[n - 1, 1]) < 1e-9])
    out += nset_lines("PULL", [n for n in upn if abs(x[n - 1, 0] - L) < 1e-9])

    def faces(conn, first, nodes_slice, face, zface):
        return [f"{i}, {face}" for i, c in enumerate(conn, first) if np.all(np.abs(z[c[nodes_slice] - 1] - zface) < 1e-9)]

    out += ["*SURFACE, NAME=SMASTER, TYPE=ELEMENT"] + faces(lo, 1, slice(4, 8), "S2", H1)
    out += ["*SURFACE, NAME=SSLAVE, TYPE=ELEMENT"] + faces(up, len(lo) + 1, slice(0, 4), "S1", H1)
    out += ["*SURFACE, NAME=STOP, TYPE=ELEMENT"] + faces(up, len(lo) + 1, slice(4, 8), "S2", H1 + H2)
    out += ccx_joint_and_steps(case, sigma_inf, tol, steps, pull, e_lower, thickness=[],
                               supports=["BASE, 1, 3", "SYM, 2, 2"], file_prints=["*CONTACT FILE", "CDIS, CSTR"])
    return "\n".join(out) + "\n"


def ccx_input_2d(h5path, steps, pull, case, sigma_inf, tol, e_lower):
    """ccx.inp of the plane-strain model: CPE6 (ccx expands them into 15-node wedges of the
    *SOLID SECTION thickness, here 1 mm, so that its forces are per mm as feps's), contact on
    the edges of the triangles (faces of the expanded wedges)."""
    h = h5py.File(h5path, "r")
    x = h["mesh/coordinates"][...]
    lo = h["mesh/groups/lower/connectivity"][...]
    up = h["mesh/groups/upper/connectivity"][...]
    y = x[:, 1]
    out = ["*HEADING", f"friction benchmark against feps, plane strain ({case}), written by "
           "scripts/bench_calculix_friction.py"]
    # feps's tri6 node order is ccx's (corners counter-clockwise, then mid-sides 1-2, 2-3, 3-1)
    out += ccx_elements(x, lo, up, "CPE6", 2)
    lon, upn = np.unique(lo), np.unique(up)
    out += nset_lines("NALL", range(1, len(x) + 1))
    out += nset_lines("BASE", [n for n in lon if abs(y[n - 1]) < 1e-9])
    out += nset_lines("PULL", [n for n in upn if abs(x[n - 1, 0] - L) < 1e-9])
    edges = {"S1": [0, 1, 3], "S2": [1, 2, 4], "S3": [2, 0, 5]}    # ccx's faces of a triangle

    def faces(conn, first, yface):
        return [f"{i}, {f}" for i, c in enumerate(conn, first) for f, e in edges.items()
                if np.all(np.abs(y[c[e] - 1] - yface) < 1e-9)]

    out += ["*SURFACE, NAME=SMASTER, TYPE=ELEMENT"] + faces(lo, 1, H1)
    out += ["*SURFACE, NAME=SSLAVE, TYPE=ELEMENT"] + faces(up, len(lo) + 1, H1)
    out += ["*SURFACE, NAME=STOP, TYPE=ELEMENT"] + faces(up, len(lo) + 1, H1 + H2)
    # OUTPUT=3D: the .frd then holds the expanded nodes' coordinates; node-to-surface contact
    # results are given at the expanded slave nodes, which are mapped back by their x, y
    out += ccx_joint_and_steps(case, sigma_inf, tol, steps, pull, e_lower, thickness=["1."],
                               supports=["BASE, 1, 2"],
                               file_prints=["*NODE FILE, OUTPUT=3D", "U", "*CONTACT FILE", "CDIS, CSTR"])
    return "\n".join(out) + "\n"


# ------------------------------------------------------------------------------ results

def feps_results(h5path):
    """Per written step: load factor, displacement, pull reaction x, interface (tau1 tau2 sn state)."""
    h = h5py.File(h5path, "r")
    x = h["mesh/coordinates"][...]
    up = np.unique(h["mesh/groups/upper/connectivity"][...])
    pull = np.array([n for n in up if abs(x[n - 1, 0] - L) < 1e-9]) - 1
    out = []
    for name in sorted(h["steps"].keys(), key=int):
        s = h["steps"][name]
        out.append(dict(t=float(s.attrs["load_factor"]), u=s["displacement"][...],
                        fx=float(s["reaction"][...][pull, 0].sum()),
                        it=s["interface/joint"][...], nodal=s["nodal_interface/joint"][...],
                        iterations=int(s.attrs["iterations"])))
    return out


def ccx_dat(path):
    """Per time: displacements of NALL, total RF of PULL, contact pair totals (CF)."""
    steps = {}
    lines = open(path).read().splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        m = re.search(r"and time\s+(\S+)", line)
        if not m:
            i += 1
            continue
        t = round(float(m.group(1)), 9)
        rec = steps.setdefault(t, {})
        i += 1
        if line.lstrip().startswith("displacements"):
            rows = []
            while i < len(lines) and (not lines[i].strip() or lines[i].split()[0].isdigit()):
                if lines[i].strip():
                    rows.append(lines[i].split())
                i += 1
            nodes = np.array([int(r[0]) for r in rows])
            u = np.zeros((nodes.max(), 3))
            u[nodes - 1] = np.array([[float(v) for v in r[1:4]] for r in rows])
            rec["u"] = u
        elif line.lstrip().startswith("total force"):
            while not lines[i].strip():
                i += 1
            rec["fx"] = float(lines[i].split()[0])
        elif line.lstrip().startswith("statistics for slave set"):
            nums = []
            while i < len(lines) and len(nums) < 4:
                p = lines[i].split()
                if p and re.match(r"^-?\d", p[0]):
                    nums.append([float(v) for v in p])
                i += 1
            rec["cf"] = nums[0][:3]          # total force on the slave surface (by the master)
            rec["area_n_s"] = nums[3]        # area, normal force (+ tension), shear force size
    return steps


def ccx_frd_contact(path, coords=None):
    """Per time: slave-node contact results {node: (copen, cslip1, cslip2, cpress, cshear1, cshear2)}.
    With coords (the frd's node coordinates are filled in), nodes by number."""
    out = {}
    t = None
    block = None
    with open(path) as f:
        for line in f:
            if line.startswith("    2C"):
                block = "COORDINATES"
            elif line.startswith(" -1") and block == "COORDINATES":
                if coords is not None:
                    coords[int(line[3:13])] = [float(line[13 + 12 * k:25 + 12 * k]) for k in range(3)]
            elif line.startswith("  100CL"):
                t = round(float(line[12:25]), 9)
                block = None
            elif line.startswith(" -4"):
                block = line.split()[1]
                if block == "CONTACT":
                    out[t] = {}
            elif line.startswith(" -1") and block == "CONTACT":
                node = int(line[3:13])
                vals = [float(line[13 + 12 * k:25 + 12 * k]) for k in range(6)]
                if any(vals):
                    out[t][node] = vals
            elif line.startswith(" -3"):
                block = None
    return out


def map_expanded(con, coords, slaves, x):
    """ccx's results at the nodes of its expanded (3D) plane-strain mesh, keyed by the 2D slave
    node at the same x, y (all expanded nodes of one 2D node carry the same values: ccx ties them)."""
    where = {(round(float(x[n - 1, 0]), 6), round(float(x[n - 1, 1]), 6)): n for n in slaves}
    out = {}
    for t, nodes in con.items():
        out[t] = {}
        for k, v in nodes.items():
            c = coords.get(k)
            n = where.get((round(c[0], 6), round(c[1], 6))) if c else None
            if n is not None:
                out[t][n] = v
    return out


# ------------------------------------------------------------------------------ comparison

def simpson_weights(xe):
    """The weights of a line3 face's ends and middle under feps's nodal rule (Simpson: L/6, L/6,
    2L/3, length per mm of thickness): the tributary lengths of its upper nodes, also for a run
    with the Gauss rule, whose file holds the Gauss points' weights instead."""
    return np.linalg.norm(xe[1] - xe[0]) * np.array([1.0, 1.0, 4.0]) / 6.0


def compare(pull, feps_h5, ccx_dir, g=FAMILIES["solid"]):
    """Rows of the comparison table per written step, and what the distributions need."""
    fr = feps_results(feps_h5)
    cd = ccx_dat(os.path.join(ccx_dir, "ccx.dat"))
    coords = {}
    cc = ccx_frd_contact(os.path.join(ccx_dir, "ccx.frd"), coords)
    h = h5py.File(feps_h5, "r")
    x = h["mesh/coordinates"][...]
    joint = h["mesh/groups/joint/connectivity"][...]
    npair, vert, isn, ist = g["npair"], g["vert"], g["i_sn"], g["i_state"]
    lower, upper = joint[:, :npair], joint[:, npair:]
    if np.abs(x[lower - 1] - x[upper - 1]).max() > 1e-9:
        sys.exit("compare: the interface's two layers do not coincide (deck numbering)")
    wts = point_weights(h, "joint")          # each interface point's area, feps's rule
    # tributary area of each slave (upper) node: a quarter of each face it belongs to (3D), the
    # Simpson weights of each line (plane strain): the weights of feps's nodal rule
    # spring: the area of ccx's node-to-surface spring at each slave node. For the 3D quad4 faces
    # the same quarters; for the plane-strain faces (8-node quadrilaterals of the expanded wedges,
    # weights 1/100 at the corners and 24/100 at the middle nodes, ccx manual) 26/100 of the line
    # at each end (two corners and a mid-thickness node) and 48/100 at the middle.
    trib, spring = {}, {}
    for c in upper:
        if npair == 3:
            a = simpson_weights(x[c - 1])
            b = np.array([0.26, 0.26, 0.48]) * np.linalg.norm(x[c[1] - 1] - x[c[0] - 1])
        else:
            a = np.full(4, np.linalg.norm(np.cross(x[c[1] - 1] - x[c[0] - 1], x[c[3] - 1] - x[c[0] - 1])) / 4.0)
            b = a
        for n, an, bn in zip(c, a, b):
            trib[n] = trib.get(n, 0.0) + an
            spring[n] = spring.get(n, 0.0) + bn
    pair = {}                     # upper node -> lower node at the same place
    for cl, cu in zip(lower, upper):
        for a, b in zip(cl, cu):
            pair[b] = a
    ups = np.array(sorted(pair))
    lows = np.array([pair[n] for n in ups])
    if npair == 3:
        cc = map_expanded(cc, coords, ups, x)
    area = g["area"]
    times = sorted(cd)
    rows, dist = [], []
    umax_all = max(np.abs(s["u"]).max() for s in fr)

    def kinematic_slip(u):
        jump = u[ups - 1] - u[lows - 1]
        return KS * np.abs(jump[:, 0]) > MU * KN * np.abs(jump[:, vert]) * (1 + 1e-3)

    for k, s in enumerate(fr):
        t = s["t"]
        tc = min(times, key=lambda v: abs(v - t))
        c = cd[tc]
        if abs(tc - t) > 1e-6:
            sys.exit(f"compare: no ccx output at time {t}")
        it = s["it"]
        tx, sn = (it[:, 0] * wts).sum(), (it[:, isn] * wts).sum()
        slip_feps = wts[it[:, ist] == 1].sum() / area
        # the .frd gives the time to 10 digits, the .dat to 7
        tf = min(cc, key=lambda v: abs(v - t)) if cc else None
        con = cc[tf] if tf is not None and abs(tf - t) < 1e-6 else {}
        slip_ccx = sum(trib[n] for n, v in con.items() if n in trib and v[3] > 0 and
                       math.hypot(v[4], v[5]) >= MU * v[3] * (1 - 1e-3)) / area
        kin_f = (np.array([trib[n] for n in ups]) * kinematic_slip(s["u"])).sum() / area
        kin_c = (np.array([trib[n] for n in ups]) * kinematic_slip(c["u"])).sum() / area
        du = np.abs(s["u"] - c["u"][:len(s["u"])]).max()
        if "cf" in c:
            tx_ccx, n_ccx = -c["cf"][0], -c["cf"][vert]
        else:   # node-to-surface: spring stress times spring area (5 digits of the .frd)
            tx_ccx = sum(v[4] * spring[n] for n, v in con.items() if n in spring)
            n_ccx = -sum(v[3] * spring[n] for n, v in con.items() if n in spring)
        rows.append(dict(step=k, t=t, ux=(t - 1.0) * pull if t > 1 else 0.0, iters=s["iterations"],
                         f_feps=s["fx"], f_ccx=c["fx"], tx_feps=tx, tx_ccx=tx_ccx, n_feps=sn,
                         n_ccx=n_ccx, slip_feps=slip_feps, slip_ccx=slip_ccx, kin_feps=kin_f,
                         kin_ccx=kin_c, du=du / umax_all))
        dist.append((s, c, con))
    # distributions along y = 0 (interface nodes; in plane strain all), at a few partial-slip steps
    line = [n for n in ups if npair == 3 or abs(x[n - 1, 1]) < 1e-9]
    line.sort(key=lambda n: x[n - 1, 0])
    return rows, dist, line, pair, x


def fmt_table(case, rows, g=FAMILIES["solid"]):
    out = [f"### Case {case}", "",
           "| step | ux pull mm | F feps N | F ccx N | F rel diff | F / (mu N) | interface shear feps / ccx N |"
           " normal feps / ccx N | slipped feps (points) | slipped ccx (nodes, .frd) | slipped by u, feps / ccx |"
           " max du / max u | feps iterations |",
           "|---:|---:|---:|---:|---:|---:|---|---|---:|---:|---|---:|---:|"]
    for r in rows:
        rel = (r["f_ccx"] - r["f_feps"]) / max(abs(r["f_feps"]), 1e-30)
        out.append(f"| {r['step']} | {r['ux']:.4f} | {r['f_feps']:.3f} | {r['f_ccx']:.3f} | {rel:+.2e} | "
                   f"{r['f_feps'] / g['f_slide']:.4f} | {r['tx_feps']:.3f} / {r['tx_ccx']:.3f} | "
                   f"{r['n_feps']:.2f} / {r['n_ccx']:.2f} | {r['slip_feps']:.3f} | {r['slip_ccx']:.3f} | "
                   f"{r['kin_feps']:.3f} / {r['kin_ccx']:.3f} | {r['du']:.1e} | {r['iters']} |")
    return out


def fmt_distribution(case, rows, dist, line, pair, x, picks, g=FAMILIES["solid"]):
    out = []
    npair, isn = g["npair"], g["i_sn"]
    for k in picks:
        s, c, con = dist[k]
        r = rows[k]
        out += ["", f"{case}, step {k} (pull {r['ux']:.4f} mm, F feps {r['f_feps']:.2f} N = "
                f"{r['f_feps'] / g['f_slide']:.3f} mu N): along the joint" + (" at y = 0" if npair == 4 else ""), "",
                "| x mm | slip ux_up - ux_low feps mm | ccx mm | tau_x feps MPa (nodal) | ccx MPa (.frd) |"
                " sigma_n feps | ccx |",
                "|---:|---:|---:|---:|---:|---:|---:|"]
        ds, smax, dtau = 0.0, 0.0, 0.0
        for n in line:
            lo = pair[n]
            sf = s["u"][n - 1, 0] - s["u"][lo - 1, 0]
            sc = c["u"][n - 1, 0] - c["u"][lo - 1, 0]
            tf = s["nodal"][lo - 1]      # feps's nodal_interface: at the lower node of the pair
            v = con.get(n, [0.0] * 6)
            # ccx's CSHEAR1: the shear the slave (upper) side exerts on the master along +x, the
            # sign of feps's tau1 (upper minus lower); CPRESS > 0 is a pressure (feps sigma_n < 0)
            out.append(f"| {x[n - 1, 0]:.2f} | {sf:.4e} | {sc:.4e} | {tf[0]:.4f} | {v[4]:.4f} | {tf[isn]:.4f} | "
                       f"{-v[3]:.4f} |")
            ds, smax, dtau = max(ds, abs(sf - sc)), max(smax, abs(sf)), max(dtau, abs(tf[0] - v[4]))
        out += ["", f"max |slip feps - slip ccx| / max slip = {ds / smax:.1e}; max |tau_x feps - tau_x ccx| = "
                f"{dtau:.4f} MPa = {dtau / (MU * P):.3f} mu p"]
        if npair == 3:
            # both codes' recovered nodal stresses differ most near the pulled end; Kn times each
            # code's own normal jump of the node pairs compares the solutions there, not the recovery
            dn = max(KN * abs((s["u"][n - 1, 1] - s["u"][pair[n] - 1, 1]) - (c["u"][n - 1, 1] - c["u"][pair[n] - 1, 1]))
                     for n in line)
            out.append(f"Kn eps_n from the node pairs' displacements: max |feps - ccx| = {dn:.4f} MPa")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--family", choices=sorted(FAMILIES), default="solid",
                    help="solid: hex8 blocks and interface-quad4 (C3D8 in ccx; default); plane-strain: "
                         "tri6 blocks and interface-line3 (CPE6 in ccx), forces per mm of thickness")
    ap.add_argument("--cases", default="gauss,nodal")
    ap.add_argument("--nx", type=int, default=20, help="elements along the joint (default 20, 5 mm)")
    ap.add_argument("--ny", type=int, default=2, help="elements across the joint (solid only)")
    ap.add_argument("--steps", type=int, default=30, help="increments of the pull (default 30)")
    ap.add_argument("--pull", type=float, default=0.06, help="pull displacement, mm (default 0.06)")
    ap.add_argument("--method", help="feps stage controls (default: full Newton, MAXIT=50, DELTA1=1e-9, "
                    "LINESEARCH=energy; with --no-line-search CUTBACKS=20 instead)")
    ap.add_argument("--no-line-search", action="store_true",
                    help="full Newton without its line search: it cycles at the slip front and needs up to 16 "
                         "cut-backs in a step (hence CUTBACKS=20), as ccx does without its own")
    ap.add_argument("--tol", type=float, default=1e-7, help="ccx R_n, C_n, R_p (*CONTROLS, FIELD)")
    ap.add_argument("--sigma-inf", type=float, default=1e-6, help="ccx node-to-surface tension sigma_inf")
    ap.add_argument("--e-lower", type=float, default=E,
                    help="Young's modulus of the lower block (default E = 10000 MPa; a stiffer one "
                         "shrinks the rotation of ccx's contact frame, a check of that difference)")
    ap.add_argument("--feps", help="feps executable (default: build the release profile)")
    ap.add_argument("--outdir")
    ap.add_argument("--reuse", action="store_true", help="keep the feps results already in --outdir")
    a = ap.parse_args()
    g = FAMILIES[a.family]
    plane = a.family == "plane-strain"
    if a.method is None:
        a.method = "METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-9, " + (
            "CUTBACKS=20" if a.no_line_search else "LINESEARCH=energy")

    if not shutil.which("ccx"):
        sudo = [] if os.geteuid() == 0 else ["sudo"]
        print("bench_calculix_friction: installing calculix-ccx", file=sys.stderr)
        subprocess.run(sudo + ["apt-get", "update", "-qq"], check=True)
        subprocess.run(sudo + ["apt-get", "install", "-y", "-qq", "calculix-ccx"], check=True,
                       env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))
    feps = feps_option(a.feps or "", "release")
    outdir = os.path.abspath(a.outdir or os.path.join(
        ROOT, "results",
        "calculix-friction-" + ("2d-" if plane else "") + datetime.datetime.now().strftime("%Y%m%d-%H%M%S")))
    os.makedirs(outdir, exist_ok=True)
    ccx_version = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "calculix-ccx"], capture_output=True,
                                 text=True).stdout or "?"
    summary = ["# feps against CalculiX: frictional interface" + (", plane strain" if plane else ""), "",
               f"date {datetime.datetime.now().isoformat(timespec='seconds')}; ccx {ccx_version}; feps {feps}",
               f"command: python3 scripts/bench_calculix_friction.py {' '.join(sys.argv[1:])}", ""]
    if plane:
        summary += ["tri6 blocks (ccx: CPE6, thickness 1 mm) and interface-line3; forces in N per mm of "
                    "thickness (feps's plane strain; ccx's forces for its 1 mm slice)", "",
                    f"mu N = tan({PHI:g} deg) * {g['n_total']:g} N/mm = {g['f_slide']:.4f} N/mm (closed form of "
                    "the sliding force)", ""]
    else:
        summary += [f"mu N = tan({PHI:g} deg) * {N_TOTAL:g} N = {F_SLIDE:.4f} N (closed form of the sliding force)", ""]
    for case in a.cases.split(","):
        itype = g["itypes"][case]
        d = os.path.join(outdir, case)
        os.makedirs(d, exist_ok=True)
        deck = os.path.join(d, "feps.dat")
        if plane:
            open(deck, "w").write(feps_deck_2d(a.nx, 4, 2, a.steps, a.pull, itype, a.method, a.e_lower))
        else:
            open(deck, "w").write(feps_deck(a.nx, a.ny, 4, 2, a.steps, a.pull, itype, a.method, a.e_lower))
        t0 = datetime.datetime.now()
        reused = a.reuse and os.path.exists(os.path.join(d, "feps.h5"))
        if not reused:
            with open(os.path.join(d, "feps.out"), "w") as fo:
                subprocess.run([feps, deck, "--output", os.path.join(d, "feps.h5")], check=True, stdout=fo,
                               stderr=subprocess.STDOUT)
        t_feps = (datetime.datetime.now() - t0).total_seconds()
        writer = ccx_input_2d if plane else ccx_input
        open(os.path.join(d, "ccx.inp"), "w").write(
            writer(os.path.join(d, "feps.h5"), a.steps, a.pull, case, a.sigma_inf, a.tol, a.e_lower))
        t0 = datetime.datetime.now()
        with open(os.path.join(d, "ccx.out"), "w") as fo:
            subprocess.run(["ccx", "-i", "ccx"], cwd=d, check=True, stdout=fo, stderr=subprocess.STDOUT,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
        t_ccx = (datetime.datetime.now() - t0).total_seconds()
        log = open(os.path.join(d, "ccx.out")).read()
        if "Job finished" not in log:
            sys.exit(f"bench_calculix_friction: ccx failed, see {d}/ccx.out")
        ccx_iters = len(re.findall(r"^ iteration \d+", log, re.M))
        rows, dist, line, pair, x = compare(a.pull, os.path.join(d, "feps.h5"), d, g)
        summary += fmt_table(case, rows, g)
        fe = open(os.path.join(d, "feps.out")).read()
        m = re.search(r"analysis\s+(.*)", fe)
        wall = "reused" if reused else f"wall {t_feps:.1f} s"
        summary += ["", f"feps: {m.group(1) if m else '?'}; {wall}. ccx: {ccx_iters} iterations; "
                    f"wall {t_ccx:.1f} s."]
        # the partial-slip steps at about 1/4, 1/2 and 3/4 of mu N, and the last step
        picks = []
        for frac in (0.25, 0.5, 0.75):
            picks.append(min(range(1, len(rows)), key=lambda k: abs(rows[k]["f_feps"] / g["f_slide"] - frac)))
        summary += fmt_distribution(case, rows, dist, line, pair, x, sorted(set(picks)), g)
        summary.append("")
    text = "\n".join(summary) + "\n"
    open(os.path.join(outdir, "summary.md"), "w").write(text)
    print(text)
    print(f"bench_calculix_friction: results in {outdir}", file=sys.stderr)


if __name__ == "__main__":
    main()
