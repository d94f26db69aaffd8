#!/usr/bin/env python3
"""A mesh, or a linear-static model, made by another program, written as a feps deck.

    python3 scripts/import_mesh.py MESH -o DECK.dat [--elastic E,NU] [--material GROUP=E,NU ...]
                                  [--feps PATH]

MESH is a gmsh mesh (.msh, formats 2 and 4, read through meshio) or an Abaqus/CalculiX input
(.inp). The deck holds the mesh as explicit tables (NODES, ELEMENTS) with the source's node and
element numbers, its sets as lists (NSET, ELSET, FSET ..., LIST), and:

- from a .msh: one GROUP per physical volume (3D; physical surface for a plane mesh) and element
  type, a node set for every physical group and, for a physical surface (line) on the boundary
  of the volume (surface), a face set of the element faces it covers. A .msh carries no
  material: --elastic E,NU gives every group one, --material GROUP=E,NU one group its own.
  gmsh numbers are kept where meshio keeps them: its nodes are numbered 1..N in the file's
  order and its elements 1..M in the order of their blocks (gmsh's own default numbering).
- from a .inp: *NODE, *ELEMENT, *NSET, *ELSET (GENERATE too), *SURFACE (TYPE=ELEMENT faces,
  TYPE=NODE), *MATERIAL with an isotropic *ELASTIC, *SOLID SECTION, *BOUNDARY, *CLOAD,
  *DLOAD (P1..P6 pressures), one *STEP with *STATIC, and the output requests (*NODE PRINT,
  *EL PRINT, *NODE FILE, *EL FILE), which feps's results file replaces. The deck runs as is.
  Anything else is one line naming the file, the line and the keyword, exit status 2: feps
  would not compute what the source asks for.

Element types, node orders and face numbers come from the library (`feps elements`, the
element catalog), never from a table of this script's own; CalculiX's C3D8 is feps's hex8
(2x2x2 Gauss), C3D20R hex20r, C3D10 tet10, C3D4 tet4, C3D6 wedge6, C3D15 wedge15, CPE6 tri6.
The .inp is read by this script, not by meshio: meshio's Abaqus reader renumbers nodes and
elements, reads only the last *NODE block and folds C3D20R into C3D20.

Exit status: 0 written; 2 a bad argument or a source feps cannot take as it is (one line).
"""
import argparse
import gzip
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from feps_cli import Error, feps_option, guard  # noqa: E402

IGNORED_INP = {"HEADING", "NODE PRINT", "EL PRINT", "NODE FILE", "EL FILE", "END STEP"}
PER_LINE = 12       # ids per line in the deck's set lists


# ------------------------------------------------------------------------------------------------
# The library's element catalog

class Catalog:
    """`feps elements`: feps type by Abaqus or meshio name, and each type's faces and nodes."""

    def __init__(self, feps):
        run = subprocess.run([feps, "elements"], capture_output=True, text=True)
        if run.returncode != 0:
            raise Error(f"feps elements failed: {run.stderr.strip()}")
        self.types = {t["name"]: t for t in json.loads(run.stdout)}
        self.by_abaqus = {t["abaqus"]: t["name"] for t in self.types.values() if t["abaqus"]}
        self.by_meshio = {t["meshio"]: t["name"] for t in self.types.values() if t["meshio"]}

    def face_corners(self, name):
        """{frozenset of a face's corner nodes (local, 0-based): face number} of a solid type."""
        out = {}
        for k, face in enumerate(self.types[name]["faces"], start=1):
            ncorner = {2: 2, 3: 3, 4: 4, 6: 3, 8: 4}[len(face)] if self.types[name]["dimension"] == 3 \
                else 2
            out[k] = [n - 1 for n in face[:ncorner]]
        return out


# ------------------------------------------------------------------------------------------------
# The deck

class Deck:
    """What the deck will hold: nodes, groups of elements, sets, materials, supports and loads."""

    def __init__(self, source):
        self.source = source
        self.title = f"imported from {os.path.basename(source)}"
        self.nodes = {}                 # id -> (x, y, z)
        self.groups = []                # (name, feps type, material, [(id, [node ids])])
        self.elements = {}              # id -> (feps type, [node ids])
        self.node_sets = {}             # name -> [ids]
        self.element_sets = {}          # name -> [ids] (the source's, to resolve its references)
        self.face_sets = {}             # name -> [(element id, face)]
        self.materials = {}             # name -> (E, nu)
        self.fixes = []                 # (set, [dof names])
        self.displacements = []         # (node, dof, value)
        self.forces = []                # (node, dof, value)
        self.pressures = []             # (face set, value)

    def write(self, path):
        lines = [f"TITLE, {self.title}", f"! written by scripts/import_mesh.py from {self.source}", "NODES"]
        lines += [f"{n}, {x!r}, {y!r}, {z!r}" for n, (x, y, z) in sorted(self.nodes.items())]
        for name, (e, nu) in self.materials.items():
            lines.append(f"MATERIAL, {name}, ELASTIC, E={e!r}, NU={nu!r}")
        for name, etype, material, members in self.groups:
            lines += [f"GROUP, {name}, TYPE={etype}, MATERIAL={material}", f"ELEMENTS, {name}"]
            lines += [", ".join(str(v) for v in [eid] + conn) for eid, conn in members]
        for name, ids in self.node_sets.items():
            lines.append(f"NSET, {name}, LIST")
            ids = sorted(set(ids))
            lines += [", ".join(map(str, ids[i:i + PER_LINE])) for i in range(0, len(ids), PER_LINE)]
        group_of = {eid: name for name, _, _, members in self.groups for eid, _ in members}
        pressures = []
        for name, faces in self.face_sets.items():
            # a feps face set lies in one group: a set over several becomes one per group
            by_group = {}
            for e, k in sorted(set(faces)):
                by_group.setdefault(group_of[e], []).append((e, k))
            parts = {g: (name if len(by_group) == 1 else f"{name}_{g}") for g in by_group}
            for g, rows in by_group.items():
                lines.append(f"FSET, {parts[g]}, LIST, GROUP={g}")
                lines += [f"{e}, {k}" for e, k in rows]
            pressures += [(parts[g], v) for n, v in self.pressures if n == name for g in by_group]
        for name, dofs in self.fixes:
            lines.append(f"FIX, {name}, " + ", ".join(dofs))
        for keyword, rows in (("DISPLACE", self.displacements), ("FORCE", self.forces)):
            if rows:
                lines.append(f"{keyword}, LIST")
                lines += [f"{n}, {d}, {v!r}" for n, d, v in rows]
        for name, value in pressures:
            lines.append(f"PRESSURE, {name}, VALUE={value!r}")
        with open(path, "w") as fh:
            fh.write("\n".join(lines) + "\n")


def deck_name(text):
    """A set, group or material name feps takes: the source's, with anything else than letters,
    digits, '_', '-' and '.' made '_'."""
    return re.sub(r"[^A-Za-z0-9_.-]", "_", text.strip()) or "unnamed"


# ------------------------------------------------------------------------------------------------
# gmsh (.msh) through meshio

def read_msh(path, catalog, elastic, materials):
    import meshio
    try:
        mesh = meshio.read(path, file_format="gmsh")
    except Exception as exc:                      # meshio raises many kinds; its message names the fault
        raise Error(f"{path}: meshio cannot read it as a gmsh mesh: {exc}", 2) from None
    deck = Deck(path)
    points = mesh.points if mesh.points.shape[1] == 3 else \
        [(p[0], p[1], 0.0) for p in mesh.points]
    deck.nodes = {i + 1: tuple(float(c) for c in p) for i, p in enumerate(points)}
    names = {int(tag): name for name, (tag, dim) in
             ((n, (int(v[0]), int(v[1]))) for n, v in mesh.field_data.items())}
    dims = {int(v[0]): int(v[1]) for v in mesh.field_data.values()}
    physical = mesh.cell_data.get("gmsh:physical")
    solid_dim = 3 if any(catalog.types.get(catalog.by_meshio.get(b.type, ""), {}).get("dimension") == 3
                         for b in mesh.cells) else 2
    face_index = {}
    next_id = 1
    groups = {}
    for i, block in enumerate(mesh.cells):
        etype = catalog.by_meshio.get(block.type)
        tags = physical[i] if physical is not None else [0] * len(block.data)
        if etype is None or catalog.types[etype]["dimension"] != solid_dim:
            continue
        corners = catalog.face_corners(etype)
        for conn, tag in zip(block.data, tags):
            eid, nodes = next_id, [int(n) + 1 for n in conn]
            next_id += 1
            group = names.get(int(tag), f"volume{int(tag)}" if physical is not None else "all")
            groups.setdefault((deck_name(group), etype), []).append((eid, nodes))
            for k, local in corners.items():
                face_index[frozenset(nodes[j] for j in local)] = (eid, k)
    if not groups:
        raise Error(f"{path}: no {solid_dim}D cells of a type feps knows "
                    f"(meshio types: {', '.join(sorted(catalog.by_meshio))})", 2)
    for (group, etype), members in groups.items():
        name = group if sum(g == group for g, _ in groups) == 1 else f"{group}_{etype}"
        material = material_for(group, elastic, materials)
        deck.materials[f"{name}_material"] = material
        deck.groups.append((name, etype, f"{name}_material", members))
    unused = set(materials) - {g for g, _ in groups}
    if unused:
        raise Error(f"--material {sorted(unused)[0]}: no such group (groups: "
                    f"{', '.join(sorted({g for g, _ in groups}))})", 2)
    # every physical group: its nodes; one of the boundary's dimension: also its faces
    for i, block in enumerate(mesh.cells):
        if physical is None:
            break
        for conn, tag in zip(block.data, physical[i]):
            name = deck_name(names.get(int(tag), f"physical{int(tag)}"))
            deck.node_sets.setdefault(name, []).extend(int(n) + 1 for n in conn)
            if dims.get(int(tag)) == solid_dim - 1:
                ncorner = 2 if solid_dim == 2 else (3 if block.type.startswith("triangle") else 4)
                face = face_index.get(frozenset(int(n) + 1 for n in conn[:ncorner]))
                if face is None:
                    raise Error(f"{path}: physical group {name}: a cell ({block.type}, nodes "
                                f"{[int(n) + 1 for n in conn]}) is no face of any element", 2)
                deck.face_sets.setdefault(name, []).append(face)
    return deck


def material_for(group, elastic, materials):
    if group in materials:
        return materials[group]
    if elastic is None:
        raise Error(f"group {group} has no material: give --elastic E,NU (every group) or "
                    f"--material {group}=E,NU (a .msh carries no material)", 2)
    return elastic


# ------------------------------------------------------------------------------------------------
# Abaqus / CalculiX (.inp)

class InpReader:
    """The keyword blocks of an .inp (with *INCLUDE), each as (file, line, keyword, params, data
    lines as [(line, fields)])."""

    def __init__(self, path):
        self.blocks = []
        self._read(path)

    def _read(self, path):
        opener = gzip.open if path.endswith(".gz") else open
        try:
            with opener(path, "rt", errors="replace") as fh:
                lines = fh.read().splitlines()
        except OSError as exc:
            raise Error(f"{path}: {exc.strerror}", 2) from None
        for number, raw in enumerate(lines, start=1):
            line = raw.strip()
            if not line or line.startswith("**"):
                continue
            if line.startswith("*"):
                parts = [p.strip() for p in line[1:].split(",")]
                keyword = " ".join(parts[0].upper().split())
                params = {}
                for p in parts[1:]:
                    if p:
                        key, _, value = p.partition("=")
                        params[key.strip().upper()] = value.strip()
                if keyword == "INCLUDE":
                    target = params.get("INPUT", "")
                    self._read(target if os.path.isabs(target) else
                               os.path.join(os.path.dirname(path), target))
                    continue
                self.blocks.append((path, number, keyword, params, []))
            elif self.blocks:
                self.blocks[-1][4].append((number, [f.strip() for f in line.split(",") if f.strip()]))
            else:
                raise Error(f"{path}:{number}: data before the first keyword", 2)


def read_inp(path, catalog):
    deck = Deck(path)
    reader = InpReader(path)
    steps = 0
    sections = []
    material = None
    for file, line, keyword, params, data in reader.blocks:
        where = f"{file}:{line}"

        def number(text, what, row=line):
            try:
                return float(text.replace("d", "e").replace("D", "E"))
            except ValueError:
                raise Error(f"{file}:{row}: *{keyword}: {what} is not a number: {text!r}", 2) from None

        def integer(text, what, row=line):
            try:
                return int(text)
            except ValueError:
                raise Error(f"{file}:{row}: *{keyword}: {what} is not a whole number: {text!r}", 2) from None

        if keyword in IGNORED_INP:
            if keyword == "HEADING" and data:
                deck.title = ", ".join(data[0][1])[:200] or deck.title
            continue
        if keyword == "NODE":
            system = params.get("SYSTEM", "R").upper()
            if system != "R":
                raise Error(f"{where}: *NODE, SYSTEM={system} is not translated (Cartesian nodes only)", 2)
            ids = []
            for row, fields in data:
                n = integer(fields[0], "the node number", row)
                xyz = [number(f, "a coordinate", row) for f in fields[1:4]] + [0.0] * (4 - len(fields))
                deck.nodes[n] = tuple(xyz[:3])
                ids.append(n)
            if "NSET" in params:
                deck.node_sets.setdefault(deck_name(params["NSET"]), []).extend(ids)
        elif keyword == "ELEMENT":
            source_type = params.get("TYPE", "").upper()
            etype = catalog.by_abaqus.get(source_type)
            if etype is None:
                raise Error(f"{where}: *ELEMENT, TYPE={source_type}: no feps element is this element "
                            f"(feps takes {', '.join(sorted(catalog.by_abaqus))})", 2)
            nnodes = catalog.types[etype]["nodes"]
            values = [v for _, fields in data for v in fields]
            rows = [data[0][0]] if data else [line]
            if len(values) % (nnodes + 1):
                raise Error(f"{where}: *ELEMENT, TYPE={source_type}: {len(values)} numbers do not make "
                            f"rows of an element number and {nnodes} nodes", 2)
            ids = []
            for i in range(0, len(values), nnodes + 1):
                eid = integer(values[i], "the element number", rows[0])
                deck.elements[eid] = (etype, [integer(v, "a node number", rows[0]) for v in values[i + 1:i + 1 + nnodes]])
                ids.append(eid)
            if "ELSET" in params:
                deck.element_sets.setdefault(deck_name(params["ELSET"]), []).extend(ids)
        elif keyword in ("NSET", "ELSET"):
            name = deck_name(params.get(keyword, ""))
            target = deck.node_sets if keyword == "NSET" else deck.element_sets
            members = target.setdefault(name, [])
            for row, fields in data:
                if "GENERATE" in params:
                    a, b, step = ([integer(f, "GENERATE's range", row) for f in fields] + [1])[:3]
                    members.extend(range(a, b + 1, step))
                    continue
                for f in fields:
                    if re.fullmatch(r"[+-]?\d+", f):
                        members.append(int(f))
                    elif deck_name(f) in target:
                        members.extend(target[deck_name(f)])
                    else:
                        raise Error(f"{file}:{row}: *{keyword}, {keyword}={name}: {f} is no number "
                                    f"and no {keyword.lower()} defined before", 2)
        elif keyword == "SURFACE":
            name = deck_name(params.get("NAME", ""))
            if params.get("TYPE", "ELEMENT").upper() == "NODE":
                for row, fields in data:
                    deck.node_sets.setdefault(name, []).extend(set_or_node(deck, fields[0], file, row))
                continue
            faces = deck.face_sets.setdefault(name, [])
            for row, fields in data:
                k = face_number(fields[1] if len(fields) > 1 else "", "S", file, row, keyword)
                faces.extend((e, k) for e in set_or_element(deck, fields[0], file, row))
        elif keyword == "MATERIAL":
            material = deck_name(params.get("NAME", ""))
        elif keyword == "ELASTIC":
            if params.get("TYPE", "ISO").upper() not in ("ISO", "ISOTROPIC"):
                raise Error(f"{where}: *ELASTIC, TYPE={params['TYPE']} is not translated (isotropic only)", 2)
            if material is None or len(data) != 1 or len(data[0][1]) != 2:
                raise Error(f"{where}: *ELASTIC: one line E, nu after a *MATERIAL is translated "
                            "(no temperature table)", 2)
            deck.materials[material] = (number(data[0][1][0], "E", data[0][0]),
                                        number(data[0][1][1], "nu", data[0][0]))
        elif keyword == "SOLID SECTION":
            sections.append((where, deck_name(params.get("ELSET", "")), deck_name(params.get("MATERIAL", ""))))
        elif keyword == "STEP":
            steps += 1
            if steps > 1:
                raise Error(f"{where}: a second *STEP is not translated (one linear-static step)", 2)
            if params.get("NLGEOM", "NO").upper() not in ("NO", ""):
                raise Error(f"{where}: *STEP, NLGEOM is not translated (feps is geometrically linear)", 2)
        elif keyword == "STATIC":
            continue    # its increments do not matter to a linear step
        elif keyword == "BOUNDARY":
            for row, fields in data:
                first = integer(fields[1], "the first DOF", row)
                last = integer(fields[2], "the last DOF", row) if len(fields) > 2 and fields[2] else first
                value = number(fields[3], "the value", row) if len(fields) > 3 else 0.0
                if not 1 <= first <= last <= 3:
                    raise Error(f"{file}:{row}: *BOUNDARY: DOFs {first}..{last}: feps nodes have DOFs 1-3", 2)
                dofs = ["XYZ"[d - 1] for d in range(first, last + 1)]
                if value == 0.0 and not re.fullmatch(r"[+-]?\d+", fields[0]):
                    set_or_node(deck, fields[0], file, row)       # a set it knows
                    deck.fixes.append((deck_name(fields[0]), dofs))
                else:
                    deck.displacements += [(n, d, value) for n in set_or_node(deck, fields[0], file, row)
                                           for d in dofs]
        elif keyword == "CLOAD":
            for row, fields in data:
                dof = integer(fields[1], "the DOF", row)
                if not 1 <= dof <= 3:
                    raise Error(f"{file}:{row}: *CLOAD: DOF {dof}: feps nodes have DOFs 1-3", 2)
                value = number(fields[2], "the magnitude", row)
                deck.forces += [(n, "XYZ"[dof - 1], value) for n in set_or_node(deck, fields[0], file, row)]
        elif keyword == "DLOAD":
            for row, fields in data:
                k = face_number(fields[1], "P", file, row, keyword)
                name = f"dload_{row}"
                deck.face_sets[name] = [(e, k) for e in set_or_element(deck, fields[0], file, row)]
                deck.pressures.append((name, number(fields[2], "the magnitude", row)))
        else:
            raise Error(f"{where}: *{keyword} is not translated (feps takes a linear-static model: "
                        "see scripts/import_mesh.py --help)", 2)
    if steps == 0:
        raise Error(f"{path}: no *STEP (a model without a step asks nothing to be computed)", 2)
    assign_sections(deck, sections)
    return deck


def set_or_node(deck, text, file, row):
    if re.fullmatch(r"[+-]?\d+", text):
        return [int(text)]
    if deck_name(text) not in deck.node_sets:
        raise Error(f"{file}:{row}: {text} is no node number and no node set defined before", 2)
    return sorted(set(deck.node_sets[deck_name(text)]))


def set_or_element(deck, text, file, row):
    if re.fullmatch(r"[+-]?\d+", text):
        return [int(text)]
    if deck_name(text) not in deck.element_sets:
        raise Error(f"{file}:{row}: {text} is no element number and no element set defined before", 2)
    return sorted(set(deck.element_sets[deck_name(text)]))


def face_number(text, letter, file, row, keyword):
    m = re.fullmatch(letter + r"(\d)", text.strip().upper())
    if not m:
        raise Error(f"{file}:{row}: *{keyword}: {text!r}: only faces {letter}1..{letter}6 are translated", 2)
    return int(m.group(1))


def assign_sections(deck, sections):
    """One GROUP per *SOLID SECTION and element type; every element must be in one."""
    taken = {}
    for where, elset, material in sections:
        if elset not in deck.element_sets:
            raise Error(f"{where}: *SOLID SECTION, ELSET={elset}: no such element set", 2)
        if material not in deck.materials:
            raise Error(f"{where}: *SOLID SECTION, MATERIAL={material}: no such material", 2)
        by_type = {}
        for eid in sorted(set(deck.element_sets[elset])):
            if eid in taken:
                raise Error(f"{where}: element {eid} has a section already ({taken[eid]})", 2)
            taken[eid] = where
            by_type.setdefault(deck.elements[eid][0], []).append((eid, deck.elements[eid][1]))
        for etype, members in by_type.items():
            name = elset if len(by_type) == 1 else f"{elset}_{etype}"
            deck.groups.append((name, etype, material, members))
    missing = sorted(set(deck.elements) - set(taken))
    if missing:
        raise Error(f"{deck.source}: element {missing[0]} (and {len(missing) - 1} more) has no "
                    "*SOLID SECTION", 2)


# ------------------------------------------------------------------------------------------------

def elastic_pair(text):
    try:
        e, nu = (float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not E,NU") from None
    return e, nu


def material_option(text):
    group, _, pair = text.partition("=")
    if not group or not pair:
        raise argparse.ArgumentTypeError(f"{text!r} is not GROUP=E,NU")
    return deck_name(group), elastic_pair(pair)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("mesh", help="the source: a gmsh .msh or an Abaqus/CalculiX .inp (.inp.gz too)")
    ap.add_argument("-o", "--output", required=True, help="the deck to write")
    ap.add_argument("--elastic", type=elastic_pair, help="E,NU of every group of a .msh")
    ap.add_argument("--material", type=material_option, action="append", default=[],
                    help="GROUP=E,NU: one group's material (a .msh), repeatable")
    ap.add_argument("--feps", default="", help="feps executable (default: $FEPS, else fpm's debug build)")
    args = ap.parse_args(argv)
    if not os.path.isfile(args.mesh):
        raise Error(f"{args.mesh}: no such file", 2)
    catalog = Catalog(feps_option(args.feps or os.environ.get("FEPS", ""), "debug"))
    lower = args.mesh.lower()
    if lower.endswith(".msh"):
        deck = read_msh(args.mesh, catalog, args.elastic, dict(args.material))
    elif lower.endswith(".inp") or lower.endswith(".inp.gz"):
        if args.elastic or args.material:
            raise Error("--elastic and --material are for a .msh: an .inp names its own materials", 2)
        deck = read_inp(args.mesh, catalog)
    else:
        raise Error(f"{args.mesh}: not a .msh or an .inp", 2)
    deck.write(args.output)
    print(f"wrote {args.output}: {len(deck.nodes)} nodes, "
          f"{sum(len(g[3]) for g in deck.groups)} elements in {len(deck.groups)} groups")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
