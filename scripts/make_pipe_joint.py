#!/usr/bin/env python3
"""Write a feps deck of a pipe joint for any pipe: two pipes and the packing between them, the
bottom pipe in soil (thesis model C, chapter 6: quarter model, y >= 0 and z >= 0; both pipes with
--soil-around-top), or with
--packing 0 one pipe in soil under jacking loads on its ends (thesis model B, chapter 5: half
model, y >= 0, edge or diagonal load).

Misalignment (--misalignment): edge, the top pipe turned about the y axis so that the joint closes
at x = +r_o (the thesis's); diagonal, turned about the axis at 45 deg in the cross-section (between
x and y), the joint closing at theta = 45 deg. The plane of deflection is a symmetry plane as long
as gravity (along -x, --gamma) does not break it: the diagonal deck is then the quarter model
turned by 45 deg (theta 45..225), its symmetry plane held normal to itself in a Cartesian CSYS
turned by 45 deg (a nodal system: feps's inclined support), so it gives the edge quarter model's
joint. With --gamma, or --full, it is the whole ring (z >= 0 still: the three-pipe system's
mid-plane): the edge case's mesh mirrored about the plane of deflection and turned by 45 deg, the
top end displaced along that direction; --full writes the edge case on the same unturned ring
(docs/verification.md, "Diagonal misalignment (issue 26 item 4)": they all give the same joint).

Soil round the top pipe (--soil-around-top): the thesis's model C has soil round the bottom pipe
only; a real drive has ground round both. The option puts the same four soil layers round the
packing and the top pipe (bonded, out to the same far boundary, fixed there in x and y), one
ground with the bottom pipe's; with --gamma the soil's end face is then the top pipe's end, on
rollers in z. Default: as the thesis (the presets write the thesis's decks byte for byte).
--interface frictional joins the soil to the pipes (and, with --soil-around-top, the packing)
through Mohr-Coulomb interfaces on r = r_o instead of shared nodes, so that the pipes can slide
through the ground (group pipe_soil; a second node row at r = r_o is the soil's inner face).

    python3 scripts/make_pipe_joint.py --inner-diameter 1000 --wall 100 --pipe-length 2500 \\
        --packing 20 --packing-G 300 --packing-nu 0.1 --angle 0.5 --jacking-stress 10 -o dn1000.dat

Every option defaults to the thesis's pipe and joint (r_i = 600, r_o = 715, L = 2500, a 15 mm
packing, G_p = 300, nu_p = 0.1; beta = 0.09 deg; q = 10 MPa; soil E = 144, nu = 0.2): with no
option it writes thesis case C_G300_nu0.1_b0.09's model. make_model_b.py and make_model_c.py
are this generator's presets for the thesis's cases.

The mesh scales with the pipe: the same elements in theta (degrees), the same number through the
wall and in the soil's four layers (out to --soil-radius, default 2000/715 r_o), and the z grading
scaled by L / 2500, so that the thesis's pipe gets the thesis's grid. --theta-step,
--wall-elements and --z-refine refine it (docs/verification.md: the convergence study for DN 1000
and DN 2400).

Gravity and in-situ stress (--gamma): gravity acts along -x, in the symmetry plane y = 0; the
joint closes at x = +r_o (theta = 0), the crown (model B's edge load: at x = -r_o, the invert).
The ground surface lies --cover above the crown; a first stage `geostatic` sets the K0 stress
field (GEOSTATIC, SURFACE=r_o + cover; K0 default 1 - sin(phi), Jaky) under GRAVITY, X=-1.
Below --water-table (a depth under the surface) the soil has the submerged unit weight gamma -
9.81e-6 N/mm3 (group soil_wet): an effective-stress model without pore pressures. The pipes
weigh nothing (as the thesis's materials); the soil's end faces rest on rollers in z (the
in-situ stress along the pipe's axis is carried there, not left unbalanced at a free face).
"""
import argparse
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from feps_cli import finite, positive, positive_int  # noqa: E402  (argparse types)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

R_IN, R_OUT, L_PIPE, PACKING = 600.0, 715.0, 2500.0, 15.0   # the thesis's pipe (SPEC 8)
R_SOIL = 2000.0            # the thesis decks' soil radius (the thesis gives none)
GAMMA_W = 9.81e-6          # N/mm3: the unit weight of water
# model C (thesis 6.2): q on the top end, the packing/bottom-pipe interface, the packing
Q = 10.0
# --capacity: the pipes' cracking concrete takes the compression surface's PHI = PSI = 35 deg (the
# laboratory tests' choice, docs/verification.md: at chapter 9's 54.9 the surface meets the cracking
# criterion in tension and full Newton stops before a peak)
CONCRETE_PHI = 35.0
KN_JOINT, KS_JOINT, PHI_JOINT, PSI_JOINT, C_JOINT = 800.0, 400.0, 20.0, 20.0, 0.05
G_PACKING, NU_PACKING, BETA = 300.0, 0.1, 0.09
SEAT_STEPS = 5             # --capacity: stage seat's steps
EQUILIBRIUM_STEPS = 100    # stage s3: at most 100 x 50 iterations, 1 per step once converged

# theta grid: 4 x 3 deg on the loaded edge (theta = 0, x = +715: sigma_max is read from elements
# with theta < 6 deg, thesis 7.4.3), then THETA_STEP up to 180. 3 deg (60 elements) because the
# gap front at beta = 0.27 is located between Gauss points: with 6 deg beyond theta = 12 (the
# first decks) Z of C_G300_nu-0.3_b0.27 was 805 mm, with 3 deg 825 and with 1.5 deg 829
# (docs/verification.md, model C mesh sensitivity).
THETA_EDGE = [3.0] * 4
THETA_STEP = 3.0
# model C's z grading at L = 2500 (scaled by L / 2500): the bottom block from its mid-length
# (z = 0, a symmetry plane) towards the joint, the top pipe from the joint with a node layer at
# its mid-length section A-A
Z_BOTTOM_STEPS = [150.0] * 4 + [100.0] * 3 + [50.0] * 4 + [25.0] * 4 + [12.5] * 4
Z_TOP_STEPS = [12.5] * 4 + [25.0] * 4 + [50.0] * 4 + [100.0] * 3 + [150.0] * 4 \
    + [150.0] * 5 + [100.0] * 3 + [50.0] * 4
PACKING_LAYERS = 2
WALL_ELEMENTS = 2          # hex8 through the pipe wall (--wall-elements: the mesh study)
# model B (thesis 5.2): theta 6 x 10, 6 x 7.5, 15 x 5 deg; z from each end 4 x 50, 3 x 100, 5 x 150
B_THETA = [(6, 10.0, "theta = 0 .. 60"), (6, 7.5, "theta = 105"), (15, 5.0, "theta = 180")]
B_Z = [(4, 50.0), (3, 100.0), (5, 150.0), (5, 150.0), (3, 100.0), (4, 50.0)]
ELEMENTS = ("hex8", "hex20", "wedge6", "wedge15", "tet4", "tet10")


def model_code_gf(fc):
    """Fracture energy (N/mm) of a concrete of compressive strength fc (MPa): fib Model Code 2010,
    eq. 5.1-9, G_F = 73 f_cm^0.18 N/m (the thesis gives none)."""
    return 0.073 * fc ** 0.18


def num(v):
    """A deck number: 15 -> '15.', 12.5 -> '12.5'."""
    return f"{v:g}" + ("." if float(v).is_integer() and "e" not in f"{v:g}" else "")


def sci(v):
    """A force in the decks' form: 1e6 -> '1.0e6', 1.25e6 -> '1.25e6'."""
    mant, exp = f"{v:.9e}".split("e")
    mant = mant.rstrip("0")
    return f"{mant}{'0' if mant.endswith('.') else ''}e{int(exp)}"


class Pipe:
    """The pipe (mm): inner and outer radius, length, packing thickness (0: model B's one pipe)."""

    def __init__(self, r_in=R_IN, r_out=R_OUT, length=L_PIPE, packing=PACKING):
        if not 0.0 < r_in < r_out or not length > 0.0 or not packing >= 0.0:
            raise ValueError(f"r_i = {r_in:g}, r_o = {r_out:g}, L = {length:g}, a = {packing:g}: "
                             "a pipe needs 0 < r_i < r_o, L > 0 and a packing a >= 0 mm")
        self.r_in, self.r_out, self.length, self.packing = r_in, r_out, length, packing
        self.rs, self.zs = r_out / R_OUT, length / L_PIPE          # the mesh's scales
        self.thesis = (r_in, r_out, length) == (R_IN, R_OUT, L_PIPE)

    def scaled_x(self, x):
        """A position across the thesis's pipe (x = 220, 250 mm) at this pipe's size (0.1 mm)."""
        return round(x * self.rs, 1)

    def default_soil_radius(self):
        return round(R_SOIL * self.rs, 1)

    def parameters(self):
        """PARAMETERS of a pipe off the thesis's size (none for it: the decks stay as they were)."""
        if self.thesis and self.packing in (0.0, PACKING):
            return ""
        return (f", r_i={self.r_in:g}, r_o={self.r_out:g}, L={self.length:g}"
                + (f", a={self.packing:g}" if self.packing else ""))


class Ground:
    """Soil weight and in-situ stress: gamma (N/mm3), K0, the surface's x (gravity along -x) and
    the water table's x (None: dry); no weight when gamma is None."""

    def __init__(self, gamma=None, k0=None, phi=None, surface=None, water=None):
        self.gamma, self.surface, self.water = gamma, surface, water
        if gamma is not None and k0 is None:
            if phi is None:
                raise ValueError("--gamma needs --k0 or the soil's --soil-phi (K0 = 1 - sin(phi), Jaky)")
            k0 = 1.0 - math.sin(math.radians(phi))
        self.k0 = k0

    def material(self, wet=False):
        """GAMMA= and K0= of the soil's MATERIAL record ('' when weightless)."""
        if self.gamma is None:
            return ""
        return f", GAMMA={self.gamma - GAMMA_W if wet else self.gamma:.6g}, K0={self.k0:.6g}"

    def dry_columns(self, radii, thetas, start=0.0):
        """Per soil element layer (between radii), the number of theta elements (from theta = start)
        above the water table, by their centre's x; all of them when dry."""
        return [sum(layer) for layer in self.dry_flags(radii, thetas, start)]

    def dry_flags(self, radii, thetas, start=0.0):
        """Per soil element layer (between radii), per theta element (from theta = start): above the
        water table, by the mean of its corners' x (all True when dry)."""
        out = []
        for r0, r1 in zip(radii, radii[1:]):
            edges = [start + sum(thetas[:j]) for j in range(len(thetas) + 1)]
            x = [0.25 * (r0 + r1) * (math.cos(math.radians(a)) + math.cos(math.radians(b)))
                 for a, b in zip(edges, edges[1:])]
            out.append([self.water is None or v > self.water for v in x])
        return out

    def layers(self, dry, n):
        """The soil groups' wet flags: (False,) when dry, else those that get elements."""
        return (False,) if self.water is None else tuple(w for w in (False, True) if any((n - k if w else k) for k in dry))

    def stage(self):
        """The geostatic stage's records, before the load stages."""
        if self.gamma is None:
            return []
        return ["! --- in-situ stress: the soil's weight along -x (gravity in the symmetry plane y = 0) and",
                f"! the K0 stress field (K0 = {self.k0:.4g}) from the ground surface at x = {self.surface:g}"
                + ("" if self.water is None else f"; soil below the water table x = {self.water:g}") + " ---",
                "! (full Newton-Raphson: the pipe settles in the ground and the soil's points may yield)",
                "STAGE, geostatic, STEPS=4, LOAD=0, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-6, "
                "LINESEARCH=energy", "GRAVITY, X=-1.", f"GEOSTATIC, SURFACE={num(self.surface)}"
                + ("" if self.water is None else f", WATER={num(self.water)}")]

    def rollers(self, pipe, r_soil, faces):
        """Rollers in z on the soil's end faces z in `faces` (not its inner edge, the pipe's)."""
        if self.gamma is None:
            return []
        out = ["! the soil's end faces on rollers in z: its in-situ stress along the axis rests there"]
        for i, z in enumerate(faces):
            out += [f"NSET, soil_end{i + 1}, CSYS=3, R={num(pipe.r_out + 1.0)}:{radius_text(r_soil)}, Z={num(z)}, "
                    "TOL=0.01", f"FIX, soil_end{i + 1}, Z"]
        return out


def soil_layers(r_soil, r_out=R_OUT):
    """Four soil element layers from r_out, growing outwards (715, 865, 1115, 1465, 2000 for
    r_soil = 2000: increments 150, 250, 350, 535 scaled to the soil extent)."""
    check_soil_radius(r_soil, r_out)
    base = [150.0, 250.0, 350.0, 535.0]
    scale = (r_soil - r_out) / sum(base)
    return [b * scale for b in base]


def check_soil_radius(r_soil, r_out=R_OUT):
    """The soil's outer radius must lie beyond the pipe's outer radius (the soil layers grow
    outwards from it; at or inside it the soil elements turn inside out)."""
    if not (math.isfinite(r_soil) and r_soil > r_out):
        raise ValueError(f"soil radius {r_soil:g} mm: the soil's outer radius must exceed the pipe's outer "
                         f"radius {r_out:g} mm")


def radius_text(r):
    """A radius for an NSET record (TOL=0.01): one decimal as the decks have always had it ('2000.0'),
    or the digits a radius off the 0.1 mm grid needs to select its nodes."""
    text = f"{r:.1f}"
    return text if float(text) == r else f"{r:.10g}"


def soil_radius_arg(text):
    """argparse type of the presets' --soil-radius (the thesis's pipe)."""
    try:
        value = float(text)
        check_soil_radius(value)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc) if "soil radius" in str(exc) else f"{text!r} is not a number")
    return value


def number_list(text):
    """'300,600,900' -> [300.0, 600.0, 900.0] (argparse type)."""
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a comma-separated list of numbers") from None
    if not values:
        raise argparse.ArgumentTypeError("empty list")
    return values


def attach_negative_lists(argv):
    """Glue a list that starts with a negative number to the option before it ('--nup',
    '-0.3,0.4' -> '--nup=-0.3,0.4'): argparse knows single negative numbers, but takes
    '-0.3,0.4' for an option and stops with "expected one argument"."""
    out = []
    for a in argv:
        if out and out[-1].startswith("--") and "=" not in out[-1] and re.fullmatch(r"-[0-9.][^,]*(,[^,]+)+", a):
            out[-1] += "=" + a
        else:
            out.append(a)
    return out


def default_steps(beta):
    """Stage-2 steps of model C off the thesis's four (beta, G_p): at least 250 and one step per
    0.27 / 500 deg of misalignment (the thesis's finest: 500 steps at 0.27 deg), rounded up to 50."""
    return max(250, 50 * math.ceil(500.0 * beta / 0.27 / 50.0 - 1e-9))


# ---------------------------------------------------------------- model B: one pipe in soil


def mesh_suffix(refine, element):
    """'' for the decks' mesh (hex8, refine 1), else e.g. '_hex20_r2' (deck and result names)."""
    return "" if (refine, element) == (1, "hex8") else f"_{element}_r{refine}"


def half_pipe_deck(kind, load, es, ks, kn, phi, psi, r_soil=R_SOIL, refine=1, element="hex8", pipe=None,
                   case="", soil_name="", refs=(), output="", writer="make_pipe_joint.py", total=1.0e6,
                   steps=None, nu_s=0.2, c=0.05, ground=None):
    """Model B's deck: kind S (elastic soil, bonded), F (interfaces pipe/soil) or P (Matsuoka
    soil), load E (edge) or D (diagonal), `total` (N) on each end of the half model. `refine`
    splits every element of the decks' mesh into refine^3 and `element` = 'hex20' uses 20-node
    hexahedra and 8-pair interfaces on that mesh (the mesh convergence study, docs/verification.md);
    'wedge6' and 'wedge15' cut each hexahedron into two wedges along its (r, theta) diagonal, so the
    faces at r = const (the interfaces) stay quadrilaterals and the pipe's ends become triangles;
    'tet4' and 'tet10' cut it into six tetrahedra around its (r, theta, z) diagonal (Kuhn's split:
    every shared face is cut along the same diagonal from both sides; tet10's mid-edge nodes are
    lattice nodes, as hex20's), kinds S and P only (their faces at r = const are triangles, which
    the interfaces of kind F do not take).
    refs: the thesis's values for the REPORT records (edge: (angle,), diagonal: (total, rigid))."""
    p, g = pipe or Pipe(packing=0.0), ground or Ground()
    if element not in ELEMENTS or refine < 1:
        raise ValueError(f"element {element!r}, refine {refine}: one of {', '.join(ELEMENTS)}, refine >= 1")
    ri, ro, L, x0 = p.r_in, p.r_out, p.length, p.scaled_x(220.0)
    interfaces = kind == "F"
    if interfaces and element.startswith("tet"):
        raise ValueError(f"element {element} has triangular faces at r = const: kind F's quadrilateral "
                         "interfaces do not fit them (use kind S or P, or a wedge)")
    quadratic = element in ("hex20", "wedge15", "tet10")
    wedges = element.startswith("wedge")
    m = refine * (2 if quadratic else 1)        # lattice intervals per interval of the decks' mesh
    step = 2 if quadratic else 1                # lattice intervals per element
    nr = 2 * m + 1 + 4 * m + (1 if interfaces else 0)   # nodes along r
    layer = nr * (27 * m + 1)                   # nodes in one z layer
    first_soil = 2 * m + 1 + (1 if interfaces else 0)   # r index + 1 of the soil's inner face
    suffix = mesh_suffix(refine, element)
    edge = load == "E"
    zg = "/".join(f"{d * p.zs:g}" for d in (50.0, 100.0, 150.0))
    title = {"S": "elastic soil", "F": "interfaces pipe/soil, elastic soil", "P": "Matsuoka soil"}[kind]
    out = [
        f"! feps deck: numerical model B (thesis chapter 5), case {case} ({title}, {soil_name} soil,",
        f"! {'edge' if edge else 'diagonal'} load). Written by scripts/{writer}.",
        f"! Half pipe (theta 0..180 deg, symmetry plane y = 0): r_i = {ri:g}, r_o = {ro:g}, length {L:g};",
        f"! soil from r = {ro:g} to {r_soil:.0f} mm in 4 element layers (the thesis gives no soil extent:",
        "! docs/verification.md shows the sensitivity). Mesh: hex8, 2 elements through the wall, theta",
        f"! 6 x 10, 6 x 7.5, 15 x 5 deg (finer on the loaded side, theta = 180), z graded {zg} mm",
        "! from each end.",
    ]
    if suffix:
        out += [f"! Mesh convergence study ({writer} --refine {refine} --element {element}): every element",
                f"! of that mesh split into {refine} x {refine} x {refine}"
                + (", 20-node hexahedra and 8-pair interfaces (unused face- and body-centre" if quadratic else "."),
                ] + (["! lattice nodes belong to no element and carry no unknowns)."] if quadratic else [])
    if not edge:
        # the diagonal problem is symmetric under (x, z) -> (-x, L - z); the mesh is not
        out += [f"! The diagonal load's lower end (x = {x0:g}..{ro:g}, theta 0..72 deg) lies on the 10 deg elements;",
                "! the two loaded corners are alike by symmetry, and in SD1 the largest most tensile stress",
                "! in the lower half of the pipe comes out 2.3% below that in the upper half (mesh)."]
    at_ro = f"their nodes coincide at r = {ro:g}."
    if interfaces and phi == psi == 15.0:
        out += [f"! Pipe and soil meet through quadrilateral interfaces (Ks = {ks:g}, Kn = {kn:g} MPa/mm,",
                f"! phi = psi = 15 deg, c = {c:g} MPa, thesis 5.4); {at_ro}"]
    elif interfaces:
        out += [f"! Pipe and soil meet through quadrilateral interfaces (Ks = {ks:g}, Kn = {kn:g} MPa/mm,",
                f"! phi = {phi:g}, psi = {psi:g} deg, c = {c:g} MPa; thesis 5.4: phi = psi = 15); their nodes",
                f"! coincide at r = {ro:g}."]
    elif kind == "P" and phi == psi == 15.0:
        out += [f"! Soil: modified Matsuoka-Nakai, phi = psi = 15 deg, c = {c:g} MPa (thesis 5.5), bonded to the pipe."]
    elif kind == "P":
        out += [f"! Soil: modified Matsuoka-Nakai, phi = {phi:g}, psi = {psi:g} deg, c = {c:g} MPa (thesis 5.5:",
                "! phi = psi = 15), bonded to the pipe."]
    else:
        out += [f"! Pipe and soil share their nodes at r = {ro:g} (bonded)."]
    params = f"PARAMETERS, kind={kind}, load={'edge' if edge else 'diagonal'}, E_s={es:g}"
    if kind != "S":
        params += f", phi={phi:g}, psi={psi:g}"
    out += [f"TITLE, Model B {case}: {title}, E_s = {es:g} MPa, {'edge' if edge else 'diagonal'} load "
            f"P = {total / 1000.0:g} kN",
            "! the case's parameters, written to the results file as /summary attributes parameter_<name>",
            params + p.parameters() + ("" if p.thesis and math.isclose(total, 1.0e6, rel_tol=1e-12) else
                                         f", q={total / (0.5 * math.pi * (ro ** 2 - ri ** 2)):.6g}"),
            "", "! --- nodes: r fastest, then theta (28), then z (25) ---"]

    def inc(v):
        text = f"{v / m:.10g}"
        return text if "." in text or "e" in text else text + "."

    def row(count, dr=0.0, dt=0.0, dz=0.0, comment="", soil=False):
        # the decks' soil layers are written to 4 decimals; a refined layer to 10 digits
        body = f"%, {count}, {f'{dr:.4f}' if soil and m == 1 else inc(dr)}, {inc(dt)}, {inc(dz)},"
        return f"{body:<29}! {comment}" if comment else body

    def first(n):                       # a new direction's node count, n nodes on the decks' mesh
        return (n - 1) * m + 1

    layers = soil_layers(r_soil, ro)
    out += [f"A, 3, {num(ri)}, 0., 0.,",
            row(first(3), dr=(ro - ri) / 2, comment=f"pipe wall: r = {ri:g}, {(ri + ro) / 2:g}, {ro:g}")]
    if interfaces:
        out.append(row(-1, comment=f"r = {ro:g} again: the soil's face (coincident nodes)"))
    out += [row(-m, dr=d, soil=True) for d in layers]
    out += [row(first(n + 1) if i == 0 else -n * m, dt=d, comment=text) for i, (n, d, text) in enumerate(B_THETA)]
    zpos = 0.0
    for i, (n, d) in enumerate(B_Z):
        zpos += n * d * p.zs
        out.append(row(first(n + 1) if i == 0 else -n * m, dz=d * p.zs,
                       comment=(f"z = 0 .. {zpos:g}" if i == 0 else f"z = {zpos:g}")))
    out.append("E,")

    def node(i, j, k, base=1):
        """Node number at lattice offsets (r, theta, z) from node `base`."""
        return base + i + j * nr + k * layer

    def solid(base):
        """The first element's nodes: hex8 corners (bottom face counter-clockwise, then the top),
        and for hex20 the mid-edges (bottom 1-2, 2-3, 3-4, 4-1, the top, then the verticals)."""
        s = step
        corners = [(0, 0, 0), (s, 0, 0), (s, s, 0), (0, s, 0)]
        nodes = [node(i, j, 0, base) for i, j, _ in corners] + [node(i, j, s, base) for i, j, _ in corners]
        if quadratic:
            mids = [(1, 0), (2, 1), (1, 2), (0, 1)]
            nodes += [node(i, j, 0, base) for i, j in mids] + [node(i, j, 2, base) for i, j in mids]
            nodes += [node(i, j, 1, base) for i, j, _ in corners]
        return nodes

    def wedge_pair(base):
        """The first cell's two wedges (C3D6 / C3D15 order), cut along the cell's (r, theta)
        diagonal: each base triangle counter-clockwise seen from above as hex8's bottom face,
        then its top; wedge15's mid-edges bottom 1-2, 2-3, 3-1, top, then the verticals."""
        s = step
        pair = []
        for tri in ([(0, 0), (s, 0), (s, s)], [(0, 0), (s, s), (0, s)]):
            nodes = [node(i, j, 0, base) for i, j in tri] + [node(i, j, s, base) for i, j in tri]
            if quadratic:
                mids = [((tri[a][0] + tri[b][0]) // 2, (tri[a][1] + tri[b][1]) // 2) for a, b in ((0, 1), (1, 2), (2, 0))]
                nodes += [node(i, j, 0, base) for i, j in mids] + [node(i, j, 2, base) for i, j in mids]
                nodes += [node(i, j, 1, base) for i, j in tri]
            pair.append(nodes)
        return pair

    def kuhn_tets(base):
        """The first cell's six tetrahedra (C3D4 / C3D10 order, positive volume) around its
        diagonal from lattice offset (0, 0, 0) to (step, step, step): one per order in which the
        path between them takes the three axes; tet10's mid-edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4."""
        tets = []
        for axes in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
            path = [(0, 0, 0)]
            for a in axes:
                path.append(tuple(v + (step if k == a else 0) for k, v in enumerate(path[-1])))
            a, b, c, d = path
            u, v, w = ([q[k] - a[k] for k in range(3)] for q in (b, c, d))
            if (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                    + u[2] * (v[0] * w[1] - v[1] * w[0])) < 0:
                b, c = c, b
            corners = [a, b, c, d]
            if quadratic:
                corners += [tuple((p[k] + q[k]) // 2 for k in range(3))
                            for p, q in ((a, b), (b, c), (c, a), (a, d), (b, d), (c, d))]
            tets.append([node(*q, base) for q in corners])
        return tets

    def element_block(nodes, copies):
        first_el = ", ".join(str(n) for n in nodes)
        k = len(nodes)
        return [f"A, {k}, {first_el},"] + [f"%, {n}, *, {k}, {inc}," for n, inc in copies if n] + ["E,"]

    def solid_blocks(base, copies):
        if element.startswith("tet"):
            return [line for nodes in kuhn_tets(base) for line in element_block(nodes, copies)]
        if not wedges:
            return element_block(solid(base), copies)
        return [line for nodes in wedge_pair(base) for line in element_block(nodes, copies)]

    around = [(27 * refine, step * nr), (24 * refine, step * layer)]
    out += ["", f"GROUP, pipe, TYPE={element}, MATERIAL=concrete"]
    out += solid_blocks(1, [(2 * refine, step)] + around)
    if g.water is None:
        out += ["", f"GROUP, soil, TYPE={element}, MATERIAL=soil"]
        out += solid_blocks(first_soil, [(4 * refine, step)] + around)
    else:
        # theta runs from 0 (x = +r, the top) to 180: each soil element layer's dry elements first
        radii = [ro + sum(layers[:i // refine]) + (i % refine) * layers[i // refine] / refine for i in range(4 * refine)]
        dry = g.dry_columns(radii + [r_soil], [d / refine for n, d, _ in B_THETA for _ in range(n * refine)])
        for wet in g.layers(dry, 27 * refine):
            out += ["", f"GROUP, soil{'_wet' if wet else ''}, TYPE={element}, MATERIAL=soil{'_wet' if wet else ''}"]
            for i, k in enumerate(dry):
                base, count = first_soil + i * step + (k * step * nr if wet else 0), 27 * refine - k if wet else k
                out += solid_blocks(base, [(count, step * nr), around[1]]) if count else []
    if interfaces:
        # lower layer: the pipe's outer face (theta then z: normal +r, towards the soil)
        o = 2 * m + 1
        corners = [(0, 0), (step, 0), (step, step), (0, step)]
        lo = [node(0, j, k, o) for j, k in corners]
        if quadratic:
            lo += [node(0, j, k, o) for j, k in [(1, 0), (2, 1), (1, 2), (0, 1)]]
        up = [n + 1 for n in lo]
        out += ["", "! lower layer = the pipe's outer face, upper = the soil's inner face",
                f"GROUP, contact, TYPE=interface-quad{8 if quadratic else 4}, MATERIAL=pipe_soil"]
        out += element_block(lo + up, around)
    out += ["E,", "", "MATERIAL, concrete, ELASTIC, E=40000., NU=0.2"]
    for wet in g.layers(dry, 27 * refine) if g.water is not None else (False,):
        name = "soil_wet" if wet else "soil"
        if kind == "P":
            out.append(f"MATERIAL, {name}, MATSUOKA, E={es:g}, NU={nu_s:g}, PHI={num(phi)}, PSI={num(psi)}, "
                       f"C={c:g}" + g.material(wet))
        else:
            out.append(f"MATERIAL, {name}, ELASTIC, E={es:g}, NU={nu_s:g}" + g.material(wet))
    if interfaces:
        out.append(f"MATERIAL, pipe_soil, INTERFACE, KN={kn:g}, KS={ks:g}, PHI={num(phi)}, PSI={num(psi)}, C={c:g}")
    rsoil = radius_text(r_soil)
    out += ["", "! --- supports ---",
            f"NSET, soil_outer, CSYS=3, R={rsoil}, TOL=0.01",
            "NSET, symmetry, CSYS=2, Y=0., TOL=0.01",
            "! The end loads are self-equilibrated in z: one soil node on the mid-plane holds the free",
            "! z translation (its reaction comes out zero).",
            f"NSET, anchor, CSYS=3, R={rsoil}, THETA=0., Z={num(L / 2)}, TOL=0.01",
            "FIX, soil_outer, X, Y", "FIX, symmetry, Y", "FIX, anchor, Z"] + g.rollers(p, r_soil, (0.0, L)) + ["",
            f"! --- loads: P = {total / 1000.0:g} kN on each end of the half model, linear in x from zero at {x0:g} mm",
            "! from the axis to its peak at the outer edge (SPEC section 8; thesis Fig. 5.2) ---",
            "FSET, end_low, GROUP=pipe, CSYS=2, Z=0., TOL=0.01",
            f"FSET, end_high, GROUP=pipe, CSYS=2, Z={num(L)}, TOL=0.01",
            f"PRESSURE, end_high, TOTAL={sci(total)}, VARY=X, ZERO=-{num(x0)}, PEAK=-{num(ro)}"]
    if edge:
        out.append(f"PRESSURE, end_low, TOTAL={sci(total)}, VARY=X, ZERO=-{num(x0)}, PEAK=-{num(ro)}")
    else:
        out.append("! diagonal: the lower end's load is the upper one's rotated by 180 deg about the axis")
        out.append(f"PRESSURE, end_low, TOTAL={sci(total)}, VARY=X, ZERO={num(x0)}, PEAK={num(ro)}")
    steps = steps or (400 if edge else 500)
    stage = "STAGE, load, STEPS=" + (f"1" if kind == "S" else f"{steps}, METHOD=initial-stiffness, MAXIT=10, "
                                     "DELTA1=1e-4") + (", LOAD=1" if g.gamma is not None else "")
    out += [""] + g.stage() + ([""] if g.gamma is not None else [])
    if kind == "F" and not edge:
        # docs/verification.md, "The diagonal model B cases with interfaces": the tension side of
        # the interface unzips at 17% of the load (brittle tension cut-off); the thesis's methods
        # do not converge through it (full Newton does, given 75-108 iterations), and the thesis carries the
        # unbalanced force (2.6.3).
        out += ["! initial stiffness, at most 10 iterations per step (thesis 5.4, 5.5). At 17% of the load",
                "! the tension side of the interface unzips (each point that reaches the apex of the",
                "! Mohr-Coulomb cone drops c / tan phi = 0.19 MPa at once) and the unbalanced force reaches",
                "! 5-15% of |P|; as in the thesis (2.6.3) it is carried into the next steps and decays",
                "! (1-4% at the end). DIVERGENCE=1 (feps's default 1e-2 is not in the thesis) lets it be",
                "! carried; docs/verification.md shows the residual history and the sensitivity, and the",
                "! converged answers (METHOD=full-newton-raphson, MAXIT=400: 6-21% larger angles).",
                stage + ", DIVERGENCE=1"]
    elif kind == "F":
        # docs/verification.md, "Model B": with the stiff soil (FE3) the sliding interface leaves
        # about 1e-2 of |P| unbalanced after 10 initial-stiffness iterations from 30% of the load,
        # right at feps's default DIVERGENCE; the thesis carries it (2.6.3).
        out += ["! initial stiffness, at most 10 iterations per step (thesis 5.4, 5.5). Where the interface",
                "! slides the 10 iterations leave an unbalanced force (FE3, stiff soil: about 1e-2 of |P| from",
                "! 30% of the load, 2.6e-2 at the end); as in the thesis (2.6.3) it is carried into the next",
                "! steps. DIVERGENCE=1 (feps's default 1e-2 is not in the thesis) lets it be carried;",
                "! docs/verification.md compares with the converged full Newton-Raphson answer.",
                stage + ", DIVERGENCE=1"]
    elif kind == "P":
        out += ["! initial stiffness, at most 10 iterations per step (thesis 5.4, 5.5)", stage]
    else:
        out += [stage]
    rot = f"REPORT, ROTATION, NAME=deflection, GROUP=pipe, R={num(ro)}, Z={num(L)}"
    region = f", FROM=-{num(x0)}, TO=-{num(ro)}"
    ref = [f", REFERENCE={v}" for v in refs] + ["", ""]
    out += ["", "! --- post-processing (thesis 7.3): the deflection angle at the pipe end is the slope of the",
            f"! axial displacement w along r = {ro:g} over the loaded region (x from -{x0:g} to -{ro:g}), the slope",
            "! the Australian model's linear compression has (thesis 7.4.2: 'as discussed in Section 7.3,",
            "! the actual misalignment angle ... can be obtained from the total deformation in the high",
            "! compression region (loaded region)'), for the edge and the diagonal load alike. The rigid",
            "! rotation (diagonal load) is the tilt of the pipe's axis between its ends (the mean ux of the",
            "! end sections): the rigid-body rotation of the pipe in the soil. The slope over the whole",
            "! diameter and the mid-length section's rotation (which adds the pipe's shear deformation)",
            "! are reported beside them; docs/verification.md compares all four with Table 7.2 ---"]
    if kind == "F" and not edge:
        out += [rot + region + ref[0], f"REPORT, TILT, NAME=rigid, GROUP=pipe, FROM=0., TO={num(L)}" + ref[1],
                f"REPORT, ROTATION, NAME=deflection_diameter, GROUP=pipe, R={num(ro)}, Z={num(L)}",
                f"REPORT, ROTATION, NAME=rigid_section, GROUP=pipe, R={num(ro)}, Z={num(L / 2)}"]
    else:
        out.append(rot + (region + (ref[0] if kind == "F" else "") if edge else ""))
    out += ["! the anchor's z reaction: zero, as the self-equilibrated end loads require (SPEC 8); its x and",
            "! y reactions are those of the soil's outer support at that node",
            "REPORT, REACTION, NAME=anchor, NSET=anchor"]
    out += ["", "SOLVER, cholmod", f"OUTPUT, {output or case + suffix}.h5", ""]
    return "\n".join(out)


# ---------------------------------------------------------------- model C: two pipes and the packing


def theta_steps(theta_step=THETA_STEP):
    """Element sizes (deg) from theta = 0 to 180: 4 x 3 at the loaded edge, then theta_step."""
    n = round(168.0 / theta_step)
    if abs(n * theta_step - 168.0) > 1e-9:
        raise ValueError("the theta step must divide 168 deg")
    return THETA_EDGE + [theta_step] * n


def runs(steps):
    """Collapse equal consecutive increments into (count, increment)."""
    out = []
    for d in steps:
        if out and abs(out[-1][1] - d) < 1e-12:
            out[-1][0] += 1
        else:
            out.append([1, d])
    return out


def direction(steps, axis, label, first=True, start=0.0):
    """DATAIN % records for one direction with increments `steps` along `axis` (0 r, 1 theta, 2 z)
    from coordinate `start`; the first record opens the direction (n = count + 1), the others
    continue it (n < 0)."""
    lines, pos = [], start
    for i, (count, d) in enumerate(runs(steps)):
        inc = [0.0, 0.0, 0.0]
        inc[axis] = d
        pos += count * d
        n = count + 1 if (i == 0 and first) else -count
        lines.append(f"%, {n}, {inc[0]:g}, {inc[1]:g}, {inc[2]:g},".ljust(30) + f"! {label} to {pos:g}")
    return lines


def split(steps, k):
    """Each increment of `steps` cut into k equal ones (the mesh refined k times along it)."""
    return [d / k for d in steps for _ in range(k)]


class Mesh:
    """Node numbering of model C's two DATAIN node blocks (theta fastest, then r, then z in each);
    `wall` elements through the pipe wall, every z increment cut into `z_refine`. A full ring
    (`full`: the thetas sum to 360) has no node row at 360 deg: its last elements close on the first row.
    With `soil_top` the top block has the soil's radii too (its soil nodes at the joint plane, iz = 0,
    belong to no element: the soil above takes the bottom block's there, one continuous ground).
    With `interface` each block has a second node row at r = r_o, the soil's inner face (coincident
    with the pipe's outer face, joined to it by interface elements): the soil's rows start at
    `soil_first`."""

    def __init__(self, pipe, r_soil, thetas, wall=WALL_ELEMENTS, z_refine=1, full=False, soil_top=False,
                 interface=False):
        self.full = full
        self.nt = len(thetas) + (0 if full else 1)         # nodes along theta
        self.r_bottom = [pipe.r_in + (pipe.r_out - pipe.r_in) * i / wall for i in range(wall + 1)]
        self.r_bottom += [pipe.r_out] if interface else []
        self.soil_first = len(self.r_bottom) - 1
        for d in soil_layers(r_soil, pipe.r_out):
            self.r_bottom.append(self.r_bottom[-1] + d)
        self.nr_bottom = len(self.r_bottom)                # 7 with 2 wall elements
        self.z_bottom = split([d * pipe.zs for d in Z_BOTTOM_STEPS], z_refine)
        self.z_top = split([d * pipe.zs for d in Z_TOP_STEPS], z_refine)
        self.packing_layers = PACKING_LAYERS * z_refine
        self.nz_bottom = len(self.z_bottom) + 1            # 20 unrefined
        self.nr_top = self.nr_bottom if soil_top else wall + 1
        self.nz_top = self.packing_layers + len(self.z_top) + 1
        self.bottom_nodes = self.nt * self.nr_bottom * self.nz_bottom

    def bottom(self, it, ir, iz):
        return 1 + it % self.nt + self.nt * (ir + self.nr_bottom * iz)

    def top(self, it, ir, iz):
        """Top block: iz = 0 is the packing's lower face, packing_layers its upper face."""
        return self.bottom_nodes + 1 + it % self.nt + self.nt * (ir + self.nr_top * iz)

    def columns(self, its):
        """The theta element indices `its` (ascending) as runs (first, count) that one DATAIN element
        block copies along theta by +1 node: a run ends before a full ring's closing element, which
        takes its nodes from the first row and so is a block of its own."""
        out = []
        for it in its:
            if out and out[-1][0] + out[-1][1] == it and not (self.full and it == self.nt - 1):
                out[-1][1] += 1
            else:
                out.append([it, 1])
        return [tuple(r) for r in out]


def hex_record(node, it, ir, iz):
    """hex8 with its bottom face counter-clockwise seen from +z: (r, t), (r+1, t), (r+1, t+1), (r, t+1)."""
    face = [node(it, ir, iz), node(it, ir + 1, iz), node(it + 1, ir + 1, iz), node(it + 1, ir, iz)]
    top = [node(it, ir, iz + 1), node(it, ir + 1, iz + 1), node(it + 1, ir + 1, iz + 1), node(it + 1, ir, iz + 1)]
    return "A, 8, " + ", ".join(str(n) for n in face + top) + ","


def joint_deck(G, nu, beta, r_soil=R_SOIL, steps=None, theta_step=THETA_STEP, soil_E=144.0, wall=WALL_ELEMENTS,
               z_refine=1, psi=PSI_JOINT, name="", reference=None, writer="make_pipe_joint.py", pipe=None, q=Q,
               joint=(KN_JOINT, KS_JOINT, PHI_JOINT, C_JOINT), soil=(0.2, None, None, None), ground=None,
               design=False, rotation=0.0, full=False, soil_top=False, capacity=None, concrete=None,
               pipe_soil=None):
    """Model C's deck: packing G_p, nu_p, misalignment beta (deg); theta_step the element size (deg)
    beyond theta = 12, wall the elements through the pipe wall, z_refine the number of parts each z
    element is cut into, psi the joint interface's dilation angle (deg), joint its (Kn, Ks, phi, c),
    soil its (nu, phi, psi, c) (phi None: elastic, else Matsuoka), reference the thesis's beta_bar.
    rotation (deg): the direction in the cross-section towards which the top pipe is displaced, where
    the joint closes (0: +x, the edge misalignment; 45: the diagonal one), the mesh turned with it;
    full: the whole ring (theta rotation-180..rotation+180, mirrored about the plane of deflection)
    instead of the quarter model's half ring (theta rotation..rotation+180: the plane of deflection
    a symmetry plane, held normal to itself in a Cartesian system turned by `rotation`; without the
    ground's weight only, whose gravity along -x it would break). soil_top: the soil's layers round
    the top pipe and the packing too, one ground with the bottom pipe's (thesis 6.2: round the bottom
    pipe only). capacity (seat fraction, seat steps): the capacity staging instead of the thesis's
    (`capacity_stages`); concrete (FT, FC, GF): the pipes of cracking CONCRETE instead of elastic;
    pipe_soil (Kn, Ks, phi, psi, c): Mohr-Coulomb interfaces between the pipes (and the packing) and
    the soil round them instead of shared nodes."""
    p, g = pipe or Pipe(), ground or Ground()
    kn, ks, phi_j, c_j = joint
    nu_s, phi_s, psi_s, c_s = soil
    if rotation != 0.0 and not full and g.gamma is not None:
        raise ValueError("gravity along -x breaks the symmetry about a plane of deflection off the x axis: "
                         "a diagonal misalignment with the ground's weight needs the full ring")
    thetas = theta_steps(theta_step)
    if full:
        thetas = thetas + thetas[::-1]          # mirrored: the same elements on either side of the edge
    m = Mesh(p, r_soil, thetas, wall, z_refine, full, soil_top, pipe_soil is not None)
    s0 = m.soil_first
    ri, ro, L, a = p.r_in, p.r_out, p.length, p.packing
    z_joint, z_top = L / 2, L / 2 + a
    delta = L * math.tan(math.radians(beta))
    E_p = 2.0 * G * (1.0 + nu)
    ntheta, nzb, nzt, npl = len(thetas), len(m.z_bottom), len(m.z_top), m.packing_layers
    stride_r_b, stride_z_b = m.nt, m.nt * m.nr_bottom
    stride_r_t, stride_z_t = m.nt, m.nt * m.nr_top
    x_from = p.scaled_x(250.0)
    soil_law = ("all elastic." if phi_s is None else f"Matsuoka-Nakai phi = {phi_s:g}, psi = {psi_s:g}, c = {c_s:g}.") \
        if concrete is None else ("pipes of CONCRETE (below), the rest elastic." if phi_s is None else
                                  f"pipes of CONCRETE (below); soil phi = {phi_s:g}, psi = {psi_s:g}, c = {c_s:g}.")
    out = [
        f"! feps deck: numerical model C (thesis chapter 6), case {name}: packing G_p = {G:g} MPa,",
        f"! nu_p = {nu:g} (E_p = 2 G_p (1 + nu_p) = {E_p:g} MPa), misalignment beta = {beta:g} deg",
        f"! (delta = L tan(beta) = {delta:.3f} mm, L = {L:g}). Written by scripts/{writer}.",
        "!",
    ] + ([
        "! Quarter model (theta 0..180, y >= 0; z >= 0) of the symmetric three-pipe system (thesis 6.2,",
        "! Fig. 6.2; SPEC section 8):"] if not full and rotation == 0.0 else [
        f"! Quarter model (theta {rotation:g}..{rotation + 180:g}: the plane of deflection a symmetry plane; z >= 0) of the",
        "! symmetric three-pipe system (thesis 6.2, Fig. 6.2; SPEC section 8), the misalignment in the direction",
        f"! theta = {rotation:g} deg:"] if not full else [
        f"! Half model (z >= 0; the whole ring, theta {rotation:g}..{rotation + 360:g}) of the symmetric three-pipe",
        "! system (thesis 6.2, Fig. 6.2; SPEC section 8), the misalignment in the direction theta = "
        f"{rotation:g} deg:"]) + [
        f"! - bottom: {'pipe' if full else 'half pipe'} r = {ri:g}..{ro:g}, z = 0..{z_joint:g} (z = 0 is the mid-length symmetry plane, fixed in",
        f"!   z), in soil r = {ro:g}..{r_soil:g} over the same z (4 hex8 layers as model B; the thesis gives no soil",
    ] + ([
        "!   extent). Pipe and soil are BONDED (shared nodes): thesis 6.2 says there was just one interface",
        "!   in the model, the one between the packing and the bottom pipe, and 6.3 calls stage 1 linear."]
        if pipe_soil is None else [
        "!   extent). Pipe and soil meet through Mohr-Coulomb interfaces (--interface frictional; thesis 6.2",
        "!   bonds them): Kn = {:g}, Ks = {:g} MPa/mm, phi = {:g}, psi = {:g} deg, c = {:g} MPa.".format(*pipe_soil)]) + [
        f"! - packing: {a:g} mm thick" + (" (SPEC 8: derived from Table 7.4's Australian columns)" if a == PACKING
                                          else "") + f", z = {z_joint:g}..{z_top:g},",
        f"!   r = {ri:g}..{ro:g}, {npl} hex8 layers, bonded to the top pipe (shared nodes at z = {z_top:g}).",
        "! - one layer of interface-quad4 between the bottom pipe's end face (lower layer, normal +z) and the",
        f"!   packing (upper layer): coincident nodes at z = {z_joint:g} (two node blocks: the bottom one ends at",
        f"!   z = {z_joint:g}, the top one starts there). Kn = {kn:g}, Ks = {ks:g} MPa/mm, " +
        (f"phi = psi = {phi_j:g} deg, c = {c_j:g} MPa." if psi == phi_j else
         f"phi = {phi_j:g}, psi = {psi:g} deg (thesis 6.2: 20), c = {c_j:g} MPa."),
    ] + ([
        f"! - top pipe: full length {L:g} (z = {z_top:g}..{z_top + L:g}), NOT in soil: thesis 6.2 has soil only around the",
        "!   bottom half pipe ('a half pipe with its surrounding soil at the bottom, a complete pipe on the",
    ] + ([
        "!   top'). Its only supports are the joint, the symmetry plane y = 0 and the prescribed x",
        "!   displacement of its upper end."] if not full and rotation == 0.0 else [
        "!   top'). Its only supports are the joint" + ("" if full else ", the symmetry plane")
        + " and the prescribed displacement of its upper end."]) if not soil_top else [
        f"! - top pipe: full length {L:g} (z = {z_top:g}..{z_top + L:g}), in soil as the bottom pipe (--soil-around-top; thesis",
        f"!   6.2 has soil round the bottom pipe only): the same 4 layers from z = {z_joint:g} to {z_top + L:g}, "
        + ("bonded to the" if pipe_soil is None else "through the"),
        ("!   packing and the top pipe" if pipe_soil is None else "!   same interfaces on the packing and the top pipe")
        + f", one ground with the bottom's (its nodes at z = {z_joint:g}; the packing's lower",
        "!   outer edge, on the interface, is not the soil's)."]) + [
        f"! - concrete E = 40000, nu = 0.2; soil E = {soil_E:g}, nu = {nu_s:g} (thesis 6.1{'' if soil_E == 144.0 else ': E = 144'}); "
        + soil_law,
    ] + ([
        "! - supports (thesis 6.2): soil outer surface fixed in x and y; z = 0 fixed in z; y = 0 fixed in y.",
        f"! - loads: q = {q:.10g} MPa uniform on the top end; delta in x on every node of the top end (thesis 6.2:",
        "!   'an equivalent displacement delta in x direction at the upper end'); the end's y and z are free."]
        if not full and rotation == 0.0 else [
        f"! - supports: soil outer surface fixed in x and y; z = 0 fixed in z; the plane theta = {rotation:g}/{rotation + 180:g}",
        "!   fixed normal to itself (y of system 4, in which every support is held).",
        f"! - loads: q = {q:.10g} MPa uniform on the top end; delta along theta = {rotation:g} deg on every node of the",
        "!   top end (thesis 6.2: 'an equivalent displacement delta ... at the upper end'); free in z."]
        if not full else [
        "! - supports (thesis 6.2): soil outer surface fixed in x and y; z = 0 fixed in z.",
        f"! - loads: q = {q:.10g} MPa uniform on the top end; delta along theta = {rotation:g} deg on every node of the",
        "!   top end (thesis 6.2: 'an equivalent displacement delta ... at the upper end'); free across it and in z."]) + ([
        "!   Stage 1: 20% of q in 1 step, the end held at ux = 0 ('without rotation'); stage 2: the other 80%",
        f"!   and delta together in {steps} steps (thesis 6.3/6.4), initial stiffness, at most 10 iterations;",
        "!   stage 3: equilibrium iterations (see the solution controls below).",
    ] if capacity is None else [
        f"!   Stage seat: {capacity[0]:g} of q and delta together in {capacity[1]} steps; stage jack: the rest of q in",
        f"!   {steps} steps, delta held; full Newton-Raphson (--capacity: see the solution controls below).",
    ]) + ([
        f"! - mesh: hex8, {wall} elements through the wall; theta 4 x 3 deg at the loaded edge (theta = {rotation:g},",
        (f"!   x = +{ro:g}: sigma_max comes from the elements with theta < 6 deg, thesis 7.4.3), then " if rotation == 0.0
         else "!   the misalignment's direction: sigma_max comes from the elements within 6 deg of it), then ")
        + f"{len(thetas) - 4} x {thetas[-1]:g} deg;"] if not full else [
        f"! - mesh: hex8, {wall} elements through the wall; theta 4 x 3 deg from the loaded edge (theta = {rotation:g};",
        f"!   sigma_max comes from the elements within 6 deg of it, thesis 7.4.3), then {len(thetas) // 2 - 4} x "
        f"{thetas[len(thetas) // 2 - 1]:g} deg",
        "!   to the opposite side, and the same mirrored back;"]) + [
        "!   z graded " + "/".join(f"{d * p.zs:g}" for d in (150.0, 100.0, 50.0, 25.0, 12.5))
        + " mm towards the joint on both sides" + ("" if z_refine == 1 else f", each cut into {z_refine}")
        + f"; a node layer at z = {z_top + L / 2:g}, the",
        "!   top pipe's mid-length section A-A of thesis Fig. 7.7.",
    ] + ([
        f"! The misalignment rotation is about +y: the joint closes at x = +{ro:g} (theta = 0) and may open",
        f"! towards x = -{ro:g} (theta = 180), as thesis Figs. 6.4 and 6.11."] if rotation == 0.0 else [
        f"! The misalignment rotation is about the axis at theta = {rotation + 90:g} deg in the cross-section: the",
        f"! joint closes at theta = {rotation:g} and may open towards theta = {rotation + 180:g}; the mesh is the edge",
        f"! case's {'full' if full else 'quarter'} mesh turned by {rotation:g} deg (make_pipe_joint.py --misalignment diagonal)."]) + [
        f"TITLE, Model C {name}: packing G_p = {G:g}, nu_p = {nu:g}, beta = {beta:g} deg, q = {q:.10g} MPa",
        "! the case's parameters, written to the results file as /summary attributes parameter_<name>",
        f"PARAMETERS, G_p={G:g}, nu_p={nu:g}, beta={beta:g}, E_s={soil_E:g}" +
        ("" if psi == PSI_JOINT else f", psi_joint={psi:g}") + p.parameters()
        + ("" if not full and rotation == 0.0 else
           f", misalignment={'edge' if rotation == 0.0 else 'diagonal'}, ring={'full' if full else 'half'}")
        + (", soil=both_pipes" if soil_top else "") + ("" if pipe_soil is None else ", soil_interface=frictional")
        + ("" if math.isclose(q, Q, rel_tol=1e-12) else f", q={q:.6g}") + ("" if kn == KN_JOINT else f", Kn={kn:g}"),
        "",
        "! --- node block 1: bottom pipe and soil (theta fastest, then r, then z) ---",
        f"A, 3, {num(ri)}, {num(rotation)}, 0.,",
    ]
    # 12 digits: a wall of 3 elements must still end on r = 715 (38.3333 x 3 would not)
    wall_record = f"%, {wall + 1}, {(ro - ri) / wall:.12g}, 0., 0.,".ljust(30) + \
        "! pipe wall r = " + ", ".join(f"{r:g}" for r in m.r_bottom[:wall + 1])
    out += direction(thetas[:m.nt - 1], 1, "theta", start=rotation)
    out.append(wall_record)
    coincident = f"%, -1, 0., 0., 0.,".ljust(30) + f"! r = {ro:g} again: the soil's inner face (coincident nodes)"
    out += [coincident] if pipe_soil is not None else []
    for d in soil_layers(r_soil, ro):
        out.append(f"%, -1, {d:.4f}, 0., 0.,".ljust(30) + "! soil layer")
    out += direction(m.z_bottom, 2, "z")
    out += ["E,", "",
            f"! --- node block 2: the packing's lower face at z = {z_joint:g} (coincident with the bottom pipe's",
            "! end face: the interface's two layers), the packing and the top pipe ---",
            f"A, 3, {num(ri)}, {num(rotation)}, {num(z_joint)},"]
    out += direction(thetas[:m.nt - 1], 1, "theta", start=rotation)
    out.append(wall_record)
    out += [coincident] if pipe_soil is not None and soil_top else []
    for d in soil_layers(r_soil, ro) if soil_top else []:
        out.append(f"%, -1, {d:.4f}, 0., 0.,".ljust(30) + "! soil layer round the top pipe")
    out += direction([a / npl] * npl, 2, "z (packing)", start=z_joint)
    out += direction(m.z_top, 2, "z", first=False, start=z_top)
    out += ["E,", ""]

    def blocks(node, its, ir, iz, copies):
        """hex8 element blocks of the theta elements `its` from (ir, iz), each run of them copied along
        theta and then by `copies` ((count, node increment), ...)."""
        return [line for it, count in m.columns(its)
                for line in [hex_record(node, it, ir, iz), f"%, {count}, *, 8, 1,"]
                + [f"%, {n}, *, 8, {inc}," for n, inc in copies] + ["E,"]]

    every = range(ntheta)
    soil_groups = []
    flags = g.dry_flags(m.r_bottom[s0:], thetas, rotation)
    dry = [sum(layer) for layer in flags]
    # the soil's z regions (node numbering, first layer, layers, z stride): round the bottom pipe, and
    # with soil_top a layer from the joint plane (its lower face the bottom block's nodes: one ground)
    # and the rest round the packing and the top pipe
    regions = [(m.bottom, 0, nzb, stride_z_b)] + ([
        (lambda it, ir, iz: m.bottom(it, ir, nzb) if iz == 0 else m.top(it, ir, 1), 0, 1, 0),
        (m.top, 1, npl + nzt - 1, stride_z_t)] if soil_top else [])
    for wet in g.layers(dry, ntheta):
        soil_groups += [f"GROUP, soil{'_wet' if wet else ''}, TYPE=hex8, MATERIAL=soil{'_wet' if wet else ''}"]
        for node, iz, nz, stride_z in regions:
            along_z = [(nz, stride_z)] if nz > 1 else []
            if g.water is None:
                soil_groups += blocks(node, every, s0, iz, [(m.nr_bottom - s0 - 1, stride_r_b)] + along_z)
            for i, layer in enumerate(flags if g.water is not None else []):
                soil_groups += blocks(node, [it for it in every if layer[it] != wet], s0 + i, iz, along_z)
        soil_groups.append("")
    out += ["GROUP, bottom_pipe, TYPE=hex8, MATERIAL=concrete"]
    out += blocks(m.bottom, every, 0, 0, [(wall, stride_r_b), (nzb, stride_z_b)]) + [""]
    out += soil_groups
    out += ["GROUP, packing, TYPE=hex8, MATERIAL=packing"]
    out += blocks(m.top, every, 0, 0, [(wall, stride_r_t), (npl, stride_z_t)]) + [""]
    out += ["GROUP, top_pipe, TYPE=hex8, MATERIAL=concrete"]
    out += blocks(m.top, every, 0, npl, [(wall, stride_r_t), (nzt, stride_z_t)]) + [""]

    def joint_block(it, count):
        lo = [m.bottom(it, 0, nzb), m.bottom(it, 1, nzb), m.bottom(it + 1, 1, nzb), m.bottom(it + 1, 0, nzb)]
        up = [m.top(it, 0, 0), m.top(it, 1, 0), m.top(it + 1, 1, 0), m.top(it + 1, 0, 0)]
        return ["A, 8, " + ", ".join(str(n) for n in lo + up) + ",", f"%, {count}, *, 8, 1,", f"%, {wall}, *, 8, {m.nt},",
                "E,"]

    def soil_material(wet):
        law = (f"ELASTIC, E={soil_E:g}{'.' if float(soil_E).is_integer() else ''}, NU={nu_s:g}" if phi_s is None else
               f"MATSUOKA, E={soil_E:g}, NU={nu_s:g}, PHI={num(phi_s)}, PSI={num(psi_s)}, C={c_s:g}")
        return f"MATERIAL, soil{'_wet' if wet else ''}, {law}" + g.material(wet)

    out += ["! lower layer = the bottom pipe's end face (counter-clockwise seen from +z: e1 along r, e2 along",
            "! theta, normal +z), upper layer = the packing's lower face; theta strides agree in both blocks",
            "GROUP, joint, TYPE=interface-quad4, MATERIAL=pipe_packing"]
    out += [line for it, count in m.columns(every) for line in joint_block(it, count)]
    out += ["E,", ""]

    def pipe_soil_blocks(lower, upper, iz, copies):
        """interface-quad4 blocks on r = r_o from layer iz: lower layer the pipe's (or the packing's)
        outer face (theta then z: normal +r, towards the soil), upper the soil's inner face."""
        def face(node, ir, it):
            return [node(it, ir, iz), node(it + 1, ir, iz), node(it + 1, ir, iz + 1), node(it, ir, iz + 1)]
        return [line for it, count in m.columns(every)
                for line in ["A, 8, " + ", ".join(str(n) for n in face(lower, wall, it) + face(upper, s0, it)) + ",",
                             f"%, {count}, *, 8, 1,"] + [f"%, {n}, *, 8, {inc}," for n, inc in copies] + ["E,"]]

    if pipe_soil is not None:
        out += ["! pipe/soil interfaces: lower layer the pipe's (and the packing's) outer face, upper the soil's",
                "GROUP, pipe_soil, TYPE=interface-quad4, MATERIAL=pipe_soil"]
        out += pipe_soil_blocks(m.bottom, m.bottom, 0, [(nzb, stride_z_b)])
        if soil_top:
            # the layer from the joint plane: the soil's lower face is the bottom block's (one ground)
            out += pipe_soil_blocks(m.top, lambda it, ir, iz: m.bottom(it, ir, nzb) if iz == 0 else m.top(it, ir, iz),
                                    0, [])
            out += pipe_soil_blocks(m.top, m.top, 1, [(npl + nzt - 1, stride_z_t)])
        out += ["E,", ""]
    out += [
            "MATERIAL, concrete, ELASTIC, E=40000., NU=0.2" if concrete is None else
            "MATERIAL, concrete, CONCRETE, E=40000., NU=0.2, FT={:g}, FC={:g}, GF={:g}, PHI={:g}, PSI={:g}".format(
                *concrete, CONCRETE_PHI, CONCRETE_PHI)]
    out += [soil_material(wet) for wet in g.layers(dry, ntheta)]
    out += [f"MATERIAL, packing, ELASTIC, G={G:g}, NU={nu:g}",
            f"MATERIAL, pipe_packing, INTERFACE, KN={num(kn)}, KS={num(ks)}, PHI={num(phi_j)}, "
            f"PSI={psi:g}{'.' if float(psi).is_integer() else ''}, C={c_j:g}"] + ([] if pipe_soil is None else [
            "MATERIAL, pipe_soil, INTERFACE, KN={:g}, KS={:g}, PHI={}, PSI={}, C={:g}".format(
                pipe_soil[0], pipe_soil[1], num(pipe_soil[2]), num(pipe_soil[3]), pipe_soil[4])]) + [
            "",
            "! --- supports (thesis 6.2) ---"] + ([] if rotation == 0.0 else [
            f"! system 4: x along the misalignment's direction theta = {rotation:g}, y across it",
            f"CSYS, 4, CARTESIAN, 0., 0., 0., {math.cos(math.radians(rotation)):.16g}, "
            f"{math.sin(math.radians(rotation)):.16g}, 0., {-math.sin(math.radians(rotation)):.16g}, "
            f"{math.cos(math.radians(rotation)):.16g}, 0."]) + [
            f"NSET, soil_outer, CSYS=3, R={radius_text(r_soil)}, TOL=0.01"]
    # the plane of deflection as a symmetry plane: y = 0, or (diagonal half model) y = 0 of system 4, held
    # normal to itself in that nodal system (every support then in it: a node has one nodal system)
    turned = "" if rotation == 0.0 or full else ", CSYS=4"
    out += [] if full else ["NSET, symmetry_y, CSYS=2, Y=0., TOL=0.01" if not turned else
                            "NSET, symmetry_plane, CSYS=4, Y=0., TOL=0.01"]
    out += ["NSET, symmetry_z, CSYS=2, Z=0., TOL=0.01",
            f"FIX, soil_outer, X, Y{turned}"] + ([] if full else [f"FIX, symmetry_{'plane' if turned else 'y'}, Y{turned}"]) \
        + [f"FIX, symmetry_z, Z{turned}"] + g.rollers(p, r_soil, (z_top + L if soil_top else z_joint,))
    out += ["", f"! --- loads: q = {q:.10g} MPa on the top end (reference load, applied 20% + 80% by the stages) ---",
            f"FSET, top_end, GROUP=top_pipe, CSYS=2, Z={num(z_top + L)}, TOL=0.01",
            f"NSET, top_end_nodes, CSYS={f'3, R={num(ri)}:{num(ro)}' if soil_top else 2}, Z={num(z_top + L)}, TOL=0.01"
            + (", GROUP=top_pipe" if soil_top and pipe_soil is not None else ""),
            f"PRESSURE, top_end, VALUE={q:.10g}", ""]
    if capacity is not None:
        out += ["! --- solution (--capacity): full Newton-Raphson with the line search, every step converged to",
                "! 1e-6 or cut back; a step that does not converge after the cut-backs stops the run ---",
                # the line search: with frictional pipe/soil interfaces full Newton cuts back without
                # end without it; with the joint's alone it ends where it would without it (to 4e-4
                # of a stage), 2.5 times faster (docs/verification.md, capacity curves)
                "CONTROLS, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-6, LINESEARCH=energy"] + g.stage()
        out += capacity_stages(capacity, steps, delta, rotation)
    else:
        out += [
            "! --- solution (thesis 6.3/6.4: initial stiffness, 'several iterations within each step",
            "! depending on convergence and controlled by the program'; no tolerance given: DELTA1 = 1e-4",
            "! as model B). Once the joint slides and a gap opens (beta = 0.27 from stage-2 step ~35) the",
            "! initial stiffness converges at ~0.95 per iteration (Kn, Ks of the interface are "
            f"{kn * a / E_p:.2g} and {ks * a / G:.2g} x",
            "! this packing layer's E_p/a, G_p/a, and the elastic matrix keeps them at sliding and open points):",
            "! 10 iterations leave up to ~5% of |P| unbalanced, which feps's default DIVERGENCE = 1e-2 turns",
            "! into endless cut-backs. DIVERGENCE = 0.1 lets each step carry its unbalanced force into the",
            "! next (eq. 2.6.4), as the thesis's program did; stage s3 then applies nothing and iterates",
            "! (up to 50 per step) until |R|/|P| < 1e-4, so the final state is in equilibrium. The HDF5",
            "! keeps the end of s2 (step s2_last) and of s3 (final). ---",
            "CONTROLS, METHOD=initial-stiffness, MAXIT=10, DELTA1=1e-4, DIVERGENCE=0.1"] + g.stage()
        out += thesis_stages(steps, delta, rotation)
    out += postprocessing(ro, L, z_joint, z_top, x_from, reference, rotation, design)
    out += ["", "SOLVER, cholmod", f"OUTPUT, {name}.h5", ""]
    return "\n".join(out)


def capacity_stages(capacity, steps, delta, rotation):
    """The capacity staging (--capacity): stage `seat`, a fraction of q with the whole misalignment
    delta, in `seat_steps`; stage `jack`, the rest of q in `steps`. The misalignment is then held
    while the jacking force grows, as in a drive (and in chapter 8's tests with the angled plate);
    the run stops where a step does not converge: the failure, under load control."""
    seat, seat_steps = capacity
    return [f"! stage seat: {seat:g} of q and the misalignment delta = {delta:.4f} mm together",
            f"STAGE, seat, STEPS={seat_steps}, LOAD={seat:g}, OUTPUT=1"] + misalignment(delta, rotation) + [
            f"! stage jack: the other {1.0 - seat:g} of q, the misalignment held",
            f"STAGE, jack, STEPS={steps}, LOAD={1.0 - seat:g}, OUTPUT=1", ""]


def misalignment(delta, rotation):
    """The top end's displacement delta along the misalignment's direction theta = rotation."""
    if rotation == 0.0:
        return [f"DISPLACE, top_end_nodes, X={delta:.4f}"]
    return [f"! along the misalignment's direction theta = {rotation:g} (system 4's x; the top end free across it)",
            f"DISPLACE, top_end_nodes, X={delta:.4f}, CSYS=4"]


def thesis_stages(steps, delta, rotation):
    """Model C's stages as thesis 6.3/6.4: 20 % of q, then the rest and delta together, then
    equilibrium iterations."""
    out = ["! stage 1: 20% of q, 1 step; the top end's ux is prescribed in stage 2, so held at 0 here",
            "STAGE, s1, STEPS=1, LOAD=0.2",
            f"! stage 2: the other 80% and delta = {delta:.4f} mm together",
            f"STAGE, s2, STEPS={steps}, LOAD=0.8",
        ] + misalignment(delta, rotation) + [
            "! stage 3: equilibrium iterations only (no load or displacement increment)",
            f"STAGE, s3, STEPS={EQUILIBRIUM_STEPS}, LOAD=0, MAXIT=50", ""]
    return out


def postprocessing(ro, L, z_joint, z_top, x_from, reference, rotation, design):
    """The REPORTs and FIELDS of model C's deck."""
    out = []
    if rotation == 0.0:
        out += ["! --- post-processing: scripts/postprocess_model_c.py computes beta*, beta_bar, Z and sigma_max",
            f"! (thesis 7.4). These REPORTs give quick views: the slope of w over x = {x_from:g}..{ro:g} on r = {ro:g} "
            "of the",
            "! top pipe's mid-length section A-A (beta_bar before the interface's own deformation is taken",
            f"! out; negative: w falls towards x = +{ro:g}; REFERENCE = minus the thesis's beta_bar) and of the",
            "! bottom pipe's end face (thesis Figs. 7.5/7.6) ---"]
        rep = (f"REPORT, ROTATION, NAME=section_AA, GROUP=top_pipe, R={num(ro)}, Z={num(z_top + L / 2)}, "
               f"FROM={num(x_from)}, TO={num(ro)}")
        out.append(rep + (f", REFERENCE={-reference:g}" if reference is not None else ""))
        out.append(f"REPORT, ROTATION, NAME=bottom_end, GROUP=bottom_pipe, R={num(ro)}, Z={num(z_joint)}, "
                   f"FROM={num(x_from)}, TO={num(ro)}")
    else:
        out += ["! --- post-processing: REPORT ROTATION takes slopes along global x, not along the misalignment's",
                "! direction: the joint's deflection is REPORT JOINT's (along theta = EDGE) ---"]
    out += ["! the force the imposed top-end displacement needs (fx: H = P e / L, the moment of the joint's",
            "! eccentric contact resultant; postprocess_model_c.py --statics drives beam theory with it)",
            "REPORT, REACTION, NAME=top_end, NSET=top_end_nodes"]
    if design:
        out += ["! the design summary of the joint (hoop tension, compression, contact width, opening, deflection,",
                "! the Australian and Haslem models beside them): /summary joint_design_*",
                "REPORT, JOINT, NAME=design, INTERFACE=joint, PIPE=bottom_pipe:top_pipe, PACKING=packing"
                + ("" if rotation == 0.0 else f", EDGE={num(rotation)}")]
    out += ["! postprocess_model_c.py reads the interface's normal stress at the nodes, feps's nodal_interface",
            "FIELDS, all, nodal_interface"]
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", required=True, metavar="DECK", help="the deck to write (its results: DECK's "
                    "name with .h5)")
    pipe = ap.add_argument_group("pipe and joint (mm, MPa, deg; default: the thesis's)")
    pipe.add_argument("--inner-diameter", type=positive, default=2 * R_IN, help=f"default {2 * R_IN:g}")
    pipe.add_argument("--wall", type=positive, default=R_OUT - R_IN, help=f"wall thickness (default {R_OUT - R_IN:g})")
    pipe.add_argument("--pipe-length", type=positive, default=L_PIPE, help=f"default {L_PIPE:g}")
    pipe.add_argument("--packing", type=finite, default=PACKING,
                      help=f"packing thickness a (default {PACKING:g}); 0: one pipe in soil loaded on its ends (model B)")
    pipe.add_argument("--packing-G", type=positive, help=f"packing shear modulus (default {G_PACKING:g})")
    pipe.add_argument("--packing-E", type=positive, help="packing Young's modulus (instead of --packing-G)")
    pipe.add_argument("--packing-nu", type=finite, default=NU_PACKING, help=f"default {NU_PACKING:g}")
    pipe.add_argument("--joint-kn", type=positive, default=KN_JOINT, help=f"MPa/mm (default {KN_JOINT:g})")
    pipe.add_argument("--joint-ks", type=positive, default=KS_JOINT, help=f"MPa/mm (default {KS_JOINT:g})")
    pipe.add_argument("--joint-phi", type=positive, default=PHI_JOINT, help=f"default {PHI_JOINT:g}")
    pipe.add_argument("--joint-psi", type=finite, default=PSI_JOINT, help=f"default {PSI_JOINT:g}")
    pipe.add_argument("--joint-c", type=finite, default=C_JOINT, help=f"default {C_JOINT:g}")
    load = ap.add_argument_group("misalignment and load")
    load.add_argument("--misalignment", choices=("edge", "diagonal"), default="edge",
                      help="edge: the top pipe deflected about the y axis, the joint closing at x = +r_o (quarter "
                           "model, y >= 0). diagonal: deflected about the axis at 45 deg in the cross-section, the "
                           "joint closing at theta = 45 deg: the quarter model turned by 45 deg (theta 45..225, the "
                           "plane of deflection held normal to itself in a CSYS turned by 45 deg), or with --gamma "
                           "(gravity along -x breaks that symmetry) or --full the whole ring (the edge case's --full "
                           "mesh turned by 45 deg). With --packing 0 (model B) the ends loaded on opposite sides "
                           "(half model)")
    load.add_argument("--full", action="store_true", help="model C: the whole ring (the edge case's mesh mirrored "
                      "about the plane of deflection) where the quarter model would do: test/cli/check_pipe_joint.py "
                      "compares them")
    load.add_argument("--angle", type=positive, default=BETA, help=f"misalignment beta (deg, default {BETA:g})")
    force = load.add_mutually_exclusive_group()
    force.add_argument("--jacking-stress", type=positive, help=f"mean stress on the pipe's end (default {Q:g})")
    force.add_argument("--jacking-force", type=positive, help="force on the whole pipe's end (N; --packing 0 "
                       "default 2.0e6, the thesis's 1000 kN on the half model)")
    load.add_argument("--steps", type=positive_int, help="load steps (model C's stage 2, or with --capacity stage "
                      "jack; default by the angle)")
    load.add_argument("--capacity", type=float, metavar="SEAT", help="model C: the capacity staging instead of the "
                      "thesis's: stage seat applies this fraction of q (0 < SEAT < 1) with the whole misalignment "
                      "in 5 steps, stage jack the rest of q in --steps steps with the misalignment held, full "
                      "Newton-Raphson; a step that does not converge stops the run (scripts/capacity_curves.py)")
    load.add_argument("--concrete", type=positive, nargs=3, metavar=("FT", "FC", "GF"), help="model C: the pipes of "
                      f"cracking CONCRETE (tensile and compressive strength, MPa; fracture energy, N/mm; PHI = PSI = "
                      f"{CONCRETE_PHI:g}) instead of elastic")
    soil = ap.add_argument_group("soil and ground")
    soil.add_argument("--soil-E", type=positive, default=144.0, help="default 144")
    soil.add_argument("--soil-nu", type=finite, default=0.2, help="default 0.2")
    soil.add_argument("--soil-phi", type=positive, help="friction angle: Matsuoka-Nakai soil (default: elastic); "
                      "with --interface frictional the pipe/soil interface's")
    soil.add_argument("--soil-psi", type=finite, help="dilation angle (default: phi)")
    soil.add_argument("--soil-c", type=finite, default=0.05, help="cohesion (default 0.05)")
    soil.add_argument("--interface", choices=("bonded", "frictional"), default="bonded",
                      help="pipe/soil: shared nodes, or Mohr-Coulomb interfaces with Ks = 50 E_s / 144, Kn = 2 Ks (the "
                           "thesis's model B), phi = --soil-phi (default 15), psi = --soil-psi, c = --soil-c; model B's "
                           "soil is then elastic, model C's stays Matsuoka-Nakai with --soil-phi. Model C: between "
                           "the soil and every pipe (and the packing) it surrounds")
    soil.add_argument("--soil-around-top", action="store_true", help="model C: the soil's layers round the top pipe "
                      "and the packing too, one ground with the bottom pipe's (default: round the bottom pipe only, "
                      "as thesis 6.2); the far boundary and, with --gamma, the rollers at the top pipe's end")
    soil.add_argument("--gamma", type=positive, help="the soil's unit weight (N/mm3; 2.0e-5 = 20 kN/m3): gravity and "
                      "the K0 stress field")
    soil.add_argument("--k0", type=positive, help="K0 (default 1 - sin(phi), Jaky)")
    soil.add_argument("--cover", type=positive, help="depth of the pipe's crown below the surface (mm; with --gamma)")
    soil.add_argument("--water-table", type=finite, help="depth of the water table below the surface (mm)")
    mesh = ap.add_argument_group("mesh")
    mesh.add_argument("--soil-radius", type=positive, help="the soil's outer radius (default 2000 r_o / 715)")
    mesh.add_argument("--theta-step", type=positive, default=THETA_STEP, help="element size (deg) beyond theta = 12 "
                      "(model C; it must divide 168)")
    mesh.add_argument("--wall-elements", type=positive_int, default=WALL_ELEMENTS, help="model C (default 2)")
    mesh.add_argument("--z-refine", type=positive_int, default=1, help="model C: cut every z element in this many")
    mesh.add_argument("--refine", type=positive_int, default=1, help="model B: every element in refine^3")
    mesh.add_argument("--element", choices=ELEMENTS, default="hex8", help="model B's element")
    a = ap.parse_args(argv)
    try:
        text = deck_of(a)
    except ValueError as exc:
        ap.error(str(exc))
    with open(a.output, "w") as f:
        f.write(text)
    print(f"wrote {a.output}")


def deck_of(a):
    """The deck of the command line's options; ValueError naming the option that is wrong."""
    p = Pipe(a.inner_diameter / 2, a.inner_diameter / 2 + a.wall, a.pipe_length, a.packing)
    r_soil = a.soil_radius or p.default_soil_radius()
    name = os.path.splitext(os.path.basename(a.output))[0]
    psi = a.soil_phi if a.soil_psi is None else a.soil_psi
    if a.gamma is None and any(v is not None for v in (a.k0, a.cover, a.water_table)):
        raise ValueError("--k0, --cover and --water-table need --gamma (the soil's weight)")
    ground = Ground()
    if a.gamma is not None:
        if a.cover is None:
            raise ValueError("--gamma needs --cover (the crown's depth, mm)")
        if r_soil > p.r_out + a.cover:
            raise ValueError(f"--cover {a.cover:g}: the soil's mesh reaches r = {r_soil:g} above the axis, beyond the "
                             f"surface at {p.r_out + a.cover:g}; give a --soil-radius of at most r_o + cover")
        if a.water_table is not None and a.water_table < 0.0:
            raise ValueError(f"--water-table {a.water_table:g}: a depth below the surface (>= 0)")
        surface = p.r_out + a.cover
        ground = Ground(a.gamma, a.k0, a.soil_phi, surface, None if a.water_table is None else surface - a.water_table)
    if a.packing == 0.0:
        if a.capacity is not None or a.concrete is not None:
            raise ValueError(f"--{'capacity' if a.capacity is not None else 'concrete'} is model C's (two pipes, "
                             "--packing > 0)")
        if a.full or a.soil_around_top:
            raise ValueError(f"--{'full' if a.full else 'soil-around-top'} is model C's (two pipes, --packing > 0); "
                             "model B is a half model of one pipe in soil")
        kind = "F" if a.interface == "frictional" else ("P" if a.soil_phi else "S")
        kn, ks, phi, psi_b, _ = pipe_soil_law(a, psi)
        force = a.jacking_force or (a.jacking_stress * math.pi * (p.r_out ** 2 - p.r_in ** 2) if a.jacking_stress
                                    else 2.0e6)
        return half_pipe_deck(kind, "E" if a.misalignment == "edge" else "D", a.soil_E, ks, kn, phi, psi_b, r_soil,
                              a.refine, a.element, pipe=p, case=name,
                              soil_name=f"E_s = {a.soil_E:g} MPa", output=name, total=force / 2.0, steps=a.steps,
                              nu_s=a.soil_nu, c=a.soil_c, ground=ground)
    if not -1.0 < a.packing_nu < 0.5 or not 0.0 <= a.joint_psi <= a.joint_phi:
        raise ValueError(f"--packing-nu {a.packing_nu:g} must lie in (-1, 0.5), --joint-psi {a.joint_psi:g} in "
                         f"[0, --joint-phi {a.joint_phi:g}]")
    if a.capacity is not None and not 0.0 < a.capacity < 1.0:
        raise ValueError(f"--capacity {a.capacity:g}: the seating fraction of q lies in (0, 1)")
    if a.concrete is not None and not a.concrete[0] < a.concrete[1]:
        raise ValueError(f"--concrete: FT {a.concrete[0]:g} must be below FC {a.concrete[1]:g}")
    G = a.packing_G or (a.packing_E / (2.0 * (1.0 + a.packing_nu)) if a.packing_E else G_PACKING)
    q = a.jacking_stress or (a.jacking_force / (math.pi * (p.r_out ** 2 - p.r_in ** 2)) if a.jacking_force else Q)
    return joint_deck(G, a.packing_nu, a.angle, r_soil, a.steps or default_steps(a.angle), a.theta_step, a.soil_E,
                      a.wall_elements, a.z_refine, a.joint_psi, name=name, pipe=p, q=q,
                      joint=(a.joint_kn, a.joint_ks, a.joint_phi, a.joint_c),
                      soil=(a.soil_nu, a.soil_phi, psi, a.soil_c), ground=ground, design=True,
                      rotation=45.0 if a.misalignment == "diagonal" else 0.0,
                      full=a.full or (a.misalignment == "diagonal" and a.gamma is not None),
                      soil_top=a.soil_around_top, capacity=None if a.capacity is None else (a.capacity, SEAT_STEPS),
                      concrete=a.concrete, pipe_soil=pipe_soil_law(a, psi) if a.interface == "frictional" else None)


def pipe_soil_law(a, psi):
    """The pipe/soil interface (Kn, Ks, phi, psi, c) of --interface frictional, model B's and C's:
    Ks = 50 E_s / 144, Kn = 2 Ks (the thesis's), phi = --soil-phi or 15 deg, psi = --soil-psi or
    phi, c = --soil-c. (Model B's Matsuoka soil takes its phi and psi from here too.)"""
    ks, phi = 50.0 * a.soil_E / 144.0, a.soil_phi or 15.0
    return (2.0 * ks, ks, phi, phi if psi is None else psi, a.soil_c)


if __name__ == "__main__":
    main()
