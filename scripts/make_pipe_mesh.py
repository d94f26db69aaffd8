#!/usr/bin/env python3
"""Write a feps deck of a model-B-like half pipe in soil (hex8), for benchmarks.

Same geometry, materials, supports and edge load as model B, case SE1 (pipe and soil bonded,
no interface elements): r_i = 600, r_o = 715,
soil to r = 2000, length 2500, theta 0..180 deg, symmetry plane y = 0, but with uniform
spacing: --pipe-layers and --soil-layers elements in r, --ntheta in theta, --nz in z.
The deck is written with DATAIN blocks, so it stays a few dozen lines at any size.

  python3 scripts/make_pipe_mesh.py --ntheta 72 --nz 100 --pipe-layers 4 --soil-layers 4 -o b200k.dat
  python3 scripts/make_pipe_mesh.py --preset 1m -o b1m.dat

Prints the node, element and DOF counts (all DOFs and the free ones feps reports) on stdout.
"""
import argparse
import sys

R_INNER, R_OUTER, R_SOIL, LENGTH = 600.0, 715.0, 2000.0, 2500.0

# name: (pipe layers, soil layers, ntheta, nz). 200k is the mesh (4 + 4 layers,
# 72 x 100); the smaller ones keep its 8 radial layers and coarsen theta and z; the 1M and
# larger ones also refine the soil radially (its 4-layer elements are 320 mm deep), which
# keeps the elements' shape but makes the factor grow faster than with theta and z alone.
PRESETS = {
    "10k": (4, 4, 18, 20),
    "50k": (4, 4, 36, 50),
    "200k": (4, 4, 72, 100),
    "1m": (8, 8, 124, 164),
    "1.1m": (8, 8, 130, 172),
    "1.2m": (8, 8, 136, 180),
}


def counts(pipe_layers, soil_layers, ntheta, nz):
    """Nodes, elements, all DOFs and free DOFs (after the supports of write_deck)."""
    nr = pipe_layers + soil_layers + 1
    nt, nzn = ntheta + 1, nz + 1
    nodes = nr * nt * nzn
    elements = (pipe_layers + soil_layers) * ntheta * nz
    outer = nt * nzn                   # r = 2000: x and y held
    symmetry = 2 * nr * nzn - 2 * nzn  # theta = 0, 180: y held (outer nodes counted above)
    free = 3 * nodes - 2 * outer - symmetry - 1  # - 1: the anchor's z
    return nodes, elements, 3 * nodes, free


def write_deck(out, pipe_layers, soil_layers, ntheta, nz, solver):
    nr = pipe_layers + soil_layers + 1
    plane = nr * (ntheta + 1)         # nodes in one z plane
    dr_pipe = (R_OUTER - R_INNER) / pipe_layers
    dr_soil = (R_SOIL - R_OUTER) / soil_layers
    dtheta = 180.0 / ntheta
    dz = LENGTH / nz
    z_anchor = (nz // 2) * dz         # a node plane at (or next to) the mid-plane
    nodes, elements, _, free = counts(pipe_layers, soil_layers, ntheta, nz)
    w = out.write
    w("! feps deck written by scripts/make_pipe_mesh.py: model-B-like half pipe in soil, hex8\n")
    w(f"! {pipe_layers} pipe + {soil_layers} soil layers, {ntheta} x {nz} elements in theta and z;"
      f" {nodes} nodes, {elements} elements, {free} free DOFs\n")
    w(f"TITLE, pipe in soil {pipe_layers}+{soil_layers} x {ntheta} x {nz} hex8 ({free} DOFs)\n")
    w(f"A, 3, {R_INNER:.1f}, 0., 0.,\n")
    w(f"%, {pipe_layers + 1}, {dr_pipe!r}, 0., 0.,\n")
    w(f"%, -{soil_layers}, {dr_soil!r}, 0., 0.,\n")
    w(f"%, {ntheta + 1}, 0., {dtheta!r}, 0.,\n")
    w(f"%, {nz + 1}, 0., 0., {dz!r},\n")
    w("E,\n")
    for name, first, layers in (("pipe", 1, pipe_layers), ("soil", pipe_layers + 1, soil_layers)):
        n1, n2 = first, first + 1
        base = [n1, n2, n2 + nr, n1 + nr]
        conn = base + [n + plane for n in base]
        w(f"GROUP, {name}, TYPE=hex8, MATERIAL={'concrete' if name == 'pipe' else 'soil'}\n")
        w("A, 8, " + ", ".join(str(n) for n in conn) + ",\n")
        w(f"%, {layers}, *, 8, 1,\n")
        w(f"%, {ntheta}, *, 8, {nr},\n")
        w(f"%, {nz}, *, 8, {plane},\n")
        w("E,\n")
    w("E,\n")
    w("MATERIAL, concrete, ELASTIC, E=40000., NU=0.2\n")
    w("MATERIAL, soil, ELASTIC, E=144., NU=0.2\n")
    w(f"NSET, soil_outer, CSYS=3, R={R_SOIL:.1f}, TOL=0.01\n")
    w("NSET, symmetry, CSYS=2, Y=0., TOL=0.01\n")
    w(f"NSET, anchor, CSYS=3, R={R_SOIL:.1f}, THETA=0., Z={z_anchor!r}, TOL=0.01\n")
    w("FIX, soil_outer, X, Y\n")
    w("FIX, symmetry, Y\n")
    w("FIX, anchor, Z\n")
    w("FSET, end_low, GROUP=pipe, CSYS=2, Z=0., TOL=0.01\n")
    w(f"FSET, end_high, GROUP=pipe, CSYS=2, Z={LENGTH:.1f}, TOL=0.01\n")
    w("PRESSURE, end_low, TOTAL=1.0e6, VARY=X, ZERO=-220., PEAK=-715.\n")
    w("PRESSURE, end_high, TOTAL=1.0e6, VARY=X, ZERO=-220., PEAK=-715.\n")
    if solver:
        w(f"SOLVER, {solver}\n")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--preset", choices=list(PRESETS), help="a named size (overrides the four sizes)")
    p.add_argument("--ntheta", type=int, default=72, help="elements in theta over 0..180 deg (72)")
    p.add_argument("--nz", type=int, default=100, help="elements along the pipe (100)")
    p.add_argument("--pipe-layers", type=int, default=4, help="elements through the pipe wall (4)")
    p.add_argument("--soil-layers", type=int, default=4, help="elements through the soil (4)")
    p.add_argument("--solver", choices=["cholmod", "skyline"], help="write a SOLVER record")
    p.add_argument("-o", "--output", help="deck file (default: standard output)")
    p.add_argument("--count-only", action="store_true", help="print the counts, write no deck")
    a = p.parse_args()
    sizes = PRESETS[a.preset] if a.preset else (a.pipe_layers, a.soil_layers, a.ntheta, a.nz)
    if min(sizes) < 1 or sizes[3] < 2:
        p.error("all sizes must be at least 1 (nz at least 2)")
    nodes, elements, dofs, free = counts(*sizes)
    if not a.count_only:
        if a.output:
            with open(a.output, "w") as f:
                write_deck(f, *sizes, a.solver)
        else:
            write_deck(sys.stdout, *sizes, a.solver)
    info = sys.stderr if not a.output and not a.count_only else sys.stdout
    print(f"nodes {nodes} elements {elements} dofs {dofs} free_dofs {free}", file=info)


if __name__ == "__main__":
    main()
