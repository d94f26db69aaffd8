#!/usr/bin/env python3
"""Write the decks of the thesis's plane-strain joint model (chapter 3): input/joint2d/<case>.dat.

    python3 scripts/make_joint_2d.py [--outdir input/joint2d] [--mesh fine|coarse|tiny] [--cases a,b]

Cases (thesis 3.3-3.4): packing G_p = 300 MPa with nu_p = 0.1, 0.4, -0.3 (Poisson's ratio study) and
G_p = 300, 600, 900 MPa with nu_p = 0.1 (stiffness study), each at beta = 0.1 and 0.3 deg, with
Kn = 800, Ks = 400 MPa/mm; and the interface-stiffness sensitivity study (thesis 3.3, Fig. 3.5):
the same packings at beta = 0.1 deg with Kn = 8000, Ks = 4000 MPa/mm (suffix _stiff).
Names: G<Gp>_nu<nu_p>_b<beta>[_stiff], e.g. G300_nu0.4_b0.1, G300_nu-0.3_b0.3, G300_nu0.1_b0.1_stiff.

Meshes: 'fine' (default, the delivered decks: 2.5 mm elements at the joint, 26 500 DOFs),
'coarse' (5 mm, 7 300 DOFs: peaks 4-20% lower, same trends) and 'tiny' (for quick checks).
Run a deck from the folder that should receive its results (OUTPUT joint2d_<case>.h5), then
scripts/summarise_joint_2d.py.

Geometry and loads follow SPEC section 8; every choice the thesis leaves open is written into the
deck's comments.
"""
import argparse
import math
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

WIDTH = 150.0          # x from 0 to 150 (pipe wall thickness direction)
PIPE_LENGTH = 150.0    # each pipe piece, L in tan(beta) = delta / L
PACKING = 15.0         # packing thickness (assumed, SPEC section 8)
Q_TOP = 30.0           # MPa on the top of the upper pipe

PACKINGS = [(300, 0.1), (300, 0.4), (300, -0.3), (600, 0.1), (900, 0.1)]
BETAS = [0.1, 0.3]
COHESION = 0.05       # MPa, interface cohesion (chapter 6's value, see the deck comments)
SOFT = (800.0, 400.0)      # Kn, Ks (MPa/mm), thesis 3.2
STIFF = (8000.0, 4000.0)   # sensitivity case

# Element sizes (mm). Each pipe piece is graded towards the joint; y bands listed from the joint
# outwards as (element height, number of elements), adding up to PIPE_LENGTH.
MESHES = {
    "fine": {"nx": 60, "pipe": [(2.5, 12), (5.0, 6), (10.0, 3), (20.0, 3)], "packing": 6},
    "tiny": {"nx": 10, "pipe": [(15.0, 2), (30.0, 4)], "packing": 1},
    "coarse": {"nx": 30, "pipe": [(5.0, 6), (10.0, 3), (20.0, 2), (25.0, 2)], "packing": 3},
}


def num(v):
    """A coordinate with a decimal point (DATAIN tells node blocks by it)."""
    t = f"{v:g}"
    return t if any(c in t for c in ".eE") else t + "."


def case_name(gp, nu, beta, stiff):
    return f"G{gp}_nu{nu:g}_b{beta:g}" + ("_stiff" if stiff else "")


def all_cases():
    cases = [(gp, nu, beta, False) for beta in BETAS for gp, nu in PACKINGS]
    cases += [(gp, nu, 0.1, True) for gp, nu in PACKINGS]
    return cases


def parse_case(name):
    for c in all_cases():
        if case_name(*c) == name:
            return c
    raise SystemExit(f"unknown case {name!r}; known: {', '.join(case_name(*c) for c in all_cases())}")


def node_block(y0, rows, nx, comment):
    """A lattice block: x fastest (2 nx + 1 nodes at nx elements), then y by `rows`, a list of
    (node spacing, number of further node rows)."""
    dx = WIDTH / (2 * nx)
    out = [f"A, 1, 0., {num(y0)},{'':12s}! {comment}", f"%, {2 * nx + 1}, {num(dx)}, 0.,"]
    first = True
    for dy, n in rows:
        if first:
            out.append(f"%, {n + 1}, 0., {num(dy)},")
            first = False
        else:
            out.append(f"%, -{n}, 0., {num(dy)},")
    out.append("E,")
    return out


def tri6_blocks(offset, nx, nrows):
    """Each quad cell (2 x 2 node spacings) split along its diagonal from the lower-left to the
    upper-right corner into two tri6 (corners counter-clockwise, then mid-sides 1-2, 2-3, 3-1)."""
    r = 2 * nx + 1
    o = offset
    a = [o + 1, o + 3, o + 2 * r + 3, o + 2, o + r + 3, o + r + 2]
    b = [o + 1, o + 2 * r + 3, o + 2 * r + 1, o + r + 2, o + 2 * r + 2, o + r + 1]
    out = []
    for tri in (a, b):
        out += ["A, 6, " + ", ".join(str(n) for n in tri) + ",",
                f"%, {nx}, *, 6, 2,", f"%, {nrows}, *, 6, {2 * r},", "E,"]
    return out


def line3_block(lower_first, upper_first, nx):
    """Interfaces along +x (normal +y): lower layer ends then middle, then the upper layer."""
    lo = [lower_first, lower_first + 2, lower_first + 1]
    up = [upper_first, upper_first + 2, upper_first + 1]
    return ["A, 6, " + ", ".join(str(n) for n in lo + up) + ",", f"%, {nx}, *, 6, 2,", "E,"]


def deck(gp, nu, beta, stiff, mesh="fine", cohesion=COHESION):
    m = MESHES[mesh]
    nx = m["nx"]
    r = 2 * nx + 1                                   # nodes in one row
    bands = m["pipe"]
    assert abs(sum(h * n for h, n in bands) - PIPE_LENGTH) < 1e-9
    npipe_rows = sum(n for _, n in bands)            # element rows in one pipe piece
    npack_rows = m["packing"]
    hp = PACKING / npack_rows
    lower_rows = [(h / 2, 2 * n) for h, n in reversed(bands)]   # from y = 0 up to the joint
    upper_rows = [(h / 2, 2 * n) for h, n in bands]              # from the joint up to the top
    n_lower = r * (2 * npipe_rows + 1)
    n_pack = r * (2 * npack_rows + 1)
    y1 = PIPE_LENGTH
    y2 = PIPE_LENGTH + PACKING
    ytop = y2 + PIPE_LENGTH
    kn, ks = STIFF if stiff else SOFT
    delta = PIPE_LENGTH * math.tan(math.radians(beta))
    name = case_name(gp, nu, beta, stiff)
    ep = 2.0 * gp * (1.0 + nu)
    out = [
        f"! feps deck: 2D joint model (thesis chapter 3), case {name}. Written by scripts/make_joint_2d.py",
        f"! (mesh '{mesh}').",
        "! Plane strain (DATAIN system 1, x-y plane; feps holds uz = 0). A strip of pipe wall 150 mm wide",
        "! (x = 0 .. 150, the wall thickness direction) across one joint: the lower pipe piece",
        f"! y = 0 .. {y1:g}, the packing y = {y1:g} .. {y2:g} ({PACKING:g} mm thick: assumed, SPEC section 8;",
        f"! the thesis gives it only in Fig. 3.1), the upper pipe piece y = {y2:g} .. {ytop:g}. The packing",
        "! covers the full width of the pipe ends (assumed: Fig. 3.1 is not legible in the text).",
        "! Mesh (ours; Fig. 3.1(b) is not reproducible): 6-node triangles, each quad cell split along its",
        "! lower-left/upper-right diagonal; x: " + f"{nx} elements of {WIDTH / nx:g} mm;",
        "! each pipe piece graded towards the joint, element heights (from the joint) "
        + ", ".join(f"{n} x {h:g}" for h, n in bands) + " mm;",
        f"! the packing {npack_rows} x {hp:g} mm. 3-point rules in the triangles and on the interfaces.",
        "! Each body has its own node block; their rows at the two pipe/packing faces coincide and are",
        "! joined only by a layer of 3-pair line interfaces (interface-line3, 3-point Gauss) on each side",
        "! of the packing, as in the thesis (3.2).",
        f"! Materials: concrete G = 40000 MPa, nu = 0.2 as printed in thesis 3.2 (E = 96000 MPa); packing",
        f"! G_p = {gp} MPa, nu_p = {nu:g} (E_p = 2 G_p (1 + nu_p) = {ep:g} MPa; the thesis's formula",
        "! 2 G (1 + 2 nu) is a misprint and does not matter: G and nu are the data). Interfaces:",
        f"! Kn = {kn:g}, Ks = {ks:g} MPa/mm, phi = psi = 20 deg, cohesion c = {cohesion:g} MPa. Chapter 3 gives no",
        "! cohesion; chapter 6 (6.2) describes its interface as 'similar to the analysis described in",
        "! Chapter 3' with the same Kn, Ks, phi, psi and c = 0.05 MPa, which we take (make_joint_2d.py",
        "! --cohesion changes it). c = 0 runs too and changes the results by less than 0.5%",
        "! (docs/verification.md, chapter 3).",
        "! Loads (thesis 3.2): bottom (y = 0) pinned; q = 30 MPa on the top (y = "
        f"{ytop:g}) applied together with",
        f"! an x displacement of the top nodes delta = L tan(beta) = 150 tan({beta:g} deg) = {delta:.4f} mm",
        "! (the top stays free in y). One stage of 400 steps, modified Euler (thesis 3.2).",
        f"TITLE, 2D joint {name}: G_p = {gp} MPa; nu_p = {nu:g}; beta = {beta:g} deg; Kn = {kn:g} MPa/mm",
        "",
        f"! --- nodes: lower pipe 1-{n_lower}, packing {n_lower + 1}-{n_lower + n_pack}, "
        f"upper pipe {n_lower + n_pack + 1}-{2 * n_lower + n_pack} ---",
    ]
    out += node_block(0.0, lower_rows, nx, "lower pipe piece, y = 0 .. 150")
    out += node_block(y1, [(hp / 2, 2 * npack_rows)], nx, f"packing, y = {y1:g} .. {y2:g}")
    out += node_block(y2, upper_rows, nx, f"upper pipe piece, y = {y2:g} .. {ytop:g}")
    out += ["", "GROUP, pipe_low, TYPE=tri6, MATERIAL=concrete"]
    out += tri6_blocks(0, nx, npipe_rows)
    out += ["", "GROUP, packing, TYPE=tri6, MATERIAL=packer"]
    out += tri6_blocks(n_lower, nx, npack_rows)
    out += ["", "GROUP, pipe_up, TYPE=tri6, MATERIAL=concrete"]
    out += tri6_blocks(n_lower + n_pack, nx, npipe_rows)
    out += ["", f"! lower interface (y = {y1:g}): lower layer = the lower pipe's top row, upper = the packing's",
            "! bottom row; along +x, so the normal is +y and eps_n > 0 is opening",
            "GROUP, if_low, TYPE=interface-line3, MATERIAL=joint"]
    out += line3_block(n_lower - r + 1, n_lower + 1, nx)
    out += ["", f"! upper interface (y = {y2:g}): lower layer = the packing's top row, upper = the upper pipe's "
            "bottom row", "GROUP, if_up, TYPE=interface-line3, MATERIAL=joint"]
    out += line3_block(n_lower + n_pack - r + 1, n_lower + n_pack + 1, nx)
    out += ["E,", "",
            "MATERIAL, concrete, ELASTIC, G=40000., NU=0.2",
            f"MATERIAL, packer, ELASTIC, G={gp:g}., NU={nu:g}",
            f"MATERIAL, joint, INTERFACE, KN={num(kn)}, KS={num(ks)}, PHI=20., PSI=20., C={num(cohesion)}",
            "",
            "! --- supports: the bottom of the lower pipe pinned ---",
            "NSET, bottom, Y=0., TOL=0.01",
            "FIX, bottom, X, Y",
            "",
            "! --- loads: pressure and misalignment displacement together, in 400 equal steps ---",
            f"NSET, top, Y={num(ytop)}, TOL=0.01",
            f"FSET, top_face, GROUP=pipe_up, Y={num(ytop)}, TOL=0.01",
            "STAGE, load, STEPS=400, METHOD=modified-euler, OUTPUT=40",
            f"PRESSURE, top_face, VALUE={num(Q_TOP)}",
            f"DISPLACE, top, X={delta:.6f}",
            "",
            "SOLVER, cholmod",
            f"OUTPUT, joint2d_{name}.h5", ""]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--outdir", default=os.path.join(ROOT, "input", "joint2d"))
    ap.add_argument("--mesh", choices=sorted(MESHES), default="fine")
    ap.add_argument("--cases", default="", help="comma-separated case names (default: all 15)")
    ap.add_argument("--cohesion", type=float, default=COHESION, help="interface cohesion c in MPa (default 0.05)")
    args = ap.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    cases = [parse_case(c) for c in args.cases.split(",") if c] or all_cases()
    for c in cases:
        with open(os.path.join(args.outdir, case_name(*c) + ".dat"), "w") as f:
            f.write(deck(*c, mesh=args.mesh, cohesion=args.cohesion))
    print(f"wrote {len(cases)} decks to {args.outdir}")


if __name__ == "__main__":
    main()
