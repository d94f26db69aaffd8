#!/usr/bin/env python3
"""Write test/data/split_cylinder.dat: the split-cylinder (Brazilian) test of a concrete disk in
plane strain (issue 27 item 2), for test_concrete.

    python3 test/data/make_split_cylinder.py [-o test/data/split_cylinder.dat]

The upper half of a disk of diameter D = 150 mm (y >= 0; y = 0 a symmetry plane), tri6, loaded
by a uniform radial pressure over the arc 2 alpha at the top, b = 2 R sin(alpha) = 12 mm wide
(b / D = 0.08, ASTM C496's 1/8 in. per 1 in. of diameter is 0.083). The mesh is the square
[-1, 1] x [0, 1] mapped onto the half disk by the elliptical grid mapping
(u, v) -> R (u sqrt(1 - v^2 / 2), v sqrt(1 - u^2 / 2)), every node (mid-sides too) mapped, so the
rim is the circle; the columns are graded so that a column of nodes meets the rim at the edge of
the loaded arc (u = sqrt(2) sin alpha) and the middle column, where the crack runs, is centred on
x = 0 (one crack band, not two split by a node line). Each quad is two tri6.
Supports: uy = 0 on y = 0; ux = 0 at one node (x = -R, y = 0), which only removes the rigid
motion (the loads are symmetric about x = 0). Concrete: CONCRETE, E = 30000, nu = 0.2,
FT = 3, GF = 0.1 N/mm, linear softening, compression elastic. The pressure rises in 100 steps to
the pressure at which Hondros's closed form puts FT at the centre (step k: k / 100 of it), and a second stage takes it to 1.0005 times that, so the first crack can be checked against the closed form (test/cli/check_split_cylinder.py).
The peak is not followed: past the first crack, displacement control of the crown or of the middle
column's opening and arc length all stall or stop (docs/verification.md, "The split-cylinder test").
"""
import argparse
import math
import os

R = 75.0
B = 12.0                                   # loaded width (mm)
ALPHA = math.asin(B / 2.0 / R)
U_EDGE = math.sqrt(2.0) * math.sin(ALPHA)  # the column that meets the rim at the arc's edge
ROWS = 14
OUTER = 12                                 # columns on each side beyond the loaded arc
FT = 3.0
# Hondros (1959): a radial pressure p over the arcs 2 alpha at both ends of a diameter puts
# sigma_x = 2 p (sin 2 alpha - alpha) / pi at the centre, so the centre reaches FT at
P_CRACK = math.pi * FT / (2.0 * (math.sin(2.0 * ALPHA) - ALPHA))
STEPS = 100                                # step k carries k / 100 of P_CRACK


def columns():
    """Node u-coordinates (corner nodes), symmetric about 0, middle column centred."""
    inner = [-U_EDGE, -U_EDGE / 3.0, U_EDGE / 3.0, U_EDGE]
    outer = [U_EDGE + (1.0 - U_EDGE) * k / OUTER for k in range(1, OUTER + 1)]
    return [-u for u in reversed(outer)] + inner + outer


def mapped(u, v):
    return R * u * math.sqrt(1.0 - v * v / 2.0), R * v * math.sqrt(1.0 - u * u / 2.0)


def deck():
    us = columns()
    vs = [k / ROWS for k in range(ROWS + 1)]
    # the quadratic grid: corner lines and mid lines
    uq = [us[0]] + [x for a, b in zip(us, us[1:]) for x in (0.5 * (a + b), b)]
    vq = [vs[0]] + [x for a, b in zip(vs, vs[1:]) for x in (0.5 * (a + b), b)]
    nu = len(uq)

    def node(i, j):
        return 1 + i + nu * j

    out = ["! The split-cylinder (Brazilian) test of a concrete disk in plane strain (issue 27 item 2).",
           "! Written by test/data/make_split_cylinder.py (its docstring gives every choice).",
           "TITLE, Split-cylinder test, D = 150 mm, b = 12 mm, plane strain", "", "NODES"]
    for j, v in enumerate(vq):
        for i, u in enumerate(uq):
            x, y = mapped(u, v)
            out.append(f"{node(i, j)}, {x:.15g}, {y:.15g}")
    out += ["", "GROUP, disk, TYPE=tri6, MATERIAL=concrete", "ELEMENTS, disk"]
    eid = 1
    for j in range(0, len(vq) - 1, 2):
        for i in range(0, nu - 1, 2):
            c = {(a, b): node(i + a, j + b) for a in range(3) for b in range(3)}
            # two triangles across the diagonal (0,0)-(2,2): corners counter-clockwise, then mid-sides
            out.append(f"{eid}, {c[0, 0]}, {c[2, 0]}, {c[2, 2]}, {c[1, 0]}, {c[2, 1]}, {c[1, 1]}")
            out.append(f"{eid + 1}, {c[0, 0]}, {c[2, 2]}, {c[0, 2]}, {c[1, 1]}, {c[1, 2]}, {c[0, 1]}")
            eid += 2
    out += ["", f"MATERIAL, concrete, CONCRETE, E=30000., NU=0.2, FT={FT:g}., GF=0.1", "",
            "NSET, axis, Y=0., TOL=1e-6", "FIX, axis, Y",
            f"NSET, left, X={-R:g}, Y=0., TOL=1e-6", "FIX, left, X",
            f"FSET, strip, GROUP=disk, CSYS=3, R={R:g}, THETA={90 - math.degrees(ALPHA):.12g}:"
            f"{90 + math.degrees(ALPHA):.12g}, TOL=1e-6",
            f"! {STEPS} steps to the closed form's cracking pressure {P_CRACK:.10g} MPa (Hondros)",
            f"STAGE, split, STEPS={STEPS}, OUTPUT=1, METHOD=full-newton-raphson, MAXIT=60, DELTA1=1e-9",
            f"PRESSURE, strip, VALUE={P_CRACK:.12g}",
            "! one step more, to 1.0005 times it: the first points crack",
            "STAGE, crack, STEPS=1, METHOD=full-newton-raphson, MAXIT=60, DELTA1=1e-9",
            f"PRESSURE, strip, VALUE={0.0005 * P_CRACK:.12g}", "", "SOLVER, cholmod", "OUTPUT, split_cylinder.h5", ""]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                           "split_cylinder.dat"))
    args = ap.parse_args()
    with open(args.output, "w") as f:
        f.write(deck())


if __name__ == "__main__":
    main()
