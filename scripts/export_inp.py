#!/usr/bin/env python3
"""Write a CalculiX (Abaqus-style) .inp of a linear feps model: mesh from feps's HDF5 file,
materials, supports and loads from the feps deck.

  python3 scripts/export_inp.py run.h5 deck.dat -o model.inp

The mesh (/mesh/coordinates, /mesh/groups/<g>/connectivity) is taken from the HDF5 file feps
wrote for the deck (a mesh-only or a full run), so node and element numbers are feps's own:
CalculiX node n is feps node n. hex8 -> C3D8 (2x2x2 Gauss), hex20 -> C3D20 (3x3x3),
hex20r -> C3D20R (2x2x2); the node order of feps's hex8 and hex20 is Abaqus's.

Supports and loads are not in the HDF5 file, so they are rebuilt from the deck with feps's
rules (docs/input-format.md): NSET (by coordinate ranges in system 2 or 3, TOL, GROUP=, or
NODE=), FIX (global X, Y, Z), FORCE (system 2 or 3), FSET and PRESSURE (VALUE= or TOTAL=,
uniform or linear in one coordinate with ZERO= and PEAK=). Pressures become CalculiX *CLOAD
nodal forces computed as feps computes them: the load's shape at the face Gauss points (2x2 on
hex8 faces, 3x3 on hex20 faces) times the face shape functions and area, with TOTAL= scaled by
the same quadrature. A per-face *DLOAD could not carry feps's intensity, which varies inside a
face and is cut off at ZERO.

Only what a linear run with one load case needs is accepted (PARAMETERS records are labels and
are skipped): ELASTIC materials, solid groups
hex8/hex20/hex20r, at most one STAGE with LOAD=1. Anything else (interfaces, DISPLACE,
TRACTION, CSYS, nodal systems in FIX, several stages) is refused with the deck's line number.
The step asks for the displacements of all nodes in the .dat file (*NODE PRINT, which
scripts/bench_calculix.sh compares with feps's node by node) and for no other output.
A deck the exporter cannot translate exits with status 1, naming the deck's line; a file that
is missing or cannot be read, with status 2.
"""
import argparse
import math
import os
import sys

import h5py
import numpy as np

CCX_TYPE = {"hex8": "C3D8", "hex20": "C3D20", "hex20r": "C3D20R"}

# Face node lists (1-based local numbers, counter-clockwise seen from outside, as feps's
# hex8 and hex20 elements and Abaqus's faces S1..S6).
HEX8_FACES = [(1, 4, 3, 2), (5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (1, 5, 8, 4)]
HEX20_FACES = [(1, 4, 3, 2, 12, 11, 10, 9), (5, 6, 7, 8, 13, 14, 15, 16), (1, 2, 6, 5, 9, 18, 13, 17),
               (2, 3, 7, 6, 10, 19, 14, 18), (3, 4, 8, 7, 11, 20, 15, 19), (1, 5, 8, 4, 17, 16, 20, 12)]
QUAD_CORNERS = np.array([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)])

DATAIN_KEYS = {"A", "%", "E"}
IGNORED = {"TITLE", "REPORT", "SOLVER", "OUTPUT", "CONTROLS", "INCLUDE", "NODE", "PARAMETERS"}


class DeckError(Exception):
    pass


def gauss_1d(n):
    if n == 2:
        return np.array([-1.0, 1.0]) / math.sqrt(3.0), np.array([1.0, 1.0])
    if n == 3:
        return np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0
    raise ValueError(n)


def square_rule(n):
    x, w = gauss_1d(n)
    pts = [(x[i], x[j]) for j in range(n) for i in range(n)]
    wts = [w[i] * w[j] for j in range(n) for i in range(n)]
    return np.array(pts), np.array(wts)


def quad4_shape(s, t):
    n = np.empty(4)
    dn = np.empty((2, 4))
    for a, (sa, ta) in enumerate(QUAD_CORNERS):
        n[a] = 0.25 * (1 + s * sa) * (1 + t * ta)
        dn[0, a] = 0.25 * sa * (1 + t * ta)
        dn[1, a] = 0.25 * ta * (1 + s * sa)
    return n, dn


def quad8_shape(s, t):
    """Serendipity quadrilateral: corners as QUAD_CORNERS, then mid-sides 1-2, 2-3, 3-4, 4-1."""
    n = np.empty(8)
    dn = np.empty((2, 8))
    for a, (sa, ta) in enumerate(QUAD_CORNERS):
        n[a] = 0.25 * (1 + s * sa) * (1 + t * ta) * (s * sa + t * ta - 1)
        dn[0, a] = 0.25 * sa * (1 + t * ta) * (2 * s * sa + t * ta)
        dn[1, a] = 0.25 * ta * (1 + s * sa) * (s * sa + 2 * t * ta)
    for a, (sa, ta) in enumerate([(0, -1), (1, 0), (0, 1), (-1, 0)], start=4):
        if sa == 0:
            n[a] = 0.5 * (1 - s * s) * (1 + t * ta)
            dn[0, a] = -s * (1 + t * ta)
            dn[1, a] = 0.5 * ta * (1 - s * s)
        else:
            n[a] = 0.5 * (1 - t * t) * (1 + s * sa)
            dn[0, a] = 0.5 * sa * (1 - t * t)
            dn[1, a] = -t * (1 + s * sa)
    return n, dn


def face_rule(nface_nodes):
    pts, wts = square_rule(2 if nface_nodes == 4 else 3)
    shape = quad4_shape if nface_nodes == 4 else quad8_shape
    return [(shape(s, t), w) for (s, t), w in zip(pts, wts)]


def to_system(csys, x):
    """Coordinates of global points x (..., 3) in system 2 (Cartesian) or 3 (cylindrical, deg)."""
    if csys in (1, 2):
        return np.array(x, dtype=float)
    r = np.hypot(x[..., 0], x[..., 1])
    th = np.degrees(np.arctan2(x[..., 1], x[..., 0]))
    return np.stack([r, th, x[..., 2]], axis=-1)


def local_basis(csys, x):
    """Columns: the system's unit directions at point x (radial, hoop, axial if cylindrical)."""
    if csys in (1, 2):
        return np.eye(3)
    th = math.atan2(x[1], x[0])
    c, s = math.cos(th), math.sin(th)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


# ---------------------------------------------------------------------------- deck reading

def records(path):
    """(line number, fields) of the deck's records; DATAIN continuation lines are dropped."""
    out = []
    with open(path) as f:
        for lineno, line in enumerate(f, start=1):
            line = line.split("!", 1)[0].strip()
            if not line:
                continue
            fields = [x.strip() for x in line.split(",")]
            if fields and fields[-1] == "":
                fields.pop()
            if not fields:
                continue
            first = fields[0]
            if first[:1].isdigit() or first[:1] in "+-." or first.upper() in DATAIN_KEYS:
                continue  # DATAIN (the mesh comes from the HDF5 file)
            out.append((lineno, fields))
    return out


def options(fields, lineno, path):
    opts = {}
    for x in fields:
        if "=" not in x:
            raise DeckError(f"{path}:{lineno}: expected KEY=value, got {x!r}")
        k, v = x.split("=", 1)
        opts[k.strip().upper()] = v.strip()
    return opts


def parse_range(text):
    if ":" in text:
        lo, hi = text.split(":", 1)
        return float(lo), float(hi)
    v = float(text)
    return v, v


COORD_INDEX = {2: {"X": 0, "Y": 1, "Z": 2}, 3: {"R": 0, "THETA": 1, "T": 1, "Z": 2}}


def region_of(opts, lineno, path):
    csys = int(opts.pop("CSYS", "2"))
    if csys == 1:
        csys = 2
    if csys not in (2, 3):
        raise DeckError(f"{path}:{lineno}: coordinate system {csys} is not supported by the exporter")
    tol = float(opts.pop("TOL", "1e-6"))
    ranges = {}
    for key in list(opts):
        if key in COORD_INDEX[csys]:
            ranges[COORD_INDEX[csys][key]] = parse_range(opts.pop(key))
    return {"csys": csys, "tol": tol, "ranges": ranges}


def in_region(region, x):
    """Boolean mask of the points x (n, 3) in the region, with feps's tolerance and theta rule."""
    c = to_system(region["csys"], x)
    tol = region["tol"]
    mask = np.ones(len(x), dtype=bool)
    for k, (lo, hi) in region["ranges"].items():
        if k == 1 and region["csys"] == 3:
            t = np.mod(c[:, 1] - (lo - tol), 360.0) + (lo - tol)
            mask &= t <= hi + tol
        else:
            mask &= (c[:, k] >= lo - tol) & (c[:, k] <= hi + tol)
    return mask


def read_deck(path):
    deck = {"groups": {}, "materials": {}, "nsets": {}, "fsets": {}, "fixes": [], "forces": [],
            "pressures": [], "stages": []}
    for lineno, f in records(path):
        key = f[0].upper()
        where = f"{path}:{lineno}"
        stage = len(deck["stages"])
        if key in IGNORED:
            continue
        if key == "GROUP":
            o = options(f[2:], lineno, path)
            gtype = o.get("TYPE", "").lower()
            if gtype not in CCX_TYPE:
                raise DeckError(f"{where}: element type {gtype!r} has no CalculiX equivalent in the exporter")
            deck["groups"][f[1]] = {"type": gtype, "material": o.get("MATERIAL")}
        elif key == "MATERIAL":
            if f[2].upper() != "ELASTIC":
                raise DeckError(f"{where}: only ELASTIC materials are exported (got {f[2]})")
            o = {k: float(v) for k, v in options(f[3:], lineno, path).items()}
            nu = o["NU"]
            e = o["E"] if "E" in o else 2.0 * o["G"] * (1.0 + nu)
            deck["materials"][f[1]] = (e, nu)
        elif key == "NSET":
            o = options(f[2:], lineno, path)
            if "NODE" in o:
                deck["nsets"][f[1]] = {"node": int(o["NODE"])}
            else:
                group = o.pop("GROUP", None)
                reg = region_of(o, lineno, path)
                if o:
                    raise DeckError(f"{where}: unknown NSET options {sorted(o)}")
                deck["nsets"][f[1]] = {"region": reg, "group": group}
        elif key == "FSET":
            o = options(f[2:], lineno, path)
            group = o.pop("GROUP")
            reg = region_of(o, lineno, path)
            if o:
                raise DeckError(f"{where}: unknown FSET options {sorted(o)}")
            deck["fsets"][f[1]] = {"region": reg, "group": group}
        elif key == "FIX":
            dofs = set()
            for x in f[2:]:
                u = x.upper()
                if u.startswith("CSYS=") and int(u[5:]) != 2:
                    raise DeckError(f"{where}: FIX in a nodal system is not exported")
                if u.startswith("CSYS="):
                    continue
                if u == "ALL":
                    dofs |= {1, 2, 3}
                else:
                    dofs.add({"X": 1, "UX": 1, "1": 1, "Y": 2, "UY": 2, "2": 2, "Z": 3, "UZ": 3, "3": 3}[u])
            deck["fixes"].append((f[1], sorted(dofs)))
        elif key == "FORCE":
            o = options(f[2:], lineno, path)
            csys = int(o.pop("CSYS", "2"))
            if csys not in (2, 3):
                raise DeckError(f"{where}: FORCE in system {csys} is not exported")
            names = {2: {"X": 0, "UX": 0, "1": 0, "Y": 1, "UY": 1, "2": 1, "Z": 2, "UZ": 2, "3": 2},
                     3: {"R": 0, "1": 0, "T": 1, "THETA": 1, "2": 1, "Z": 2, "3": 2}}[csys]
            comp = np.zeros(3)
            for k, v in o.items():
                comp[names[k]] = float(v)
            deck["forces"].append({"set": f[1], "csys": csys, "components": comp, "stage": stage})
        elif key == "PRESSURE":
            o = options(f[2:], lineno, path)
            p = {"set": f[1], "stage": stage}
            if "TOTAL" in o:
                p["total"] = float(o.pop("TOTAL"))
            else:
                p["value"] = float(o.pop("VALUE"))
            if "VARY" in o:
                vcs = int(o.pop("VARY_CSYS", "0"))
                coord = o.pop("VARY").upper()
                if vcs == 0:
                    vcs = 2 if coord in ("X", "Y", "Z") else 3
                p["vary"] = (vcs, COORD_INDEX[vcs][coord], float(o.pop("ZERO")), float(o.pop("PEAK")))
            if o:
                raise DeckError(f"{where}: unknown PRESSURE options {sorted(o)}")
            deck["pressures"].append(p)
        elif key == "STAGE":
            o = options(f[2:], lineno, path)
            deck["stages"].append(float(o.get("LOAD", "1")))
            if len(deck["stages"]) > 1:
                raise DeckError(f"{where}: more than one STAGE: the exporter writes one load case")
            if deck["stages"][0] != 1.0:
                raise DeckError(f"{where}: LOAD= other than 1 is not exported")
        else:
            raise DeckError(f"{where}: keyword {f[0]} is not supported by the exporter")
    return deck


# ---------------------------------------------------------------------------- model building

def node_set(deck, name, coords, groups):
    s = deck["nsets"][name]
    if "node" in s:
        return np.array([s["node"]])
    mask = in_region(s["region"], coords)
    if s["group"] is not None:
        used = np.zeros(len(coords), dtype=bool)
        used[groups[s["group"]]["conn"].ravel() - 1] = True
        mask &= used
    nodes = np.flatnonzero(mask) + 1
    if len(nodes) == 0:
        raise DeckError(f"node set {name} selects no node")
    return nodes


def face_set(deck, name, coords, groups):
    s = deck["fsets"][name]
    conn = groups[s["group"]]["conn"]
    faces = HEX8_FACES if conn.shape[1] == 8 else HEX20_FACES
    inside = in_region(s["region"], coords)
    out = []
    for e in range(len(conn)):
        for fn in faces:
            nodes = conn[e, [a - 1 for a in fn]]
            if inside[nodes - 1].all():
                out.append(nodes)
    if not out:
        raise DeckError(f"face set {name} selects no element face")
    return out


def pressure_forces(p, faces, coords):
    """Nodal forces {node: (3,)} of a pressure on faces, integrated as feps does."""
    rule = face_rule(len(faces[0]))

    def shape_at(x):
        if "vary" not in p:
            return 1.0
        csys, k, zero, peak = p["vary"]
        c = to_system(csys, x)[k]
        return max(0.0, (c - zero) / (peak - zero))

    points = []  # per face: list of (nodal weights N*w*dA, unit normal, shape value)
    integral = 0.0
    for nodes in faces:
        xf = coords[nodes - 1]
        pts = []
        for (n, dn), w in rule:
            xg = n @ xf
            c = np.cross(dn[0] @ xf, dn[1] @ xf)
            da = np.linalg.norm(c)
            normal = c / da if da > 0 else np.zeros(3)
            sh = shape_at(xg)
            integral += sh * w * da
            pts.append((n * w * da, normal, sh))
        points.append((nodes, pts))
    if "total" in p:
        if not integral > 0:
            raise DeckError(f"pressure on {p['set']}: the load shape integrates to zero")
        peak = p["total"] / integral
    else:
        peak = p["value"]
    forces = {}
    for nodes, pts in points:
        for nw, normal, sh in pts:
            t = -peak * sh * normal
            for a, node in enumerate(nodes):
                forces.setdefault(int(node), np.zeros(3))
                forces[int(node)] += nw[a] * t
    return forces


def build(h5path, deckpath):
    deck = read_deck(deckpath)
    with h5py.File(h5path, "r") as h:
        coords = h["mesh/coordinates"][...]
        groups = {}
        for name, g in h["mesh/groups"].items():
            if name not in deck["groups"]:
                raise DeckError(f"group {name} of {h5path} is not in the deck")
            conn = g["connectivity"][...]
            groups[name] = {"conn": conn, **deck["groups"][name]}
    load_factor = deck["stages"][0] if deck["stages"] else 1.0

    fixed = {}
    for name, dofs in deck["fixes"]:
        for n in node_set(deck, name, coords, groups):
            fixed.setdefault(int(n), set()).update(dofs)

    forces = {}

    def add(node, f, factor):
        forces.setdefault(node, np.zeros(3))
        forces[node] += factor * f

    for fl in deck["forces"]:
        factor = load_factor if fl["stage"] == 0 else 1.0
        for n in node_set(deck, fl["set"], coords, groups):
            add(int(n), local_basis(fl["csys"], coords[n - 1]) @ fl["components"], factor)
    for p in deck["pressures"]:
        factor = load_factor if p["stage"] == 0 else 1.0
        for n, f in pressure_forces(p, face_set(deck, p["set"], coords, groups), coords).items():
            add(n, f, factor)
    return deck, coords, groups, fixed, forces


def num(v):
    """Shortest text that reads back as the same double; CalculiX reads at most 20 characters
    of a number, so longer ones keep 14 significant digits."""
    text = repr(float(v))
    return text if len(text) <= 20 else f"{float(v):.13e}"


def write_inp(out, deck, coords, groups, fixed, forces, source):
    w = out.write
    w(f"** CalculiX input written by scripts/export_inp.py from {source}\n")
    w("*HEADING\n")
    w(f"feps model {source}\n")
    w("*NODE, NSET=NALL\n")
    for i, x in enumerate(coords, start=1):
        w(f"{i}, {num(x[0])}, {num(x[1])}, {num(x[2])}\n")
    first = 1
    for name, g in groups.items():
        w(f"*ELEMENT, TYPE={CCX_TYPE[g['type']]}, ELSET={name}\n")
        for e, row in enumerate(g["conn"], start=first):
            nodes = [str(int(n)) for n in row]
            # At most 16 entries on a data line: C3D20 continues on a second line.
            w(", ".join([str(e)] + nodes[:15]) + ("," if len(nodes) > 15 else "") + "\n")
            if len(nodes) > 15:
                w(", ".join(nodes[15:]) + "\n")
        first += len(g["conn"])
    for mat in dict.fromkeys(g["material"] for g in groups.values()):
        e, nu = deck["materials"][mat]
        w(f"*MATERIAL, NAME={mat}\n*ELASTIC\n{num(e)}, {num(nu)}\n")
    for name, g in groups.items():
        w(f"*SOLID SECTION, ELSET={name}, MATERIAL={g['material']}\n")
    w("*BOUNDARY\n")
    for n in sorted(fixed):
        for d in sorted(fixed[n]):
            w(f"{n}, {d}, {d}, 0.\n")
    w("*STEP\n*STATIC, SOLVER=SPOOLES\n*CLOAD\n")
    for n in sorted(forces):
        for d in range(3):
            if forces[n][d] != 0.0:
                w(f"{n}, {d + 1}, {num(forces[n][d])}\n")
    w("*NODE PRINT, NSET=NALL\nU\n*END STEP\n")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("h5", help="feps results (or mesh-only) HDF5 file of the deck")
    p.add_argument("deck", help="the feps deck (materials, supports, loads)")
    p.add_argument("-o", "--output", required=True, help=".inp file to write")
    a = p.parse_args()
    for path, what in ((a.h5, "HDF5 file"), (a.deck, "deck")):
        if not os.path.isfile(path):
            print(f"export_inp: error: no {what} {path}", file=sys.stderr)
            return 2
    try:
        deck, coords, groups, fixed, forces = build(a.h5, a.deck)
    except (DeckError, KeyError, ValueError) as exc:
        print(f"export_inp: error: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        # a deck that cannot be read, or a file that is not HDF5 (h5py's message)
        print(f"export_inp: error: cannot read {exc.filename or a.h5}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    try:
        with open(a.output, "w") as out:
            write_inp(out, deck, coords, groups, fixed, forces, a.deck)
    except OSError as exc:
        print(f"export_inp: error: cannot write {a.output}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    total = sum(forces.values()) if forces else np.zeros(3)
    nfix = sum(len(d) for d in fixed.values())
    print(f"export_inp: {len(coords)} nodes, {sum(len(g['conn']) for g in groups.values())} elements, "
          f"{nfix} fixed DOFs, {len(forces)} loaded nodes, resultant {total[0]:.6g} {total[1]:.6g} "
          f"{total[2]:.6g} N -> {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
