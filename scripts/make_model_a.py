#!/usr/bin/env python3
"""Write the decks of thesis numerical model A (chapter 4): input/modelA/<case>_<wall>.dat for
the edge loads E1-E3 and the diagonal loads D1-D3 on the thick (t = 25 mm) and the thin
(t = 14.3 mm) wall pipe (the thesis calls the thin-wall cases EN1-3, DN1-3).

    python3 scripts/make_model_a.py [--outdir input/modelA]

Geometry, loads and supports follow SPEC section 8 and thesis 4.2-4.4; every choice the thesis
leaves to its figures is written into the deck's comments (and listed in DECISIONS below).
"""
import argparse
import math
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

R_OUT = 100.0
WALLS = {"thick": 75.0, "thin": 85.7}          # inner radius; t = 25 and 14.3 mm
LENGTH = 232.0
LOAD = 5000.0                                   # N on each end of the half model
E1_SYSTEMS = {"upper": 4, "lower": 5}           # CSYS numbers of E1/D1's tent coordinate

DECISIONS = """\
! Choices the thesis leaves to its figures (Figures 4.1-4.3 are not in the text):
! * Mesh: that of thesis Table 2.1 (4 hex8 through the wall; theta 4 x 5.5, 2 x 7, 12 x 9,
!   2 x 7, 4 x 5.5 deg, so that the 11 and 22 deg load spans at theta = 0 and 180 are element
!   boundaries), with z graded symmetrically over the 232 mm: 2 x 6.5, 2 x 7.5, 2 x 9, 14 x 10,
!   2 x 9, 2 x 7.5, 2 x 6.5 mm (the mid-plane z = 116 is a node layer). The thin wall uses the
!   same mesh with 4 x 3.575 mm through the wall.
! * E1 ("bi-linearly distributed concentrated load"): a plane (linear in x and y) tent over the
!   outer corner: peak at (r = r_o, theta = 180), zero along the straight line from
!   (r = r_m, theta = 180) to (r = r_o, theta = 158), r_m = (r_i + r_o) / 2, i.e. linear along the
!   radial edge and along the outer rim, on the footprint of E2 (outer half thickness, 22 deg).
!   It is written as a pressure linear in the axial coordinate of an auxiliary cylindrical
!   system whose axis lies in the end plane, normal to that zero line.
! * Supports (thesis 4.3.1, 4.3.2): y = 0 fixed in y; the three outer-surface nodes at the
!   loaded edge of each end (theta 169..180, r = r_o; for the diagonal loads theta 169..180 at
!   the upper end and 0..11 at the lower end) fixed in x; the outer node of the lower end's
!   loaded corner fixed in z (the end loads balance in z: its reaction comes out zero).
! * Direction: the upper end z = 232 is pressed in -z, the lower end z = 0 in +z.
"""


def node_block(r_in):
    dr = (R_OUT - r_in) / 4.0
    return [
        f"A, 3, {r_in:g}, 0., 0.,",
        f"%, 5, {dr:.4f}, 0., 0.,       ! r = {r_in:g} .. 100, 4 elements",
        "%, 5, 0., 5.5, 0.,          ! theta 0 .. 22",
        "%, -2, 0., 7., 0.,          ! 36",
        "%, -12, 0., 9., 0.,         ! 144",
        "%, -2, 0., 7., 0.,          ! 158",
        "%, -4, 0., 5.5, 0.,         ! 180",
        "%, 3, 0., 0., 6.5,          ! z 0 .. 13",
        "%, -2, 0., 0., 7.5,         ! 28",
        "%, -2, 0., 0., 9.,          ! 46",
        "%, -14, 0., 0., 10.,        ! 186 (mid-plane 116 is layer 13)",
        "%, -2, 0., 0., 9.,          ! 204",
        "%, -2, 0., 0., 7.5,         ! 219",
        "%, -2, 0., 0., 6.5,         ! 232",
        "E,",
    ]


def tent_system(csys_id, r_mid, side):
    """CSYS whose axial coordinate is the distance from E1's zero line (into the loaded corner).
    side = +1: corner at theta = 0; -1: at theta = 180. Returns (record, peak distance)."""
    ax_, ay_ = side * r_mid, 0.0                                      # zero line end on the radial edge
    th = math.radians(22.0 if side > 0 else 158.0)
    bx, by = R_OUT * math.cos(th), R_OUT * math.sin(th)               # zero line end on the rim
    cx, cy = side * R_OUT, 0.0                                        # the loaded corner
    nx, ny = by - ay_, -(bx - ax_)                                    # normal to the zero line
    if nx * (cx - ax_) + ny * (cy - ay_) < 0.0:
        nx, ny = -nx, -ny
    nn = math.hypot(nx, ny)
    nx, ny = nx / nn, ny / nn
    peak = nx * (cx - ax_) + ny * (cy - ay_)
    rec = (f"CSYS, {csys_id}, CYLINDRICAL, {ax_:.4f}, 0., 0., {nx:.8f}, {ny:.8f}, 0., 0., 0., 1.")
    return rec, peak


def end_load(kind, end, corner, r_in):
    """Records of one end's load. kind 1..3; end 'upper'/'lower'; corner 180 or 0 (deg)."""
    z = LENGTH if end == "upper" else 0.0
    r_mid = 0.5 * (r_in + R_OUT)
    name = f"{end}_E{kind}"
    th = "158.:180." if corner == 180 else "0.:22."
    th11 = "169.:180." if corner == 180 else "0.:11."
    out = []
    if kind == 1:
        rec, peak = tent_system(E1_SYSTEMS[end], r_mid, -1 if corner == 180 else 1)
        out += [f"! E1 tent: zero on the line from (r = {r_mid:g}, theta = {corner}) to (r = 100, theta = "
                f"{158 if corner == 180 else 22}), peak {peak:.4f} mm further, at the outer corner",
                rec,
                f"FSET, {name}, GROUP=pipe, CSYS=3, R={r_mid:g}:100., THETA={th}, Z={z:g}, TOL=0.01",
                f"PRESSURE, {name}, TOTAL={LOAD:g}, VARY=Z, VARY_CSYS={E1_SYSTEMS[end]}, ZERO=0., "
                f"PEAK={peak:.4f}"]
    elif kind == 2:
        out += [f"FSET, {name}, GROUP=pipe, CSYS=3, R={r_mid:g}:100., THETA={th}, Z={z:g}, TOL=0.01",
                f"PRESSURE, {name}, TOTAL={LOAD:g}"]
    else:
        out += [f"FSET, {name}, GROUP=pipe, CSYS=3, THETA={th11}, Z={z:g}, TOL=0.01",
                f"PRESSURE, {name}, TOTAL={LOAD:g}"]
    return out


def deck(load, kind, wall):
    r_in = WALLS[wall]
    t = R_OUT - r_in
    diagonal = load == "D"
    area = 0.5 * math.pi * (R_OUT ** 2 - r_in ** 2)
    q = LOAD / area
    lower_corner = 0 if diagonal else 180
    thesis_name = f"{load}{'N' if wall == 'thin' else ''}{kind}"
    shape = {1: "bilinear load concentrated at the outer corner",
             2: "uniform over the outer half thickness, 22 deg",
             3: "uniform over the full thickness, 11 deg"}[kind]
    out = [
        f"! feps deck: numerical model A (thesis chapter 4), case {load}{kind} {wall} wall"
        f" (thesis {thesis_name}). Written by scripts/make_model_a.py.",
        f"! Half pipe (theta 0..180, symmetry plane y = 0): r_i = {r_in:g}, r_o = 100 (t = {t:.1f}), length 232,",
        "! hex8, linear elastic E = 31700, nu = 0.2 (Ripley's model pipe).",
        f"! {'Diagonal' if diagonal else 'Edge'} load {load}{kind}: {shape}; P = 5 kN on each end of the half model",
        f"! (mean end pressure q = {q:.3f} MPa, which normalises the thesis's stress contours);",
        "! the upper end (z = 232) is loaded at theta = 180, the lower end (z = 0) at theta = "
        f"{lower_corner}{' (the upper load rotated by 180 deg)' if diagonal else ''}.",
        DECISIONS.rstrip("\n"),
        f"TITLE, Model A {load}{kind} {wall} wall (thesis {thesis_name}): P = 5 kN, q = {q:.3f} MPa",
        "",
        "! --- nodes: r fastest (5), then theta (25), then z (27) ---",
    ]
    out += node_block(r_in)
    out += ["", "GROUP, pipe, TYPE=hex8, MATERIAL=concrete",
            "A, 8, 1, 2, 7, 6, 126, 127, 132, 131,",
            "%, 4, *, 8, 1,", "%, 24, *, 8, 5,", "%, 26, *, 8, 125,", "E,", "E,", "",
            "MATERIAL, concrete, ELASTIC, E=31700., NU=0.2", "",
            "! --- supports (thesis 4.3.1 / 4.3.2, Figure 4.3) ---",
            "NSET, symmetry, CSYS=2, Y=0., TOL=0.01",
            "FIX, symmetry, Y",
            "NSET, x_upper, CSYS=3, R=100., THETA=169.:180., Z=232., TOL=0.01",
            f"NSET, x_lower, CSYS=3, R=100., THETA={'0.:11.' if diagonal else '169.:180.'}, Z=0., TOL=0.01",
            "FIX, x_upper, X", "FIX, x_lower, X",
            f"NSET, z_corner, CSYS=3, R=100., THETA={lower_corner}., Z=0., TOL=0.01",
            "FIX, z_corner, Z", "",
            "! --- loads: 5 kN on each end, pressing the ends towards each other ---"]
    out += end_load(kind, "upper", 180, r_in)
    out += end_load(kind, "lower", lower_corner, r_in)
    out += ["", "! linear elastic: one step", "STAGE, load, STEPS=1", "",
            "SOLVER, cholmod", f"OUTPUT, modelA_{load}{kind}_{wall}.h5", ""]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--outdir", default=os.path.join(ROOT, "input", "modelA"))
    args = ap.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    n = 0
    for load in "ED":
        for kind in (1, 2, 3):
            for wall in WALLS:
                with open(os.path.join(args.outdir, f"{load}{kind}_{wall}.dat"), "w") as f:
                    f.write(deck(load, kind, wall))
                n += 1
    print(f"wrote {n} decks to {args.outdir}")


if __name__ == "__main__":
    main()
