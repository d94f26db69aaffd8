#!/usr/bin/env python3
"""Write the decks of the thesis's back analysis of the laboratory tests (chapter 9):
input/chapter9/<case>.dat for
  CR   plain model pipe,
  RE1  hoop reinforcement near the external surface at the joint (as tested, thesis 8.7),
  RE2  the same reinforcement near the internal surface,
  PR1  local prestressing: radial pressure q = 5 MPa from a steel band at the joint (stage 1),
       then the band as hoop bars, born stress-free (ACTIVATE), and the end load (stage 2),
  PR2  the same with q = 1 MPa.

    python3 scripts/make_chapter9.py [--outdir input/chapter9] [--steps 400]
                                     [--tension closest-point] [--method full-newton-raphson]
                                     [--band pretensioned | posttensioned]

--tension closest-point writes the concrete with the continuous tension rule (not in the thesis;
docs/verification.md, "The tension zone of the Matsuoka-Nakai model"), with which a few
full-Newton steps reproduce the thesis's 400: e.g. --steps 5 --tension closest-point --method
full-newton-raphson. --band pretensioned (not in the thesis) models PR1 and PR2's band as a
pretensioned band bonded to the pipe: its bars exist from the start and stage 1 prestresses them
(PRESTRESS) to the hoop force q R b that would press the band's width b = 13 mm with q; bonded,
the band then loses force as the concrete under it contracts (about 13% for PR1). The thesis's
model, the default, is a post-tensioned band: the pressure q on the plain pipe, then the band
born stress-free. --band posttensioned builds that model with the band's own force (PRESTRESS
..., BOND=after: the unbonded band pulls on its nodes in stage 1 and is born carrying T). The
defaults write the thesis's decks (input/chapter9).

Geometry, material and loads follow SPEC section 8 and thesis 9.1-9.3; the choices the thesis
leaves to its figures are written into each deck's comments (DECISIONS below).
"""
import argparse
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

R_IN, R_OUT, LENGTH = 75.0, 100.0, 232.0
NR, NT = 5, 13                      # nodes along r and theta (quarter, theta 90..180)
LAYER = NR * NT                     # nodes in one z layer
NZ = 27
Z_NODES = [0.0, 6.5, 13.0, 20.5, 28.0, 37.0, 46.0] + [46.0 + 10.0 * k for k in range(1, 15)] + \
          [195.0, 204.0, 211.5, 219.0, 225.5, 232.0]
R_NODES = [R_IN + 6.25 * k for k in range(NR)]
THETA_NODES = [90.0 + 9.0 * k for k in range(7)] + [151.0, 158.0] + [158.0 + 5.5 * k for k in range(1, 5)]
P_QUARTER = 50000.0                 # N: P = 200 kN on the whole pipe end, a quarter of it here
HOOP_AREA = 6.28                    # mm2 (thesis 9.2, Figure 8.7)
BAND_AREAS = (4.5, 9.0, 4.5)        # mm2 at z = 219, 225.5, 232 (thesis 9.3, Figure 9.5)
REBAR_R = {"RE1": 3, "RE2": 1}      # r index: 93.75 (cover 6.25 to the outside), 81.25
REBAR_Z = (24, 25)                  # z index: 219 and 225.5 (13 and 6.5 mm below the loaded end)
PRESTRESS = {"PR1": 5.0, "PR2": 1.0}
BAND_R, BAND_WIDTH = 100.0, 13.0    # the band on the external surface, z = 219 .. 232

DECISIONS = """\
! Choices the thesis leaves to its figures (Figures 8.6, 8.7, 9.1, 9.2, 9.5 are not in the text):
! * Mesh: model A's thick-wall mesh (input/modelA) restricted to theta 90..180: 4 hex8 through
!   the wall (6.25 mm), theta 6 x 9, 2 x 7, 4 x 5.5 deg (fine at the heavily loaded theta = 180),
!   z 2 x 6.5, 2 x 7.5, 2 x 9, 14 x 10, 2 x 9, 2 x 7.5, 2 x 6.5 mm over the 232 mm length.
! * Load: P = 200 kN on the whole end (so 50 kN on the quarter), from the angled plate B;
!   linear in x on each side: zero at x = 0 (theta = 90, under the plate's least closure) and
!   largest at x = -100 (theta = 180), the distribution of a rigid plate rotating about the
!   y axis (thesis 8.3: "linearly distributed on each half of the pipe end"). Peak 25.9 MPa,
!   mean 14.6 MPa.
! * Supports: every node of the bottom z = 0 fixed in x, y and z ("the nodes fixed at the pipe
!   bottom"); x = 0 (theta = 90) fixed in x and y = 0 (theta = 180) fixed in y (symmetry).
! * Concrete: modified Matsuoka-Nakai, E = 31700, nu = 0.22, phi = psi = 54.9 deg, ft = 5 MPa.
! * Solution: modified Newton-Raphson, 400 equal steps (thesis 9.2), at most 10 iterations.
"""

REBAR_NOTE = """\
! * Reinforcement (RE1, RE2): two hoop rings of 3-node bars (E = 200 GPa, A = 6.28 mm2 each, perfect
!   bond: the bars share the solid's nodes) at z = 219 and 225.5 (13 and 6.5 mm below the loaded
!   end); RE1 at r = 93.75 (6.25 mm from the external surface), RE2 at r = 81.25 (6.25 mm from the
!   internal surface). Each ring: 6 bar3 elements over theta pairs of equal spacing
!   (90-108-126-144, 144-158, 158-169-180)."""

BAND_NOTE = """\
! * Prestressing band (PR1, PR2): 13 mm wide on the external surface from z = 219 to the loaded end
!   z = 232 (two element layers); stage 1 applies the band's radial pressure q on that surface,
!   in 50 steps (thesis 9.3); stage 2 applies the end load P in 400 steps. The band is three hoop
!   rings of 3-node bars at r = 100: 4.5 mm2 at z = 219 and 232, 9 mm2 at z = 225.5 (18 mm2 in all,
!   trapezoidal shares of the band's section), E = 200 GPa.
! * As in the thesis, q acts on the plain pipe in stage 1 and the band's bars are added in stage 2
!   (STAGE ..., ACTIVATE=band_edges:band_middle): they carry nothing in stage 1 and enter stage 2
!   stress-free, so the whole of q prestresses the concrete. The bottom is fixed in both stages
!   (the thesis had it pinned in stage 1; the band is 219 mm away from it)."""

POST_NOTE = """\
! * Prestressing band (PR1, PR2): 13 mm wide on the external surface from z = 219 to the loaded end
!   z = 232, three hoop rings of 3-node bars at r = 100: 4.5 mm2 at z = 219 and 232, 9 mm2 at
!   z = 225.5 (18 mm2 in all), E = 200 GPa.
! * --band posttensioned (the thesis's model, built with PRESTRESS ..., BOND=after): stage 1
!   tensions the band to the hoop force T = q R b that presses its width b = 13 mm at R = 100 with
!   q (the same stress T / 18 mm2 in all three rings) while it is not bonded, so its pull on the
!   rings' nodes stands in for the pressure q; it is bonded from stage 2 on, carrying T."""

TENDON_NOTE = """\
! * Prestressing band (PR1, PR2): 13 mm wide on the external surface from z = 219 to the loaded end
!   z = 232, three hoop rings of 3-node bars at r = 100: 4.5 mm2 at z = 219 and 232, 9 mm2 at
!   z = 225.5 (18 mm2 in all), E = 200 GPa.
! * --band pretensioned (not the thesis's model, which applies the pressure q to the plain pipe
!   and adds the band afterwards): the band's bars exist from the start and stage 1 prestresses
!   them (PRESTRESS, 50 steps) to the hoop force T = q R b that would press the band's width
!   b = 13 mm at R = 100 with q: the same stress T / 18 mm2 in all three rings. Bonded, the band
!   loses force as the concrete under it contracts."""


def node(ir, it, iz):
    return 1 + ir + NR * it + LAYER * iz


def node_block():
    return [
        "A, 3, 75., 90., 0.,",
        "%, 5, 6.25, 0., 0.,         ! r = 75 .. 100, 4 elements",
        "%, 7, 0., 9., 0.,           ! theta 90 .. 144",
        "%, -2, 0., 7., 0.,          ! 158",
        "%, -4, 0., 5.5, 0.,         ! 180",
        "%, 3, 0., 0., 6.5,          ! z 0 .. 13",
        "%, -2, 0., 0., 7.5,         ! 28",
        "%, -2, 0., 0., 9.,          ! 46",
        "%, -14, 0., 0., 10.,        ! 186",
        "%, -2, 0., 0., 9.,          ! 204",
        "%, -2, 0., 0., 7.5,         ! 219",
        "%, -2, 0., 0., 6.5,         ! 232",
        "E,",
    ]


def pipe_block():
    """DATAIN element block of the pipe's hex8 (4 through the wall, 12 in theta, 26 in z)."""
    return [f"A, 8, 1, 2, {NR + 2}, {NR + 1}, {LAYER + 1}, {LAYER + 2}, {LAYER + NR + 2}, {LAYER + NR + 1},",
            "%, 4, *, 8, 1,", f"%, 12, *, 8, {NR},", f"%, 26, *, 8, {LAYER},", "E,"]


def supports():
    """The bottom z = 0 fixed, and the symmetry planes x = 0 and y = 0."""
    return ["NSET, bottom, CSYS=2, Z=0., TOL=0.01", "FIX, bottom, X, Y, Z",
            "NSET, sym_x, CSYS=2, X=0., TOL=0.01", "FIX, sym_x, X",
            "NSET, sym_y, CSYS=2, Y=0., TOL=0.01", "FIX, sym_y, Y"]


def hoop_ring_block(ir, izs):
    """DATAIN element block: bar3 rings along theta at r index ir and z indices izs (equally spaced)."""
    first = [node(ir, 0, izs[0]), node(ir, 1, izs[0]), node(ir, 2, izs[0])]
    lines = ["A, 3, " + ", ".join(str(n) for n in first) + ",",
             f"%, 6, *, *, {2 * NR},              ! 6 bars around theta 90..180"]
    if len(izs) > 1:
        dz = izs[1] - izs[0]
        assert all(b - a == dz for a, b in zip(izs, izs[1:]))
        lines.append(f"%, {len(izs)}, *, *, {dz * LAYER},           ! rings at z = "
                     + ", ".join(f"{Z_NODES[i]:g}" for i in izs))
    lines.append("E,")
    return lines


def deck(case, steps=400, tension="proportional", method="modified-newton-raphson", band="pressure", q=None):
    """The deck of one case. For PR1/PR2, `q` (MPa) replaces the thesis's band pressure and the
    deck is labelled PARAMETERS q, band (scripts/study_prestress.py)."""
    if q is not None and not case.startswith("PR"):
        raise ValueError(f"q applies to the band cases PR1 and PR2, not {case}")
    labelled = q is not None
    if q is None and case.startswith("PR"):
        q = PRESTRESS[case]
    out = [
        f"! feps deck: back analysis of the laboratory tests (thesis chapter 9), case {case}.",
        "! Written by scripts/make_chapter9.py.",
        "! Quarter of the thick model pipe (theta 90..180; symmetry planes x = 0 and y = 0): r_i = 75,",
        "! r_o = 100, length 232, hex8; loaded through the angled plate B on the top end z = 232.",
        DECISIONS.rstrip("\n"),
    ]
    if case.startswith("RE"):
        out.append(REBAR_NOTE)
    if case.startswith("PR"):
        out.append({"pressure": BAND_NOTE, "pretensioned": TENDON_NOTE, "posttensioned": POST_NOTE}[band])
    titles = {"CR": "plain pipe", "RE1": "hoop bars near the external surface",
              "RE2": "hoop bars near the internal surface"}
    if case.startswith("PR"):
        titles[case] = f"prestressing band, q = {q:g} MPa"
    out += [f"TITLE, Chapter 9 back analysis {case}: {titles[case]}, P = 200 kN (quarter: 50 kN)", "",
            "! --- nodes: r fastest (5), then theta (13), then z (27) ---"]
    out += node_block()
    out += ["", "GROUP, pipe, TYPE=hex8, MATERIAL=concrete"] + pipe_block()
    if case.startswith("RE"):
        out += ["", f"GROUP, rebar, TYPE=bar3, MATERIAL=hoop_bar"]
        out += hoop_ring_block(REBAR_R[case], list(REBAR_Z))
    if case.startswith("PR"):
        out += ["", "GROUP, band_edges, TYPE=bar3, MATERIAL=band_edge"]
        out += hoop_ring_block(NR - 1, [24, 26])
        out += ["", "GROUP, band_middle, TYPE=bar3, MATERIAL=band_middle"]
        out += hoop_ring_block(NR - 1, [25])
    concrete = "MATERIAL, concrete, MATSUOKA, E=31700., NU=0.22, PHI=54.9, PSI=54.9, FT=5."
    if tension != "proportional":
        concrete += f", TENSION={tension}"
    out += ["E,", "", concrete]
    if labelled:
        out += [f"PARAMETERS, q={q:g}, band={band}"]
    if case.startswith("RE"):
        out.append(f"MATERIAL, hoop_bar, BAR, E=200000., A={HOOP_AREA}")
    if case.startswith("PR"):
        out.append(f"MATERIAL, band_edge, BAR, E=200000., A={BAND_AREAS[0]}")
        out.append(f"MATERIAL, band_middle, BAR, E=200000., A={BAND_AREAS[1]}")
    out += ["", "! --- supports ---",
            *supports(), "",
            "! --- loads ---",
            "FSET, top, GROUP=pipe, CSYS=2, Z=232., TOL=0.01"]
    out += ["", f"CONTROLS, METHOD={method}, MAXIT={30 if method == 'full-newton-raphson' else 10}"]
    if case.startswith("PR") and band in ("pretensioned", "posttensioned"):
        stress = q * BAND_R * BAND_WIDTH / sum(BAND_AREAS)
        bond = ", BOND=after" if band == "posttensioned" else ""
        out += ["", f"! stage 1: the band's bars prestressed to T = q R b = {q * BAND_R * BAND_WIDTH:g} N "
                f"(q = {q:g} MPa), {stress:.6g} MPa" + (", bonded from stage 2" if bond else ""),
                "STAGE, prestress, STEPS=50",
                f"PRESTRESS, band_edges, STRESS={stress:.6g}{bond}",
                f"PRESTRESS, band_middle, STRESS={stress:.6g}{bond}", "",
                "! stage 2: the end load (the bonded band keeps its prestress)",
                f"STAGE, load, STEPS={steps}",
                f"PRESSURE, top, TOTAL={P_QUARTER:g}, VARY=X, ZERO=0., PEAK=-100."]
    elif case.startswith("PR"):
        out += ["FSET, band, GROUP=pipe, CSYS=3, R=100., Z=219.:232., TOL=0.01", "",
                f"! stage 1: the band's prestress, a uniform radial pressure q = {q:g} MPa under the band",
                "STAGE, prestress, STEPS=50",
                f"PRESSURE, band, VALUE={q:g}", "",
                "! stage 2: the band's bars are born stress-free; the end load (the prestress stays)",
                f"STAGE, load, STEPS={steps}, ACTIVATE=band_edges:band_middle",
                f"PRESSURE, top, TOTAL={P_QUARTER:g}, VARY=X, ZERO=0., PEAK=-100."]
    else:
        out += [f"STAGE, load, STEPS={steps}",
                f"PRESSURE, top, TOTAL={P_QUARTER:g}, VARY=X, ZERO=0., PEAK=-100."]
    out += ["", "SOLVER, cholmod", f"OUTPUT, chapter9_{case}.h5", ""]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--outdir", default=os.path.join(ROOT, "input", "chapter9"))
    ap.add_argument("--steps", type=int, default=400, help="steps of the loading stage (thesis: 400)")
    ap.add_argument("--tension", choices=["proportional", "closest-point"], default="proportional",
                    help="the concrete's tension rule (thesis: proportional)")
    ap.add_argument("--method", choices=["modified-newton-raphson", "full-newton-raphson"],
                    default="modified-newton-raphson", help="solution method (thesis: modified-newton-raphson)")
    ap.add_argument("--band", choices=["pressure", "pretensioned", "posttensioned"], default="pressure",
                    help="PR1/PR2's prestress: pressure q on the plain pipe, then the band born "
                         "(thesis), or the band's bars pretensioned to q R b and bonded (pretensioned), or "
                         "tensioned to q R b and bonded from stage 2 (posttensioned, the thesis's model with "
                         "the band's own force)")
    args = ap.parse_args()
    if args.steps < 1:
        ap.error(f"--steps {args.steps}: at least one step is needed")
    os.makedirs(args.outdir, exist_ok=True)
    cases = ["CR", "RE1", "RE2", "PR1", "PR2"]
    for case in cases:
        with open(os.path.join(args.outdir, f"{case}.dat"), "w") as f:
            f.write(deck(case, args.steps, args.tension, args.method, args.band))
    print(f"wrote {len(cases)} decks to {args.outdir}")


if __name__ == "__main__":
    main()
