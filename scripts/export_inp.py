#!/usr/bin/env python3
"""Write a CalculiX (Abaqus-style) .inp of a linear feps model from feps's results file.

  python3 scripts/export_inp.py run.h5 -o model.inp

Everything comes from the HDF5 file feps wrote for the deck
(docs/output-format.md), so node and element numbers are feps's own (CalculiX node n is feps
node n) and nothing of feps's physics is computed again here:
- the mesh: /mesh/coordinates, /mesh/groups/<g>/connectivity, each group's element as the
  catalog's `abaqus_type` attribute names it (hex8 C3D8, hex20 C3D20, hex20r C3D20R, tet4
  C3D4, tet10 C3D10, wedge6 C3D6, wedge15 C3D15: the same node order; the hexahedra and
  tetrahedra integrate as CalculiX does, the wedges do not (feps 3 x 2 and 6 x 3 points, ccx 2
  and 9: docs/verification.md, "Tetrahedra and wedges"), so their results differ by that);
- the materials: /materials/<name> (kind elastic, E or G, nu);
- the loads: /steps/<last>/applied_force, the nodal forces feps applied (nodal loads and the
  consistent forces of its pressures and tractions), as *CLOAD;
- the supports: /constraints/<k> (each FIX record's set and direction, as the run read them)
  and the nodes of each set, /sets/nodes/<set>, as the run resolved them.
The deck itself is not read.

Only what a linear run with one load case needs is accepted: ELASTIC materials, 3D solid groups
whose type has an Abaqus equivalent, one stage, supports that hold in the global system.
Anything else (interfaces, bars, plane strain, hex8b, DISPLACE, RELEASE, a FIX in a cylindrical
or nodal system, several stages)
is refused, naming the deck's line where a record is the cause.
The step asks for the displacements of all nodes in the .dat file (*NODE PRINT, which
scripts/bench_calculix.sh compares with feps's node by node) and for no other output.
A model the exporter cannot translate exits with status 1; a file that is missing or cannot
be read, with status 2.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402

REFUSED = {"displace": "DISPLACE (prescribed displacements)", "release": "RELEASE (released supports)"}


class ExportError(Exception):
    pass


def fixes(h):
    """[(set name, dof 1..3)] of the run's FIX records (/constraints); ExportError naming the deck's
    line for a record the exporter cannot write."""
    fr.require(h, "constraints", " (a result of a feps that did not write its supports: run the deck again)")
    out = []
    for k in sorted(h["constraints"]):
        a = h[f"constraints/{k}"].attrs
        kind, where = fr.text(a["kind"]), fr.text(a["source"])
        if kind in REFUSED:
            raise ExportError(f"{where}: {REFUSED[kind]} is not exported")
        if int(a["csys"]) not in (1, 2):          # DATAIN's global Cartesian systems
            raise ExportError(f"{where}: FIX in a cylindrical or nodal system is not exported")
        if int(a["active_from"]) > 1:
            raise ExportError(f"{where}: a FIX of a later stage is not exported")
        out.append((fr.text(a["set"]), int(a["dof"])))
    return out


def build(h5path):
    """(coords, groups {name: (CalculiX type, material, conn)}, materials {name: (E, nu)}, fixed {node:
    dofs}, forces (nnode, 3), the deck's name)."""
    with fr.open_result(h5path) as h:
        held = fixes(h)
        deck = fr.summary(h).get("input_file", h5path)
        coords = fr.coordinates(h)
        groups, materials = {}, {}
        for name in fr.groups(h):
            group = h[f"mesh/groups/{name}"].attrs
            ccx = fr.text(group["abaqus_type"]) if "abaqus_type" in group else ""
            if not ccx or fr.text(group["family"]) != "solid" or int(group["dimension"]) != 3:
                raise ExportError(f"group {name}: element type {fr.element_type(h, name)!r} has no CalculiX "
                                  "equivalent in the exporter")
            mat = fr.text(group["material"])
            groups[name] = (ccx, mat, fr.connectivity(h, name) + 1)
            attrs = h[f"materials/{mat}"].attrs
            if fr.text(attrs["kind"]) != "elastic":
                raise ExportError(f"material {mat}: only elastic materials are exported (got {fr.text(attrs['kind'])})")
            nu = float(attrs["nu"])
            materials[mat] = (float(attrs["e"]) if "e" in attrs else 2.0 * float(attrs["g"]) * (1.0 + nu), nu)
        step = fr.last_step(h)
        if float(h[f"steps/{step}"].attrs["load_factor"]) > 1.0:
            raise ExportError(f"{h5path}: more than one stage: the exporter writes one load case")
        fr.require(h, f"steps/{step}/applied_force", " (a result of a feps that did not write the applied forces, "
                   "or FIELDS left out applied_force)")
        forces = h[f"steps/{step}/applied_force"][...]
        fixed = {}
        for name, dof in held:
            fr.require(h, f"sets/nodes/{name}", f" (the node set of FIX, {name})")
            for n in h[f"sets/nodes/{name}"][...].ravel():
                fixed.setdefault(int(n), set()).add(dof)
    return coords, groups, materials, fixed, forces, deck


def num(v):
    """Shortest text that reads back as the same double; CalculiX reads at most 20 characters
    of a number, so longer ones keep 14 significant digits."""
    text = repr(float(v))
    return text if len(text) <= 20 else f"{float(v):.13e}"


def write_inp(out, coords, groups, materials, fixed, forces, source):
    w = out.write
    w(f"** CalculiX input written by scripts/export_inp.py from {source}\n")
    w("*HEADING\n")
    w(f"feps model {source}\n")
    w("*NODE, NSET=NALL\n")
    for i, x in enumerate(coords, start=1):
        w(f"{i}, {num(x[0])}, {num(x[1])}, {num(x[2])}\n")
    first = 1
    for name, (ccx, _, conn) in groups.items():
        w(f"*ELEMENT, TYPE={ccx}, ELSET={name}\n")
        for e, row in enumerate(conn, start=first):
            nodes = [str(int(n)) for n in row]
            # At most 16 entries on a data line: C3D20 continues on a second line.
            w(", ".join([str(e)] + nodes[:15]) + ("," if len(nodes) > 15 else "") + "\n")
            if len(nodes) > 15:
                w(", ".join(nodes[15:]) + "\n")
        first += len(conn)
    for mat in dict.fromkeys(g[1] for g in groups.values()):
        e, nu = materials[mat]
        w(f"*MATERIAL, NAME={mat}\n*ELASTIC\n{num(e)}, {num(nu)}\n")
    for name, (_, mat, _) in groups.items():
        w(f"*SOLID SECTION, ELSET={name}, MATERIAL={mat}\n")
    w("*BOUNDARY\n")
    for n in sorted(fixed):
        for d in sorted(fixed[n]):
            w(f"{n}, {d}, {d}, 0.\n")
    w("*STEP\n*STATIC, SOLVER=SPOOLES\n*CLOAD\n")
    for n in range(len(forces)):
        for d in range(3):
            if forces[n, d] != 0.0:
                w(f"{n + 1}, {d + 1}, {num(forces[n, d])}\n")
    w("*NODE PRINT, NSET=NALL\nU\n*END STEP\n")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("h5", help="feps results HDF5 file of the deck")
    p.add_argument("deck", nargs="?", help="not read (the supports come from the results file); "
                   "accepted so that older command lines still work")
    p.add_argument("-o", "--output", required=True, help=".inp file to write")
    a = p.parse_args()
    if not os.path.isfile(a.h5):
        print(f"export_inp: error: no HDF5 file {a.h5}", file=sys.stderr)
        return 2
    try:
        coords, groups, materials, fixed, forces, deck = build(a.h5)
    except (ExportError, KeyError) as exc:
        print(f"export_inp: error: {exc}", file=sys.stderr)
        return 1
    except (OSError, ValueError) as exc:
        # a file that is not HDF5
        print(f"export_inp: error: cannot read {getattr(exc, 'filename', None) or a.h5}: "
              f"{getattr(exc, 'strerror', None) or exc}", file=sys.stderr)
        return 2
    try:
        with open(a.output, "w") as out:
            write_inp(out, coords, groups, materials, fixed, forces, deck)
    except OSError as exc:
        print(f"export_inp: error: cannot write {a.output}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    total = forces.sum(axis=0)
    nfix = sum(len(d) for d in fixed.values())
    print(f"export_inp: {len(coords)} nodes, {sum(len(g[2]) for g in groups.values())} elements, "
          f"{nfix} fixed DOFs, {int(np.any(forces != 0.0, axis=1).sum())} loaded nodes, resultant {total[0]:.6g} "
          f"{total[1]:.6g} {total[2]:.6g} N -> {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
