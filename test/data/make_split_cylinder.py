#!/usr/bin/env python3
"""Write test/data/split_cylinder.dat and split_cylinder_peak.dat: the split-cylinder (Brazilian)
test of a concrete disk in plane strain (issue 27 item 2), for test/cli/check_split_cylinder.py.

    python3 test/data/make_split_cylinder.py [-o test/data/split_cylinder.dat]
    python3 test/data/make_split_cylinder.py --peak [--refine 3] [--gf 0.03] [-o FILE]

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
With --peak (test/data/split_cylinder_peak.dat) the deck follows the peak instead: CONCRETE with
DAMAGE=TENSILE (a cracked point keeps its compression along the crack; with the default isotropic
damage every control stalls at 1.0011 times the cracking pressure, docs/verification.md, "The
split-cylinder test"), the pressure to the cracking pressure in 10 steps, then indirect
displacement control: the opening of the middle column at the centre (its corner nodes at
y = 0, x = +-2.83 mm: a gauge wider than one column whatever --refine, so the crack may settle in
any column under it) grows by 0.05 mm in 200 steps, the pressure's pattern the cracking
pressure. --refine m (odd) divides every element side by m; --gf sets GF.
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
PEAK_LOAD_STEPS = 10                       # the peak deck: to P_CRACK in 10 steps (elastic)
PEAK_OPENING = 0.05                        # then the opening at the centre (mm) ...
PEAK_STEPS = 200                           # ... in 200 steps


def columns(refine=1):
    """Node u-coordinates (corner nodes), symmetric about 0, middle column centred: 3 refine
    columns under the loaded arc (refine odd), OUTER refine beyond it on each side."""
    inner = [-U_EDGE] + [U_EDGE * (2 * k - 3 * refine) / (3 * refine) for k in range(1, 3 * refine)] + [U_EDGE]
    outer = [U_EDGE + (1.0 - U_EDGE) * k / (OUTER * refine) for k in range(1, OUTER * refine + 1)]
    return [-u for u in reversed(outer)] + inner + outer


def mapped(u, v):
    return R * u * math.sqrt(1.0 - v * v / 2.0), R * v * math.sqrt(1.0 - u * u / 2.0)


def deck(peak=False, refine=1, gf=0.1):
    """The deck: the onset test (default), or with `peak` the peak test (module docstring)."""
    us = columns(refine)
    vs = [k / (ROWS * refine) for k in range(ROWS * refine + 1)]
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
    supports = ["NSET, axis, Y=0., TOL=1e-6", "FIX, axis, Y",
                f"NSET, left, X={-R:g}, Y=0., TOL=1e-6", "FIX, left, X",
                f"FSET, strip, GROUP=disk, CSYS=3, R={R:g}, THETA={90 - math.degrees(ALPHA):.12g}:"
                f"{90 + math.degrees(ALPHA):.12g}, TOL=1e-6"]
    if peak:
        half = R * U_EDGE / 3.0    # the coarse middle column's half width at y = 0: the gauge
        out += ["", f"MATERIAL, concrete, CONCRETE, E=30000., NU=0.2, FT={FT:g}., GF={gf:g}, DAMAGE=TENSILE", ""]
        out += supports
        out += [f"NSET, crack_right, X={half:.15g}, Y=0., TOL=1e-6",
                f"NSET, crack_left, X={-half:.15g}, Y=0., TOL=1e-6",
                f"! {PEAK_LOAD_STEPS} steps to the closed form's cracking pressure {P_CRACK:.10g} MPa (Hondros)",
                f"STAGE, split, STEPS={PEAK_LOAD_STEPS}, OUTPUT=1, METHOD=full-newton-raphson, MAXIT=60, DELTA1=1e-9",
                f"PRESSURE, strip, VALUE={P_CRACK:.12g}",
                f"! then the middle column's opening at the centre grows by {PEAK_OPENING:g} mm in {PEAK_STEPS} steps;",
                "! the pressure's pattern is the cracking pressure, so p = (1 + load factor) times it",
                f"STAGE, open, STEPS={PEAK_STEPS}, OUTPUT=1, PATH=DISPLACEMENT, NSET=crack_right, FROM=crack_left, "
                f"DOF=X, VALUE={PEAK_OPENING:g}, METHOD=full-newton-raphson, MAXIT=60, DELTA1=1e-9",
                f"PRESSURE, strip, VALUE={P_CRACK:.12g}", "", "SOLVER, cholmod", "OUTPUT, split_cylinder_peak.h5", ""]
        return "\n".join(out)
    out += ["", f"MATERIAL, concrete, CONCRETE, E=30000., NU=0.2, FT={FT:g}., GF=0.1", ""]
    out += supports
    out += [f"! {STEPS} steps to the closed form's cracking pressure {P_CRACK:.10g} MPa (Hondros)",
            f"STAGE, split, STEPS={STEPS}, OUTPUT=1, METHOD=full-newton-raphson, MAXIT=60, DELTA1=1e-9",
            f"PRESSURE, strip, VALUE={P_CRACK:.12g}",
            "! one step more, to 1.0005 times it: the first points crack",
            "STAGE, crack, STEPS=1, METHOD=full-newton-raphson, MAXIT=60, DELTA1=1e-9",
            f"PRESSURE, strip, VALUE={0.0005 * P_CRACK:.12g}", "", "SOLVER, cholmod", "OUTPUT, split_cylinder.h5", ""]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", help="the deck (default: test/data/split_cylinder.dat, or "
                    "test/data/split_cylinder_peak.dat with --peak)")
    ap.add_argument("--peak", action="store_true", help="the peak test: DAMAGE=TENSILE, the opening controlled")
    ap.add_argument("--refine", type=int, default=1, help="divide every element side by this odd number "
                    "(with --peak; default 1)")
    ap.add_argument("--gf", type=float, default=0.1, help="fracture energy GF, N/mm (with --peak; default 0.1)")
    args = ap.parse_args()
    if args.refine < 1 or args.refine % 2 == 0:
        ap.error("--refine must be odd (the middle column stays centred on x = 0)")
    if not args.peak and (args.refine != 1 or args.gf != 0.1):
        ap.error("--refine and --gf go with --peak")
    default = "split_cylinder_peak.dat" if args.peak else "split_cylinder.dat"
    output = args.output or os.path.join(os.path.dirname(os.path.abspath(__file__)), default)
    with open(output, "w") as f:
        f.write(deck(args.peak, args.refine, args.gf))


if __name__ == "__main__":
    main()
