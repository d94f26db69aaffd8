#!/usr/bin/env python3
"""Independent equilibrium check of a feps result file (docs/output-format.md).

Kept in test/reference/ as a deliberately independent check: it assembles the nodal forces
with shape functions, rules and frames of its own, so that an error in feps's element code cannot
hide itself. Its readings of the deck (which nodes are loaded, the nodal systems) are part of that
independence: they do not come from feps's resolution of the sets.

    python3 test/reference/check_equilibrium.py RESULT.h5 [--step NNNN] [--deck DECK] [--applied FX,FY,FZ]

From the mesh and the written Gauss-point fields of one step it assembles the nodal internal
forces with its own shape functions, derivatives and integration weights (nothing of feps's
element code):

  solids      f_a = sum_g w_g det J  sigma . grad N_a      (hex8, hex20, hex20r, tri6, tri6-6;
              hex8b adds the B-bar term p (mean grad N_a - grad N_a), p = tr(sigma) / 3;
              plane strain per unit thickness)
  interfaces  f_a = +-sum_g w_g |J| N_a (tau1 e1 + tau2 e2 + sigma_n n), + on the upper layer,
              - on the lower; e1 = dx/ds1 / |dx/ds1|, n along dx/ds1 x dx/ds2, e2 = n x e1 from the
              lower layer (thesis eq. 2.3.4); 2D: e1 along dx/ds, n = e_z x e1
  bars        f_a = sum_g w_g F_g dN_a/ds t_g,  t = dx/ds / |dx/ds|

and prints one line per check, PASS or FAIL against the stated tolerance (|P| is the larger of
the 2-norms of the reactions and of the loads, f_int - r at the loaded nodes):

  interface-frame  the written relative displacements (interface_strain) against u_upper - u_lower
                   in the frame above, relative to the largest of them (tolerance 1e-9): it
                   confirms the frame the tractions are resolved in
  free-nodes       |f_int| at the nodes without reaction and without applied load (the nodes of
                   the deck's FORCE, PRESSURE and TRACTION sets), 2-norm over them / |P|
  supports         |f_int - r| at the nodes with a reaction (global components), 2-norm / |P|
  reaction-nodal   reaction_nodal against r in the nodal systems of the deck's FIX/DISPLACE CSYS
                   (tolerance 1e-9)
  held-directions  |f_int - r| in the held directions (nonzero nodal reaction), max / |P|: feps's
                   reaction is f_int - f_ext there, so only rounding is allowed, whatever the residual
  applied          |sum r + applied| / |P|: the applied total from --applied, else from the deck
                   when every load record's resultant is known (one stage; FORCE in Cartesian
                   directions; PRESSURE or TRACTION with TOTAL= on a plane face set); else SKIP.
                   It equals the resultant of the residual vector, which the step's residual bounds
                   by sqrt(free DOFs) |R| (tolerance: that plus rounding)

free-nodes and supports pass below the step's `residual` attribute (feps's |R| / |P| over all
free DOFs, these among them) plus rounding. Rounding is 1e-9 |P|, or more where a stiff part
moves far: 64 eps k max|u_e| h_e^m over the elements (k h^m = E h for solids, Kn h^2 for
interfaces, EA / h for bars), the error of stresses recovered from large displacements (E = 1e11
"rigid" blocks). A wrong weight, component, point order or sign gives errors of order 1e-2..1.
The nodes of RELEASE sets and of post-tensioned (BOND=AFTER) bar groups count as loaded (their
stage puts forces on them). Not covered: a step whose loads and reactions vanish (a block lifted
off), where feps scales its residual by the step's initial out-of-balance force, which the file
does not hold.

Exit status 0 when every check passes, 1 when one fails, 2 for a file or deck that cannot be read.
"""
import argparse
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import feps_results as fr  # noqa: E402  (reading only: open_result, steps, connectivity, ...)

ROUNDING = 1e-9
FRAME_TOL = 1e-9

# ------------------------------------------------------------------------------ own element library
# Natural coordinates of the nodes, written from docs/output-format.md "Where each Gauss-point row is".
HEX8 = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                 [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
HEX20_MID = np.array([[0, -1, -1], [1, 0, -1], [0, 1, -1], [-1, 0, -1],      # 9-12: 1-2, 2-3, 3-4, 4-1
                      [0, -1, 1], [1, 0, 1], [0, 1, 1], [-1, 0, 1],          # 13-16: 5-6, 6-7, 7-8, 8-5
                      [-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], float)  # 17-20: 1-5 .. 4-8
QUAD8 = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], float)


def n_hex8(x):
    return [(1 + x[0] * a[0]) * (1 + x[1] * a[1]) * (1 + x[2] * a[2]) / 8 for a in HEX8]


def n_hex20(x):
    out = [(1 + x[0] * a[0]) * (1 + x[1] * a[1]) * (1 + x[2] * a[2]) * (x[0] * a[0] + x[1] * a[1] + x[2] * a[2] - 2) / 8
           for a in HEX8]
    for a in HEX20_MID:
        f = 1.0
        for d in range(3):
            f = f * ((1 - x[d] * x[d]) if a[d] == 0 else (1 + x[d] * a[d]))
        out.append(f / 4)
    return out


def n_quad4(s):
    return [(1 + s[0] * a[0]) * (1 + s[1] * a[1]) / 4 for a in QUAD8[:4]]


def n_quad8(s):
    out = [(1 + s[0] * a[0]) * (1 + s[1] * a[1]) * (s[0] * a[0] + s[1] * a[1] - 1) / 4 for a in QUAD8[:4]]
    for a in QUAD8[4:]:
        if a[0] == 0:
            out.append((1 - s[0] * s[0]) * (1 + s[1] * a[1]) / 2)
        else:
            out.append((1 - s[1] * s[1]) * (1 + s[0] * a[0]) / 2)
    return out


def n_tri3(s):
    return [1 - s[0] - s[1], s[0], s[1]]


def n_tri6(s):
    l1, l2, l3 = 1 - s[0] - s[1], s[0], s[1]
    return [l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), l3 * (2 * l3 - 1), 4 * l1 * l2, 4 * l2 * l3, 4 * l3 * l1]


def lagrange(nodes_s):
    def shape(s):
        out = []
        for i, si in enumerate(nodes_s):
            f = 1.0
            for j, sj in enumerate(nodes_s):
                if j != i:
                    f = f * (s[0] - sj) / (si - sj)
            out.append(f)
        return out
    return shape


def evaluate(shape, points):
    """Shape functions (npts, nn) and their natural derivatives (npts, nn, dim) by the complex step
    (exact to rounding for these polynomials)."""
    points = np.asarray(points, float)
    npts, dim = points.shape
    n = np.array([np.real(np.array(shape(p.astype(complex)), dtype=complex)) for p in points])
    d = np.empty(n.shape + (dim,))
    h = 1e-30
    for k in range(dim):
        for g, p in enumerate(points):
            q = p.astype(complex)
            q[k] += 1j * h
            d[g, :, k] = np.imag(np.array(shape(q), dtype=complex)) / h
    return n, d


def gauss(n):
    if n == 1:
        return np.array([0.0]), np.array([2.0])
    if n == 2:
        g = 1 / math.sqrt(3)
        return np.array([-g, g]), np.array([1.0, 1.0])
    if n == 3:
        g = math.sqrt(0.6)
        return np.array([-g, 0.0, g]), np.array([5 / 9, 8 / 9, 5 / 9])
    if n == 4:
        a, b = 0.861136311594053, 0.339981043584856
        wa, wb = 0.347854845137454, 0.652145154862546
        return np.array([-a, -b, b, a]), np.array([wa, wb, wb, wa])
    raise ValueError(n)


def tensor(n, dim):
    """Tensor-product Gauss rule, the first coordinate fastest."""
    g, w = gauss(n)
    if dim == 2:
        pts = [(g[i], g[j]) for j in range(n) for i in range(n)]
        wts = [w[i] * w[j] for j in range(n) for i in range(n)]
    else:
        pts = [(g[i], g[j], g[k]) for k in range(n) for j in range(n) for i in range(n)]
        wts = [w[i] * w[j] * w[k] for k in range(n) for j in range(n) for i in range(n)]
    return np.array(pts), np.array(wts)


def tri3pt():
    a = 1 / 6
    return np.array([[a, a], [1 - 2 * a, a], [a, 1 - 2 * a]]), np.full(3, 1 / 6)


def tri6pt():
    a, b = 0.445948490915965, 0.091576213509771
    wa, wb = 0.223381589678011 / 2, 0.109951743655322 / 2
    pts = [[a, a], [1 - 2 * a, a], [a, 1 - 2 * a], [b, b], [1 - 2 * b, b], [b, 1 - 2 * b]]
    return np.array(pts), np.array([wa] * 3 + [wb] * 3)


def rule(etype):
    """(kind, shape function, nodes per layer, points (npts, dim), weights) of an element type."""
    t = etype.lower()
    if t in ("hex8", "hex8b"):
        return ("solid", n_hex8, 8) + tensor(2, 3)
    if t == "hex20":
        return ("solid", n_hex20, 20) + tensor(3, 3)
    if t == "hex20r":
        return ("solid", n_hex20, 20) + tensor(2, 3)
    if t == "tri6":
        return ("solid2d", n_tri6, 6) + tri3pt()
    if t == "tri6-6":
        return ("solid2d", n_tri6, 6) + tri6pt()
    m = re.fullmatch(r"bar([2-5])", t)
    if m:
        nn = int(m.group(1))
        g, w = gauss(nn - 1)
        return ("bar", lagrange(np.linspace(-1, 1, nn)), nn, g[:, None], w)
    m = re.fullmatch(r"interface-(quad4|quad8|tri3|tri6|line2|line3)(-nodal)?", t)
    if m:
        shape, nodal = m.group(1), bool(m.group(2))
        if shape == "quad4":
            pts, w = (QUAD8[:4], np.ones(4)) if nodal else tensor(2, 2)
            return ("interface3d", n_quad4, 4, pts, w)
        if shape == "quad8":
            # nodal: Simpson's 3x3 rule at the 8 nodes and the centre
            if nodal:
                pts = np.vstack([QUAD8, [[0, 0]]])
                w = np.array([1 / 9] * 4 + [4 / 9] * 4 + [16 / 9])
            else:
                pts, w = tensor(3, 2)
            return ("interface3d", n_quad8, 8, pts, w)
        if shape == "tri3":
            pts, w = (np.array([[0, 0], [1, 0], [0, 1]], float), np.full(3, 1 / 6)) if nodal else tri3pt()
            return ("interface3d", n_tri3, 3, pts, w)
        if shape == "tri6":
            pts, w = (np.array([[.5, 0], [.5, .5], [0, .5]]), np.full(3, 1 / 6)) if nodal else tri6pt()
            return ("interface3d", n_tri6, 6, pts, w)
        nodes_s = [-1.0, 1.0] if shape == "line2" else [-1.0, 1.0, 0.0]
        if nodal:
            pts = np.array(nodes_s)[:, None]
            w = np.ones(2) if shape == "line2" else np.array([1 / 3, 1 / 3, 4 / 3])
        else:
            g, w = gauss(len(nodes_s))
            pts = g[:, None]
        return ("interface2d", lagrange(nodes_s), len(nodes_s), pts, w)
    raise ValueError(f"element type '{etype}' is not known to this checker")


# ------------------------------------------------------------------------------ internal forces
def stress_tensor(s, plane):
    """(npts, d, d) from rows sxx syy szz syz sxz sxy."""
    if plane:
        return np.stack([np.stack([s[:, 0], s[:, 5]], -1), np.stack([s[:, 5], s[:, 1]], -1)], -2)
    return np.stack([np.stack([s[:, 0], s[:, 5], s[:, 4]], -1),
                     np.stack([s[:, 5], s[:, 1], s[:, 3]], -1),
                     np.stack([s[:, 4], s[:, 3], s[:, 2]], -1)], -2)


def solid_forces(x, conn, etype, stress, fint):
    kind, shape, nn, pts, w = rule(etype)
    plane = kind == "solid2d"
    dim = 2 if plane else 3
    npts = len(w)
    nel = conn.shape[0]
    if stress.shape[0] != nel * npts:
        raise ValueError(f"{etype}: {stress.shape[0]} stress rows for {nel} elements x {npts} points")
    n, dn = evaluate(shape, pts)
    xe = x[conn][:, :, :dim]                                   # (nel, nn, dim)
    sig = stress_tensor(stress, plane).reshape(nel, npts, dim, dim)
    fe = np.zeros((nel, nn, dim))
    grads, dvs = [], []
    for g in range(npts):
        jac = np.einsum("ena,nb->eab", xe, dn[g])              # dx_a / dxi_b
        det = np.linalg.det(jac)
        if np.any(det <= 0):
            raise ValueError(f"{etype}: an element with det J <= 0 (node order?)")
        grad = np.einsum("nb,eba->ena", dn[g], np.linalg.inv(jac))   # dN/dx
        dv = w[g] * det
        grads.append(grad)
        dvs.append(dv)
        fe += dv[:, None, None] * np.einsum("ena,eab->enb", grad, sig[:, g])
    if etype.lower() == "hex8b":
        vol = sum(dvs)
        mean = sum(dv[:, None, None] * gr for dv, gr in zip(dvs, grads)) / vol[:, None, None]
        for g in range(npts):
            p = np.trace(sig[:, g], axis1=1, axis2=2) / 3
            fe += (dvs[g] * p)[:, None, None] * (mean - grads[g])
    np.add.at(fint[:, :dim], conn, fe)


def interface_frame(xl, dn, kind):
    """Per element at one point: (e1, e2, n, |J|) from the lower layer's coordinates (nel, nn, 3)."""
    if kind == "interface2d":
        a1 = np.einsum("enk,n->ek", xl, dn[:, 0])
        jl = np.linalg.norm(a1, axis=1)
        e1 = a1 / jl[:, None]
        nrm = np.column_stack([-e1[:, 1], e1[:, 0], np.zeros(len(e1))])
        return e1, None, nrm, jl
    a1 = np.einsum("enk,n->ek", xl, dn[:, 0])
    a2 = np.einsum("enk,n->ek", xl, dn[:, 1])
    e1 = a1 / np.linalg.norm(a1, axis=1)[:, None]
    ns = np.cross(a1, a2)
    ja = np.linalg.norm(ns, axis=1)
    nrm = ns / ja[:, None]
    return e1, np.cross(nrm, e1), nrm, ja


def interface_forces(x, u, conn, etype, traction, strain, fint):
    """Adds the interface's nodal forces; returns (max |written strain - own|, max |own strain|)."""
    kind, shape, nn, pts, w = rule(etype)
    npts, nel = len(w), conn.shape[0]
    if conn.shape[1] != 2 * nn:
        raise ValueError(f"{etype}: {conn.shape[1]} nodes per element, expected {2 * nn}")
    if traction.shape[0] != nel * npts:
        raise ValueError(f"{etype}: {traction.shape[0]} traction rows for {nel} elements x {npts} points")
    n, dn = evaluate(shape, pts)
    lo, up = conn[:, :nn], conn[:, nn:]
    xl = x[lo]
    t = traction.reshape(nel, npts, -1)
    st = strain.reshape(nel, npts, -1) if strain is not None else None
    fe = np.zeros((nel, nn, 3))
    err, big = 0.0, 0.0
    for g in range(npts):
        e1, e2, nrm, jac = interface_frame(xl, dn[g], kind)
        if kind == "interface2d":
            tg = t[:, g, 0:1] * e1 + t[:, g, 1:2] * nrm
        else:
            tg = t[:, g, 0:1] * e1 + t[:, g, 1:2] * e2 + t[:, g, 2:3] * nrm
        fe += (w[g] * jac)[:, None, None] * n[g][None, :, None] * tg[:, None, :]
        if st is not None and u is not None:
            jump = np.einsum("n,enk->ek", n[g], u[up] - u[lo])
            own = ([np.sum(jump * e1, 1), np.sum(jump * nrm, 1)] if kind == "interface2d" else
                   [np.sum(jump * e1, 1), np.sum(jump * e2, 1), np.sum(jump * nrm, 1)])
            own = np.column_stack(own)
            err = max(err, float(np.max(np.abs(own - st[:, g, :own.shape[1]]), initial=0.0)))
            big = max(big, float(np.max(np.abs(own), initial=0.0)))
    np.add.at(fint, up, fe)
    np.add.at(fint, lo, -fe)
    return err, big


def bar_forces(x, conn, etype, force, fint):
    kind, shape, nn, pts, w = rule(etype)
    npts, nel = len(w), conn.shape[0]
    if force.shape[0] != nel * npts:
        raise ValueError(f"{etype}: {force.shape[0]} rows for {nel} elements x {npts} points")
    n, dn = evaluate(shape, pts)
    f = force[:, 0].reshape(nel, npts)
    xe = x[conn]
    fe = np.zeros((nel, nn, 3))
    for g in range(npts):
        a = np.einsum("enk,n->ek", xe, dn[g, :, 0])
        tg = a / np.linalg.norm(a, axis=1)[:, None]
        fe += (w[g] * f[:, g])[:, None, None] * dn[g, :, 0][None, :, None] * tg[:, None, :]
    np.add.at(fint, conn, fe)


def stiffness_scale(f, group, kind):
    """The material's stiffness that turns a displacement into a force: E h (solids, MPa mm),
    Kn h^2 (interfaces, MPa mm), E A / h (bars, N / mm), without the element size h."""
    name = fr.text(f[f"mesh/groups/{group}"].attrs.get("material", ""))
    mat = f[f"materials/{name}"].attrs if name and f"materials/{name}" in f else {}
    get = lambda k: float(mat[k]) if k in mat else 0.0  # noqa: E731
    if kind.startswith("interface"):
        return max(get("kn"), get("ks")), 2
    if kind == "bar":
        return get("e") * get("a"), -1
    e = get("e") or 2 * get("g") * (1 + get("nu"))
    nu = get("nu")
    # the largest entry of the isotropic D: E (1 - nu) / ((1 + nu)(1 - 2 nu))
    return e * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) if -1 < nu < 0.5 else e, 1


def internal_forces(f, step):
    """(f_int (nnode, 3), [(group, frame error, frame scale)], rounding floor (N)).

    The floor is what rounding in the written stresses can leave at a node: a stress recovered
    from displacements u carries an error of about eps |u| / h times the stiffness, and a node
    gathers it from up to 8 elements of up to 27 points; 64 eps * stiffness * max|u_e| * h_e^k
    over the elements bounds it. It matters only where a stiff part moves far (E = 1e11 blocks)."""
    x = fr.coordinates(f)
    sg = f[f"steps/{step}"]
    u = sg["displacement"][...] if "displacement" in sg else None
    fint = np.zeros_like(x)
    frames = []
    floor = 0.0
    for group in fr.groups(f):
        etype = fr.element_type(f, group)
        conn = fr.connectivity(f, group)
        kind = rule(etype)[0]
        if u is not None:
            k, power = stiffness_scale(f, group, kind)
            h = np.ptp(x[conn], axis=1).max(axis=1)
            umax = np.abs(u[conn]).max(axis=(1, 2))
            if len(h):
                floor = max(floor, 64 * np.finfo(float).eps * k * float(np.max(umax * h ** power)))
        if kind.startswith("solid"):
            fr.require(f, f"steps/{step}/stress/{group}", " (the deck's FIELDS left out stress)")
            solid_forces(x, conn, etype, sg[f"stress/{group}"][...], fint)
        elif kind.startswith("interface"):
            fr.require(f, f"steps/{step}/interface/{group}", " (the deck's FIELDS left out interface)")
            key = f"interface_strain/{group}"
            strain = sg[key][...] if key in sg else None
            err, big = interface_forces(x, u, conn, etype, sg[f"interface/{group}"][...], strain, fint)
            if strain is not None and u is not None:
                frames.append((group, err, big))
        else:
            fr.require(f, f"steps/{step}/bar/{group}", " (the deck's FIELDS left out bar)")
            bar_forces(x, conn, etype, sg[f"bar/{group}"][...], fint)
    return fint, frames, floor


# ------------------------------------------------------------------------------ the deck's load sets
def deck_records(path):
    records = []
    with open(path, encoding="utf-8", errors="replace") as fh:
        for line in fh:
            line = line.split("!", 1)[0].strip()
            if not line:
                continue
            fields = [v.strip() for v in line.split(",")]
            if fields and fields[-1] == "":
                fields.pop()
            if fields and not re.match(r"[0-9+\-.]", fields[0]):
                records.append(fields)
    return records


def options(fields):
    out = {}
    for v in fields:
        if "=" in v:
            k, val = v.split("=", 1)
            out[k.strip().upper()] = val.strip()
    return out


def csys_coords(x, csys, systems):
    """Coordinates (names -> arrays) of points x in system csys."""
    if csys in (1, 2):
        return {"X": x[:, 0], "Y": x[:, 1], "Z": x[:, 2]}
    if csys == 3:
        origin, axis, ref = np.zeros(3), np.array([0, 0, 1.0]), np.array([1.0, 0, 0])
        kind = "CYLINDRICAL"
    elif csys in systems:
        kind, origin, axis, ref = systems[csys]
        if kind == "CARTESIAN":
            d = x - origin
            return {"X": d[:, 0], "Y": d[:, 1], "Z": d[:, 2]}
    else:
        raise ValueError(f"coordinate system {csys} is not defined")
    d = x - origin
    z = d @ axis
    rad = d - np.outer(z, axis)
    er = ref - (ref @ axis) * axis
    er /= np.linalg.norm(er)
    et = np.cross(axis, er)
    theta = np.degrees(np.arctan2(rad @ et, rad @ er)) % 360.0
    return {"R": np.linalg.norm(rad, axis=1), "THETA": theta, "T": theta, "Z": z}


def in_range(values, text, tol, angle):
    lo, _, hi = text.partition(":")
    lo = float(lo)
    hi = float(hi) if hi else lo
    if angle:
        shifted = lo + (values - lo + tol) % 360.0 - tol
        return shifted <= hi + tol
    return (values >= lo - tol) & (values <= hi + tol)


def select(x, opts, systems, group_nodes):
    if "NODE" in opts:
        return np.array([int(opts["NODE"]) - 1])
    csys = int(opts.get("CSYS", "2"))
    tol = float(opts.get("TOL", "1e-6"))
    coords = csys_coords(x, csys, systems)
    mask = np.ones(len(x), bool)
    for key, val in opts.items():
        if key in ("CSYS", "TOL", "GROUP", "NODE"):
            continue
        if key not in coords:
            raise ValueError(f"coordinate {key} is not one of system {csys}")
        mask &= in_range(coords[key], val, tol, key in ("THETA", "T"))
    if "GROUP" in opts:
        keep = np.zeros(len(x), bool)
        keep[group_nodes(opts["GROUP"])] = True
        mask &= keep
    return np.flatnonzero(mask)


def deck_loads(f, deck):
    """(loaded node indices, [(record text, nodes, known resultant or None)], one stage?, nodal
    systems (nnode, 3, 3): the rows are a node's directions, from its FIX/DISPLACE CSYS) of a deck."""
    x = fr.coordinates(f)
    records = deck_records(deck)
    systems, sets = {}, {}
    ncsys = 3
    group_nodes = lambda g: fr.group_nodes(f, g)  # noqa: E731
    for rec in records:
        key = rec[0].upper()
        if key == "CSYS":
            ncsys = int(rec[1])
            vals = [float(v) for v in rec[3:] if v]
            kind = rec[2].upper()
            origin = np.array(vals[0:3])
            axis = np.array(vals[3:6]) if kind == "CYLINDRICAL" else np.array([0, 0, 1.0])
            axis = axis / np.linalg.norm(axis)
            if len(vals) >= 9:
                ref = np.array(vals[6:9])
            else:
                ref = np.array([0, 1.0, 0]) if abs(abs(axis[0]) - 1) < 1e-12 else np.array([1.0, 0, 0])
            systems[ncsys] = (kind, origin, axis, ref)
        elif key in ("NSET", "FSET"):
            sets[rec[1]] = (key, options(rec[2:]))
    basis = np.broadcast_to(np.eye(3), (len(x), 3, 3)).copy()
    builtin = {3: ("CYLINDRICAL", np.zeros(3), np.array([0, 0, 1.0]), np.array([1.0, 0, 0]))}
    for rec in records:
        key = rec[0].upper()
        if key in ("FIX", "DISPLACE", "RELEASE") and len(rec) > 1 and rec[1] in sets:
            csys = int(options(rec[2:]).get("CSYS", "2"))
            if csys > 2:
                system = builtin.get(csys) or systems.get(csys)
                if system is None:
                    raise ValueError(f"{deck}: {key} in coordinate system {csys}, which no CSYS defines")
                nodes = select(x, sets[rec[1]][1], systems, group_nodes)
                basis[nodes] = nodal_directions(x[nodes], system)
    loaded = set()
    # loads on nodes of no load record: a released support's force while its stage removes it,
    # a post-tensioned tendon's pull on its nodes in its stage
    for rec in records:
        key = rec[0].upper()
        if key == "RELEASE" and len(rec) > 1 and rec[1] in sets:
            loaded.update(select(x, sets[rec[1]][1], systems, group_nodes).tolist())
        elif key == "PRESTRESS" and options(rec[2:]).get("BOND", "").upper() == "AFTER":
            loaded.update(group_nodes(rec[1]).tolist())
    loads = []
    stages = sum(1 for rec in records if rec[0].upper() == "STAGE")
    for rec in records:
        key = rec[0].upper()
        if key not in ("FORCE", "PRESSURE", "TRACTION"):
            continue
        name = rec[1]
        if name not in sets:
            raise ValueError(f"{deck}: {key} on set {name}, which no NSET or FSET defines")
        nodes = select(x, sets[name][1], systems, group_nodes)
        loaded.update(nodes.tolist())
        loads.append((",".join(rec), nodes, known_resultant(key, rec, sets[name][1], nodes, x, f)))
    born = set()
    for rec in records:
        if rec[0].upper() == "STAGE":
            for v in rec[2:]:
                k, _, val = v.partition("=")
                if k.strip().upper() == "ACTIVATE":
                    born.update(g.strip() for g in val.split(":"))
    return np.array(sorted(loaded), dtype=np.int64), loads, stages <= 1, basis, born


def known_resultant(key, rec, set_opts, nodes, x, f):
    """The load record's resultant where it follows from the record alone, else None."""
    opts = options(rec[2:])
    csys = int(opts.get("CSYS", "2"))
    dirs = {"X": 0, "UX": 0, "1": 0, "Y": 1, "UY": 1, "2": 1, "Z": 2, "UZ": 2, "3": 2}
    if key == "FORCE" and csys in (1, 2):
        v = np.zeros(3)
        for k, val in opts.items():
            if k in dirs:
                v[dirs[k]] += float(val)
        return v * len(nodes)
    if "TOTAL" not in opts:
        return None
    total = float(opts["TOTAL"])
    if key == "TRACTION":
        if csys not in (1, 2):
            return None
        v = np.zeros(3)
        for k, val in opts.items():
            if k in dirs:
                v[dirs[k]] += float(val)
        return total * v / np.linalg.norm(v)
    # PRESSURE with TOTAL on a plane face set normal to a global axis: the resultant pushes
    # into the group's elements, towards the side where its nodes lie
    span = np.ptp(x[nodes], axis=0)
    axes = np.flatnonzero(span < 1e-9 * max(1.0, np.ptp(x, axis=0).max()))
    if len(axes) != 1 or "GROUP" not in set_opts:
        return None
    a = int(axes[0])
    plane = x[nodes[0], a]
    side = x[fr.group_nodes(f, set_opts["GROUP"]), a] - plane
    if np.all(side >= -1e-9):
        sign = 1.0
    elif np.all(side <= 1e-9):
        sign = -1.0
    else:
        return None
    v = np.zeros(3)
    v[a] = sign * total
    return v


# ------------------------------------------------------------------------------ checks
def nodal_directions(x, system):
    """(n, 3, 3): rows radial, hoop, axial of a cylindrical system at points x (Cartesian: global)."""
    kind, origin, axis, ref = system
    if kind != "CYLINDRICAL":
        return np.broadcast_to(np.eye(3), (len(x), 3, 3)).copy()
    d = x - origin
    rad = d - np.outer(d @ axis, axis)
    rad /= np.linalg.norm(rad, axis=1)[:, None]
    hoop = np.cross(axis, rad)
    return np.stack([rad, hoop, np.broadcast_to(axis, rad.shape)], axis=1)


def verdict(value, tol):
    return "PASS" if value <= tol else "FAIL"


def run(args):
    f = fr.open_result(args.result)
    with f:
        if "mesh/coordinates" not in f:
            raise ValueError(f"{args.result}: no /mesh/coordinates (not a feps result file?)")
        step = fr.pick_step(f, args.step)
        sg = f[f"steps/{step}"]
        fr.require(f, f"steps/{step}/reaction", " (the deck's FIELDS left out reaction)")
        residual = float(sg.attrs.get("residual", 0.0))
        lf = float(sg.attrs.get("load_factor", float("nan")))
        r = sg["reaction"][...]
        rn = sg["reaction_nodal"][...] if "reaction_nodal" in sg else None
        fint, frames, floor = internal_forces(f, step)
        used_nodes = np.unique(np.concatenate([fr.connectivity(f, g).ravel() for g in fr.groups(f)]))
        x = fr.coordinates(f)
        deck = args.deck
        if deck is None and "summary" in f and "input_file" in f["summary"].attrs:
            deck = fr.text(f["summary"].attrs["input_file"])
        if deck is not None and args.deck is None and not os.path.isfile(deck) and not os.path.isabs(deck):
            # a deck named relative to the folder the run was started in: try the result's folder
            beside = os.path.join(os.path.dirname(os.path.abspath(args.result)), deck)
            deck = beside if os.path.isfile(beside) else deck
        if deck is None or not os.path.isfile(deck):
            raise ValueError(f"{args.result}: the deck {deck!r} cannot be read (give --deck)")
        loaded, loads, one_stage, basis, born = deck_loads(f, deck)

    nnode = len(fint)
    used = np.zeros(nnode, bool)
    used[used_nodes] = True
    g = fint - r
    has_r = np.linalg.norm(r, axis=1) > 0
    is_loaded = np.zeros(nnode, bool)
    is_loaded[loaded] = True
    free = ~has_r & ~is_loaded
    held = has_r & ~is_loaded
    pnorm = max(np.linalg.norm(r), np.linalg.norm(g[is_loaded]))
    if pnorm == 0:
        pnorm = 1.0
    rounding = max(ROUNDING, floor / pnorm)
    tol = residual + rounding
    fails = 0
    print(f"{args.result} step {step}: load factor {lf:g}, residual {residual:.3e}, |P| = {pnorm:.6e} N, "
          f"{nnode} nodes: {free.sum()} free, {held.sum()} with reactions, {is_loaded.sum()} loaded (not checked one by one)")
    for group, err, big in frames:
        if group in born:
            print(f"interface-frame {group}: SKIP (born by ACTIVATE: its strains count from its birth)")
            continue
        rel = err / big if big > 0 else err
        v = verdict(rel, FRAME_TOL)
        fails += v == "FAIL"
        print(f"interface-frame {group}: max |written - own relative displacement| = {err:.3e} mm "
              f"(/ max {big:.3e} = {rel:.3e}), tol {FRAME_TOL:.0e}: {v}")
    for name, mask in (("free-nodes", free), ("supports", held)):
        if not mask.any():
            print(f"{name}: no such node")
            continue
        rel = np.linalg.norm(g[mask]) / pnorm
        worst = int(np.argmax(np.linalg.norm(g * mask[:, None], axis=1)))
        v = verdict(rel, tol)
        fails += v == "FAIL"
        print(f"{name}: |f_int - r| = {rel:.3e} |P| (2-norm), max {np.abs(g[mask]).max() / pnorm:.3e} |P| at node "
              f"{worst + 1}, tol residual + rounding {rounding:.1e} = {tol:.3e}: {v}")
    # the reactions in the nodal systems: written (reaction_nodal) or, without it, the global ones
    rnod = np.einsum("nij,nj->ni", basis, r)
    if rn is not None:
        rel = np.abs(rn - rnod).max() / pnorm
        v = verdict(rel, ROUNDING)
        fails += v == "FAIL"
        print(f"reaction-nodal: max |reaction_nodal - (nodal directions) r| = {rel:.3e} |P| "
              f"({int((np.abs(basis - np.eye(3)).max(axis=(1, 2)) > 0).sum())} nodes in a nodal system), "
              f"tol {ROUNDING:.0e}: {v}")
    # held directions: g must vanish there to rounding, whatever the residual (feps's reaction is
    # f_int - f_ext there); the held directions are those with a nonzero nodal reaction (a free
    # direction of a node in a nodal system may hold ~1e-26 N from the rotation)
    comp = np.einsum("nij,nj->ni", basis, g)
    mask = (np.abs(rnod) > 1e-12 * np.abs(r).max()) & held[:, None]
    rel = np.abs(comp[mask]).max(initial=0.0) / pnorm
    v = verdict(rel, rounding)
    fails += v == "FAIL"
    print(f"held-directions: max |f_int - r| in the {mask.sum()} held directions = {rel:.3e} |P|, "
          f"tol {rounding:.1e}: {v}")
    total_r = r.sum(axis=0)
    applied = None
    source = ""
    if args.applied is not None:
        applied, source = args.applied, "--applied"
    elif one_stage and loads and all(k is not None for _, _, k in loads):
        applied, source = lf * sum(k for _, _, k in loads), "deck x load factor"
    for text, nodes, known in loads:
        res = g[nodes].sum(axis=0)
        want = "" if known is None or not one_stage else f", the record x load factor gives {np.array2string(lf * known, precision=6)}"
        print(f"  load {text}: {len(nodes)} nodes, sum (f_int - r) = {np.array2string(res, precision=6)} N{want}")
    if applied is None:
        print(f"applied: sum r = {np.array2string(total_r, precision=6)} N; the applied total is not known "
              f"from the deck alone (give --applied FX,FY,FZ): SKIP")
    else:
        # sum r + applied = -(sum of the residual vector over the free DOFs), which the step's
        # residual bounds by sqrt(free DOFs) |R| (Cauchy-Schwarz), not by |R|
        ndof = 3 * used.sum() - int(mask.sum())
        tol3 = residual * math.sqrt(max(ndof, 1)) + rounding
        rel = np.linalg.norm(total_r + applied) / pnorm
        v = verdict(rel, tol3)
        tol = tol3
        fails += v == "FAIL"
        print(f"applied: |sum r + applied| = {rel:.3e} |P| (sum r = {np.array2string(total_r, precision=6)}, "
              f"applied = {np.array2string(np.asarray(applied), precision=6)} from {source}), "
              f"tol residual sqrt({ndof} free DOFs) + rounding = {tol:.3e}: {v}")
    return 1 if fails else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("--step", help="step number (default: the last)")
    ap.add_argument("--deck", help="the deck (default: /summary input_file)")
    ap.add_argument("--applied", help="total applied force FX,FY,FZ (N) at the step")
    args = ap.parse_args()
    if args.applied is not None:
        text = args.applied
        try:
            args.applied = np.array([float(v) for v in text.split(",")])
            assert args.applied.shape == (3,)
        except (ValueError, AssertionError):
            print(f"check_equilibrium: error: --applied {text!r}: expected FX,FY,FZ", file=sys.stderr)
            return 2
    try:
        return run(args)
    except (ValueError, KeyError, OSError, IndexError, TypeError) as exc:
        msg = str(exc).strip().replace("\n", " ")
        print(f"check_equilibrium: error: {msg}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
