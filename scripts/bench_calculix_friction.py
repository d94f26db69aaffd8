#!/usr/bin/env python3
"""feps's frictional interface against CalculiX's penalty contact with Coulomb friction.

  python3 scripts/bench_calculix_friction.py                    # both cases, default mesh
  python3 scripts/bench_calculix_friction.py --cases gauss --nx 40
  python3 scripts/bench_calculix_friction.py --feps build/.../feps --outdir /tmp/fric
  python3 scripts/bench_calculix_friction.py --cases nodal --e-lower 1e6   # the sharpest check

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

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

L, W, H1, H2 = 100.0, 10.0, 20.0, 10.0
E, NU = 10000.0, 0.2
KN, KS, PHI = 1.0e5, 5.0e4, 30.0
P = 1.0
MU = math.tan(math.radians(PHI))
N_TOTAL = P * L * W          # the interface's normal force, by equilibrium of the upper block
F_SLIDE = MU * N_TOTAL       # closed form: the pull force once the whole joint slides


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


def ccx_input(h5path, steps, pull, case, sigma_inf, tol, e_lower):
    h = h5py.File(h5path, "r")
    x = h["mesh/coordinates"][...]
    lo = h["mesh/groups/lower/connectivity"][...]
    up = h["mesh/groups/upper/connectivity"][...]
    z = x[:, 2]
    out = ["*HEADING", f"friction benchmark against feps ({case}), written by scripts/bench_calculix_friction.py",
           "*NODE"]
    out += [f"{n}, {float(x[n - 1, 0])!r}, {float(x[n - 1, 1])!r}, {float(x[n - 1, 2])!r}" for n in range(1, len(x) + 1)]
    # feps's hex8 node order is Abaqus's: C3D8 face S1 is nodes 1-2-3-4 (here z = min), S2 5-8.
    out.append("*ELEMENT, TYPE=C3D8, ELSET=LOWER")
    out += [f"{i}, " + ", ".join(map(str, c)) for i, c in enumerate(lo, 1)]
    out.append("*ELEMENT, TYPE=C3D8, ELSET=UPPER")
    out += [f"{i}, " + ", ".join(map(str, c)) for i, c in enumerate(up, len(lo) + 1)]
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
    out += ["*MATERIAL, NAME=BASE", "*ELASTIC", f"{e_lower!r}, {NU!r}",
            "*MATERIAL, NAME=BLOCK", "*ELASTIC", f"{E!r}, {NU!r}",
            "*SOLID SECTION, ELSET=LOWER, MATERIAL=BASE", "*SOLID SECTION, ELSET=UPPER, MATERIAL=BLOCK",
            "*SURFACE INTERACTION, NAME=JOINT", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR"]
    if case == "gauss":
        out += [f"{KN!r}", "*FRICTION", f"{MU!r}, {KS!r}",
                "*CONTACT PAIR, INTERACTION=JOINT, TYPE=SURFACE TO SURFACE", "SSLAVE, SMASTER"]
    else:
        out += [f"{KN!r}, {sigma_inf!r}", "*FRICTION", f"{MU!r}, {KS!r}",
                "*CONTACT PAIR, INTERACTION=JOINT, TYPE=NODE TO SURFACE, SMALL SLIDING", "SSLAVE, SMASTER"]
    out += ["*BOUNDARY", "BASE, 1, 3", "SYM, 2, 2", "PULL, 1, 1, 0."]
    # ccx's default tolerances (0.5% of the average force) are far looser than feps's; both
    # are tightened so that the comparison sees the models, not the iteration ends.
    controls = ["*CONTROLS, PARAMETERS=FIELD", f"{tol!r}, {tol!r}, , , {tol!r}"]
    prints = ["*NODE PRINT, NSET=NALL", "U", "*NODE PRINT, NSET=PULL, TOTALS=ONLY", "RF"]
    if case == "gauss":
        # the pair's total force (CF) exists for face-to-face contact only (ccx 2.20 crashes on
        # it with node-to-surface contact); there the .frd's spring stresses times areas give it
        prints += ["*CONTACT PRINT, SLAVE=SSLAVE, MASTER=SMASTER", "CF"]
    prints += ["*CONTACT FILE", "CDIS, CSTR"]
    out += ["*STEP, INC=1000"] + controls + ["*STATIC", "1., 1.", "*DLOAD", f"STOP, P2, {P!r}"] + prints + ["*END STEP"]
    out += (["*STEP, INC=1000"] + controls + ["*STATIC, DIRECT", f"{1.0 / steps!r}, 1.", "*BOUNDARY", f"PULL, 1, 1, {pull!r}"]
            + prints + ["*END STEP"])
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
                        it=s["interface/joint"][...], iterations=int(s.attrs["iterations"])))
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


def ccx_frd_contact(path):
    """Per time: slave-node contact results {node: (copen, cslip1, cslip2, cpress, cshear1, cshear2)}."""
    out = {}
    t = None
    block = None
    with open(path) as f:
        for line in f:
            if line.startswith("  100CL"):
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


# ------------------------------------------------------------------------------ comparison

def point_weights(xe):
    """Weights of an interface element's 4 points, 2x2 Gauss or nodal alike: a quarter of its
    (rectangular) lower face each."""
    area = np.linalg.norm(np.cross(xe[1] - xe[0], xe[3] - xe[0]))
    return np.full(4, area / 4.0)


def to_nodes(itype, values):
    """Corner values of each element from its 4 point values (bilinear extrapolation for Gauss)."""
    if itype == "interface-quad4-nodal":
        return values
    s = math.sqrt(3.0)
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    gp = [(-1, -1), (1, -1), (-1, 1), (1, 1)]
    m = np.array([[0.25 * (1 + ca * s * ga) * (1 + cb * s * gb) for ga, gb in gp] for ca, cb in corners])
    return np.einsum("cg,egk->eck", m, values)


def compare(itype, pull, feps_h5, ccx_dir):
    """Rows of the comparison table per written step, and what the distributions need."""
    fr = feps_results(feps_h5)
    cd = ccx_dat(os.path.join(ccx_dir, "ccx.dat"))
    cc = ccx_frd_contact(os.path.join(ccx_dir, "ccx.frd"))
    h = h5py.File(feps_h5, "r")
    x = h["mesh/coordinates"][...]
    joint = h["mesh/groups/joint/connectivity"][...]
    lower, upper = joint[:, :4], joint[:, 4:]
    if np.abs(x[lower - 1] - x[upper - 1]).max() > 1e-9:
        sys.exit("compare: the interface's two layers do not coincide (deck numbering)")
    wts = np.concatenate([point_weights(x[c - 1]) for c in lower])
    # tributary area of each slave (upper) node: a quarter of each face it belongs to
    trib = {}
    for c in upper:
        a = np.linalg.norm(np.cross(x[c[1] - 1] - x[c[0] - 1], x[c[3] - 1] - x[c[0] - 1])) / 4.0
        for n in c:
            trib[n] = trib.get(n, 0.0) + a
    pair = {}                     # upper node -> lower node at the same place
    for cl, cu in zip(lower, upper):
        for a, b in zip(cl, cu):
            pair[b] = a
    ups = np.array(sorted(pair))
    lows = np.array([pair[n] for n in ups])
    area = L * W
    times = sorted(cd)
    rows, dist = [], []
    umax_all = max(np.abs(s["u"]).max() for s in fr)

    def kinematic_slip(u):
        jump = u[ups - 1] - u[lows - 1]
        return KS * np.abs(jump[:, 0]) > MU * KN * np.abs(jump[:, 2]) * (1 + 1e-3)

    for k, s in enumerate(fr):
        t = s["t"]
        tc = min(times, key=lambda v: abs(v - t))
        c = cd[tc]
        if abs(tc - t) > 1e-6:
            sys.exit(f"compare: no ccx output at time {t}")
        it = s["it"]
        tx, sn = (it[:, 0] * wts).sum(), (it[:, 2] * wts).sum()
        slip_feps = wts[it[:, 3] == 1].sum() / area
        # the .frd gives the time to 10 digits, the .dat to 7
        tf = min(cc, key=lambda v: abs(v - t)) if cc else None
        con = cc[tf] if tf is not None and abs(tf - t) < 1e-6 else {}
        slip_ccx = sum(trib[n] for n, v in con.items() if n in trib and v[3] > 0 and
                       math.hypot(v[4], v[5]) >= MU * v[3] * (1 - 1e-3)) / area
        kin_f = (np.array([trib[n] for n in ups]) * kinematic_slip(s["u"])).sum() / area
        kin_c = (np.array([trib[n] for n in ups]) * kinematic_slip(c["u"])).sum() / area
        du = np.abs(s["u"] - c["u"][:len(s["u"])]).max()
        if "cf" in c:
            tx_ccx, n_ccx = -c["cf"][0], -c["cf"][2]
        else:   # node-to-surface: spring stress times spring area (5 digits of the .frd)
            tx_ccx = sum(v[4] * trib[n] for n, v in con.items() if n in trib)
            n_ccx = -sum(v[3] * trib[n] for n, v in con.items() if n in trib)
        rows.append(dict(step=k, t=t, ux=(t - 1.0) * pull if t > 1 else 0.0, iters=s["iterations"],
                         f_feps=s["fx"], f_ccx=c["fx"], tx_feps=tx, tx_ccx=tx_ccx, n_feps=sn,
                         n_ccx=n_ccx, slip_feps=slip_feps, slip_ccx=slip_ccx, kin_feps=kin_f,
                         kin_ccx=kin_c, du=du / umax_all))
        dist.append((s, c, con))
    # distributions along y = 0 (interface nodes), at a few partial-slip steps
    line = [n for n in ups if abs(x[n - 1, 1]) < 1e-9]
    line.sort(key=lambda n: x[n - 1, 0])
    return rows, dist, line, pair, x, joint, itype


def fmt_table(case, rows):
    out = [f"### Case {case}", "",
           "| step | ux pull mm | F feps N | F ccx N | F rel diff | F / (mu N) | interface shear feps / ccx N |"
           " normal feps / ccx N | slipped feps (points) | slipped ccx (nodes, .frd) | slipped by u, feps / ccx |"
           " max du / max u | feps iterations |",
           "|---:|---:|---:|---:|---:|---:|---|---|---:|---:|---|---:|---:|"]
    for r in rows:
        rel = (r["f_ccx"] - r["f_feps"]) / max(abs(r["f_feps"]), 1e-30)
        out.append(f"| {r['step']} | {r['ux']:.4f} | {r['f_feps']:.3f} | {r['f_ccx']:.3f} | {rel:+.2e} | "
                   f"{r['f_feps'] / F_SLIDE:.4f} | {r['tx_feps']:.3f} / {r['tx_ccx']:.3f} | "
                   f"{r['n_feps']:.2f} / {r['n_ccx']:.2f} | {r['slip_feps']:.3f} | {r['slip_ccx']:.3f} | "
                   f"{r['kin_feps']:.3f} / {r['kin_ccx']:.3f} | {r['du']:.1e} | {r['iters']} |")
    return out


def fmt_distribution(case, rows, dist, line, pair, x, joint, itype, picks):
    out = []
    lower = joint[:, :4]
    upper = joint[:, 4:]
    for k in picks:
        s, c, con = dist[k]
        # feps nodal shear: the points' tau1 taken to the corners and averaged over elements
        it = s["it"].reshape(len(joint), 4, 4)
        corner = to_nodes(itype, it[:, :, :3])
        acc, cnt = {}, {}
        for e in range(len(joint)):
            for a in range(4):
                n = upper[e, a]
                acc[n] = acc.get(n, 0.0) + corner[e, a]
                cnt[n] = cnt.get(n, 0) + 1
        r = rows[k]
        out += ["", f"{case}, step {k} (pull {r['ux']:.4f} mm, F feps {r['f_feps']:.2f} N = "
                f"{r['f_feps'] / F_SLIDE:.3f} mu N): along the joint at y = 0", "",
                "| x mm | slip ux_up - ux_low feps mm | ccx mm | tau_x feps MPa (nodal) | ccx MPa (.frd) |"
                " sigma_n feps | ccx |",
                "|---:|---:|---:|---:|---:|---:|---:|"]
        ds, smax, dtau = 0.0, 0.0, 0.0
        for n in line:
            lo = pair[n]
            sf = s["u"][n - 1, 0] - s["u"][lo - 1, 0]
            sc = c["u"][n - 1, 0] - c["u"][lo - 1, 0]
            tf = acc[n] / cnt[n]
            v = con.get(n, [0.0] * 6)
            # ccx's CSHEAR1: the shear the slave (upper) side exerts on the master along +x, the
            # sign of feps's tau1 (upper minus lower); CPRESS > 0 is a pressure (feps sigma_n < 0)
            out.append(f"| {x[n - 1, 0]:.2f} | {sf:.4e} | {sc:.4e} | {tf[0]:.4f} | {v[4]:.4f} | {tf[2]:.4f} | "
                       f"{-v[3]:.4f} |")
            ds, smax, dtau = max(ds, abs(sf - sc)), max(smax, abs(sf)), max(dtau, abs(tf[0] - v[4]))
        out += ["", f"max |slip feps - slip ccx| / max slip = {ds / smax:.1e}; max |tau_x feps - tau_x ccx| = "
                f"{dtau:.4f} MPa = {dtau / (MU * P):.3f} mu p"]
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="gauss,nodal")
    ap.add_argument("--nx", type=int, default=20, help="elements along the joint (default 20, 5 mm)")
    ap.add_argument("--ny", type=int, default=2)
    ap.add_argument("--steps", type=int, default=30, help="increments of the pull (default 30)")
    ap.add_argument("--pull", type=float, default=0.06, help="pull displacement, mm (default 0.06)")
    ap.add_argument("--method", help="feps stage controls (default: full Newton, MAXIT=50, DELTA1=1e-9, "
                    "LINESEARCH=energy; with --no-line-search CUTBACKS=20 instead)")
    ap.add_argument("--no-line-search", action="store_true",
                    help="full Newton without its line search: it cycles at the slip front and needs up to 10 "
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
    if a.method is None:
        a.method = "METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-9, " + (
            "CUTBACKS=20" if a.no_line_search else "LINESEARCH=energy")

    if not shutil.which("ccx"):
        sudo = [] if os.geteuid() == 0 else ["sudo"]
        print("bench_calculix_friction: installing calculix-ccx", file=sys.stderr)
        subprocess.run(sudo + ["apt-get", "update", "-qq"], check=True)
        subprocess.run(sudo + ["apt-get", "install", "-y", "-qq", "calculix-ccx"], check=True,
                       env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))
    feps = a.feps
    if not feps:
        subprocess.run(["fpm", "build", "--profile", "release"], cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
        feps = os.path.join(ROOT, subprocess.run(["fpm", "run", "--profile", "release", "--runner", "echo"], cwd=ROOT,
                                                 check=True, capture_output=True, text=True).stdout.split()[-1])
    feps = os.path.abspath(feps)
    outdir = os.path.abspath(a.outdir or os.path.join(
        ROOT, "results", "calculix-friction-" + datetime.datetime.now().strftime("%Y%m%d-%H%M%S")))
    os.makedirs(outdir, exist_ok=True)
    ccx_version = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "calculix-ccx"], capture_output=True,
                                 text=True).stdout or "?"
    summary = ["# feps against CalculiX: frictional interface", "",
               f"date {datetime.datetime.now().isoformat(timespec='seconds')}; ccx {ccx_version}; feps {feps}",
               f"command: python3 scripts/bench_calculix_friction.py {' '.join(sys.argv[1:])}", "",
               f"mu N = tan({PHI:g} deg) * {N_TOTAL:g} N = {F_SLIDE:.4f} N (closed form of the sliding force)", ""]
    for case in a.cases.split(","):
        itype = {"gauss": "interface-quad4", "nodal": "interface-quad4-nodal"}[case]
        d = os.path.join(outdir, case)
        os.makedirs(d, exist_ok=True)
        deck = os.path.join(d, "feps.dat")
        open(deck, "w").write(feps_deck(a.nx, a.ny, 4, 2, a.steps, a.pull, itype, a.method, a.e_lower))
        t0 = datetime.datetime.now()
        reused = a.reuse and os.path.exists(os.path.join(d, "feps.h5"))
        if not reused:
            with open(os.path.join(d, "feps.out"), "w") as fo:
                subprocess.run([feps, deck, "--output", os.path.join(d, "feps.h5")], check=True, stdout=fo,
                               stderr=subprocess.STDOUT)
        t_feps = (datetime.datetime.now() - t0).total_seconds()
        open(os.path.join(d, "ccx.inp"), "w").write(
            ccx_input(os.path.join(d, "feps.h5"), a.steps, a.pull, case, a.sigma_inf, a.tol, a.e_lower))
        t0 = datetime.datetime.now()
        with open(os.path.join(d, "ccx.out"), "w") as fo:
            subprocess.run(["ccx", "-i", "ccx"], cwd=d, check=True, stdout=fo, stderr=subprocess.STDOUT,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
        t_ccx = (datetime.datetime.now() - t0).total_seconds()
        log = open(os.path.join(d, "ccx.out")).read()
        if "Job finished" not in log:
            sys.exit(f"bench_calculix_friction: ccx failed, see {d}/ccx.out")
        ccx_iters = len(re.findall(r"^ iteration \d+", log, re.M))
        rows, dist, line, pair, x, joint, itype = compare(itype, a.pull, os.path.join(d, "feps.h5"), d)
        summary += fmt_table(case, rows)
        fe = open(os.path.join(d, "feps.out")).read()
        m = re.search(r"analysis\s+(.*)", fe)
        wall = "reused" if reused else f"wall {t_feps:.1f} s"
        summary += ["", f"feps: {m.group(1) if m else '?'}; {wall}. ccx: {ccx_iters} iterations; "
                    f"wall {t_ccx:.1f} s."]
        # the partial-slip steps at about 1/4, 1/2 and 3/4 of mu N, and the last step
        picks = []
        for frac in (0.25, 0.5, 0.75):
            picks.append(min(range(1, len(rows)), key=lambda k: abs(rows[k]["f_feps"] / F_SLIDE - frac)))
        summary += fmt_distribution(case, rows, dist, line, pair, x, joint, itype, sorted(set(picks)))
        summary.append("")
    text = "\n".join(summary) + "\n"
    open(os.path.join(outdir, "summary.md"), "w").write(text)
    print(text)
    print(f"bench_calculix_friction: results in {outdir}", file=sys.stderr)


if __name__ == "__main__":
    main()
