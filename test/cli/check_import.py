#!/usr/bin/env python3
"""Checks of scripts/import_mesh.py: meshes made by gmsh and models written for CalculiX, imported,
run by feps and compared with closed forms and with CalculiX's own results.

    python3 test/cli/check_import.py [--feps PATH]        (FEPS: the executable; default fpm's debug build)

1. A quarter of a thick pipe (r 600..715 mm, 200 mm long, plane strain: both ends held axially,
   the symmetry planes on rollers) under 1 MPa of internal pressure, meshed by gmsh (from PyPI)
   in this script, in tet10 (a .msh of format 4.1) and in hex20 (format 2.2); its radial
   displacement at every node against Lame's solution.
2. CalculiX's published test examples (Debian's calculix-ccx-test, installed by scripts/setup.sh)
   that use only solids and the keywords import_mesh.py translates: the deck runs as written and
   its displacements agree node by node with the example's .dat.ref to the 7 digits it prints.
3. What cannot be translated is one line naming file, line and keyword, exit status 2, no deck.
"""
import argparse
import gzip
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from feps_cli import feps_option  # noqa: E402

EXAMPLES = "/usr/share/doc/calculix-ccx-test/examples/test"
# the examples within what import_mesh.py translates (a linear-static step, solids only), one per
# element type it maps, the pressure, nodal force and prescribed displacement paths among them
CCX_CASES = {"beam8p": "C3D8, nodal forces", "beam10p": "C3D10, nodal forces",
             "beampset": "C3D20R, nodal forces", "achtelp": "C3D20R, nodal forces on a set",
             "achteld": "C3D20R, prescribed displacements"}
RI, RO, LENGTH, E, NU, P = 600.0, 715.0, 200.0, 40000.0, 0.2, 1.0

passed = failed = 0


def ok(name):
    global passed
    passed += 1
    print(f"  ok   {name}")


def bad(name):
    global failed
    failed += 1
    print(f"  FAIL {name}")


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def displacements(h5path):
    """{node id: u} of the last step of a results file (ids from /mesh/node_ids, else 1..N)."""
    with h5py.File(h5path) as f:
        ids = f["mesh/node_ids"][()] if "node_ids" in f["mesh"] else np.arange(1, f["mesh/coordinates"].shape[0] + 1)
        last = sorted(f["steps"], key=int)[-1]
        u = f[f"steps/{last}/displacement"][()]
        coords = f["mesh/coordinates"][()]
    return dict(zip(ids.tolist(), u)), dict(zip(ids.tolist(), coords))


# ------------------------------------------------------------------------------------------------

def gmsh_pipe(path, kind, version):
    """The quarter pipe of the docstring: tet10 from gmsh's tetrahedra, hex20 from a transfinite
    quadrilateral section extruded in layers; physical groups inner, outer, x0, y0, ends, pipe."""
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    geo = gmsh.model.geo
    c = geo.addPoint(0, 0, 0)
    p1, p2, p3, p4 = (geo.addPoint(*xyz) for xyz in ((RI, 0, 0), (RO, 0, 0), (0, RO, 0), (0, RI, 0)))
    l1, a_out, l2, a_in = geo.addLine(p1, p2), geo.addCircleArc(p2, c, p3), geo.addLine(p3, p4), \
        geo.addCircleArc(p4, c, p1)
    s = geo.addPlaneSurface([geo.addCurveLoop([l1, a_out, l2, a_in])])
    if kind == "hex20":
        for line in (l1, l2):
            geo.mesh.setTransfiniteCurve(line, 4)
        for arc in (a_out, a_in):
            geo.mesh.setTransfiniteCurve(arc, 10)
        geo.mesh.setTransfiniteSurface(s)
        geo.mesh.setRecombine(2, s)
        out = geo.extrude([(2, s)], 0, 0, LENGTH, [3], recombine=True)
    else:
        gmsh.option.setNumber("Mesh.MeshSizeMax", 50.0)
        out = geo.extrude([(2, s)], 0, 0, LENGTH)
    geo.synchronize()
    top, vol, s_y0, s_out, s_x0, s_in = [t for _, t in out]      # extrude's order: top, volume, sides
    for name, dim, tags in (("inner", 2, [s_in]), ("outer", 2, [s_out]), ("x0", 2, [s_x0]),
                            ("y0", 2, [s_y0]), ("ends", 2, [s, top]), ("pipe", 3, [vol])):
        gmsh.model.setPhysicalName(dim, gmsh.model.addPhysicalGroup(dim, tags), name)
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.write(path)
    gmsh.finalize()


def lame_radial(r):
    """Plane-strain radial displacement of the pipe under internal pressure P."""
    a = P * RI ** 2 / (E * (RO ** 2 - RI ** 2))
    return a * ((1 + NU) * (1 - 2 * NU) * r + (1 + NU) * RO ** 2 / r)


def check_gmsh(feps, tmp):
    # The error is the mesh's: halving the element size takes it from 8.7e-5 to 1.8e-5 (tet10)
    # and from 1.25e-4 to 1.6e-5 (hex20, 3 x 9 x 3 elements), measured 2026-11-27; the
    # tolerance is twice the coarse meshes' error.
    for kind, version, tol in (("tet10", 4.1, 2e-4), ("hex20", 2.2, 2.5e-4)):
        msh, deck, h5 = (os.path.join(tmp, f"pipe_{kind}{ext}") for ext in (".msh", ".dat", ".h5"))
        gmsh_pipe(msh, kind, version)
        r = run([sys.executable, os.path.join(ROOT, "scripts/import_mesh.py"), msh, "-o", deck,
                 "--elastic", f"{E},{NU}", "--feps", feps])
        if r.returncode != 0:
            bad(f"import of a gmsh {kind} pipe (msh {version}): {r.stderr.strip()}")
            continue
        with open(deck, "a") as fh:
            fh.write("FIX, x0, X\nFIX, y0, Y\nFIX, ends, Z\nPRESSURE, inner, VALUE=1.\n")
        r = run([feps, deck, "--output", h5, "--quiet"])
        if r.returncode != 0:
            bad(f"feps on the imported {kind} pipe: {r.stderr.strip()[:300]}")
            continue
        u, x = displacements(h5)
        worst = 0.0
        for n, un in u.items():
            radius = math.hypot(x[n][0], x[n][1])
            ur = (un[0] * x[n][0] + un[1] * x[n][1]) / radius
            worst = max(worst, abs(ur - lame_radial(radius)) / lame_radial(RO))
        (ok if worst <= tol else bad)(f"gmsh {kind} pipe (msh {version}) against Lame: largest radial "
                                      f"error {worst:.1e} of u_r(R), tolerance {tol:g}, {len(u)} nodes")


# ------------------------------------------------------------------------------------------------

def example_file(name, ext):
    for path in (os.path.join(EXAMPLES, name + ext), os.path.join(EXAMPLES, name + ext + ".gz")):
        if os.path.isfile(path):
            return path
    return None


def ccx_displacements(path):
    """{node: (ux, uy, uz)} of the first displacement block of a CalculiX .dat."""
    opener = gzip.open if path.endswith(".gz") else open
    out, inside = {}, False
    with opener(path, "rt") as fh:
        for line in fh:
            if line.strip().startswith("displacements"):
                if out:
                    break
                inside = True
                continue
            if inside:
                parts = line.split()
                if len(parts) == 4:
                    out[int(parts[0])] = tuple(float(v) for v in parts[1:])
                elif out:
                    break
    return out


def check_calculix(feps, tmp):
    if not os.path.isdir(EXAMPLES):
        bad(f"no CalculiX test examples in {EXAMPLES} (scripts/setup.sh installs calculix-ccx-test)")
        return
    for name, what in CCX_CASES.items():
        inp, ref = example_file(name, ".inp"), example_file(name, ".dat.ref")
        deck, h5 = os.path.join(tmp, name + ".dat"), os.path.join(tmp, name + ".h5")
        r = run([sys.executable, os.path.join(ROOT, "scripts/import_mesh.py"), inp, "-o", deck, "--feps", feps])
        if r.returncode != 0:
            bad(f"CalculiX {name} ({what}): import: {r.stderr.strip()}")
            continue
        r = run([feps, deck, "--output", h5, "--quiet"])
        if r.returncode != 0:
            bad(f"CalculiX {name} ({what}): feps: {r.stderr.strip()[:300]}")
            continue
        u, _ = displacements(h5)
        expected = ccx_displacements(ref)
        scale = max(max(abs(v) for v in vals) for vals in expected.values())
        worst = 0.0
        for node, vals in expected.items():
            for got, want in zip(u[node], vals):
                # 7 significant digits printed: half a unit of the 7th digit, and the solvers'
                # round-off (1e-10 of the largest displacement) for values printed near zero
                worst = max(worst, abs(got - want) / (5e-7 * abs(want) + 1e-10 * scale))
        (ok if worst <= 1.0 else bad)(f"CalculiX {name} ({what}): {len(expected)} nodes' displacements "
                                      f"within the 7 printed digits ({worst:.2f} of the allowance)")


# The face numbers of the CalculiX manual (its element sections; the same as Abaqus's), written
# here independently of the library: face k's corner nodes.
MANUAL_FACES = {
    "C3D8": [(1, 2, 3, 4), (5, 8, 7, 6), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 8, 4), (4, 8, 5, 1)],
    "C3D4": [(1, 2, 3), (1, 4, 2), (2, 4, 3), (3, 4, 1)],
    "C3D6": [(1, 2, 3), (4, 5, 6), (1, 2, 5, 4), (2, 3, 6, 5), (3, 1, 4, 6)],
}
MANUAL_FACES.update({"C3D20": MANUAL_FACES["C3D8"], "C3D20R": MANUAL_FACES["C3D8"],
                     "C3D10": MANUAL_FACES["C3D4"], "C3D15": MANUAL_FACES["C3D6"]})


def check_catalog(feps):
    import json
    table = {t["abaqus"]: t for t in json.loads(run([feps, "elements"]).stdout) if t["abaqus"]}
    for name, faces in MANUAL_FACES.items():
        got = table.get(name, {}).get("faces", [])
        same = len(got) == len(faces) and all(set(g[:len(f)]) == set(f) for g, f in zip(got, faces))
        (ok if same else bad)(f"feps elements: {name} is {table.get(name, {}).get('name')}, its faces "
                              "numbered as the CalculiX manual's S1..S6" + ("" if same else f": {got}"))


def check_refusals(feps, tmp):
    cases = {
        "an untranslated keyword": ("*NODE\n1,0,0,0\n*AMPLITUDE,NAME=A\n0,0\n", ".inp", ":3: *AMPLITUDE is not translated"),
        "an element type feps does not have": ("*NODE\n1,0,0,0\n*ELEMENT,TYPE=C3D8R\n1,1,1,1,1,1,1,1,1\n",
                                               ".inp", ":3: *ELEMENT, TYPE=C3D8R: no feps element"),
        "a node set not defined": ("*NODE\n1,0,0,0\n*STEP\n*BOUNDARY\nLEFT,1,3\n", ".inp",
                                   ":5: LEFT is no node number and no node set"),
        "a second step": ("*NODE\n1,0,0,0\n*STEP\n*STATIC\n*END STEP\n*STEP\n", ".inp", ":6: a second *STEP"),
        "neither .msh nor .inp": ("x", ".txt", "not a .msh or an .inp"),
    }
    for what, (text, ext, pattern) in cases.items():
        src, deck = os.path.join(tmp, "bad" + ext), os.path.join(tmp, "bad.dat")
        with open(src, "w") as fh:
            fh.write(text)
        r = run([sys.executable, os.path.join(ROOT, "scripts/import_mesh.py"), src, "-o", deck, "--feps", feps])
        lines = r.stderr.strip().splitlines()
        (ok if r.returncode == 2 and len(lines) == 1 and pattern in lines[0] and not os.path.exists(deck)
         else bad)(f"import_mesh.py refuses {what}: exit {r.returncode}, one line, no deck"
                   + ("" if r.returncode == 2 else f": {r.stderr.strip()[:200]}"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--feps", default=os.environ.get("FEPS", ""), help="the feps executable")
    args = ap.parse_args()
    feps = feps_option(args.feps, "debug")
    check_catalog(feps)
    with tempfile.TemporaryDirectory() as tmp:
        check_gmsh(feps, tmp)
        check_calculix(feps, tmp)
        check_refusals(feps, tmp)
    print(f"check_import: {passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
