#!/usr/bin/env python3
"""Write the decks of thesis model C (chapter 6): input/modelC/<case>.dat for the 12 cases
C_G<G_p>_nu<nu_p>_b<beta> (G_p = 300, 900 MPa; nu_p = 0.1, 0.4, -0.3; beta = 0.09, 0.27 deg).

    python3 scripts/make_model_c.py [--outdir input/modelC] [--cases C_G300_nu0.1_b0.09,...]
                                    [--steps N] [--soil-radius 2000] [--theta-step 3]
                                    [--wall-elements 2] [--z-refine 1]

Parametric campaigns beyond the thesis's twelve cases: give lists, and a deck is written for every
combination (the thesis's own cases among them are the same decks as above):

    python3 scripts/make_model_c.py --outdir input/sweep --Gp 300,600,900 --nup 0.1 --beta 0.09,0.18
                                    [--soil-E 144,1440] [--psi 0,10,20]

Case names: C_G<G_p>_nu<nu_p>_b<beta>, with _Es<E_s> appended when the soil's E is not the
thesis's 144 MPa and _psi<psi> when the joint interface's dilation angle is not its 20 deg.
Stage-2 steps off the thesis grid: at least the thesis's 250 and one step per 0.000 54 deg of
misalignment (500 at 0.27 deg), rounded up to 50 (see stage2_steps).

Quarter model (y >= 0, z >= 0) of the symmetric three-pipe system, thesis Fig. 6.2 and SPEC
section 8: the bottom half pipe (z 0..1250) in soil, a 15 mm packing (z 1250..1265) bonded to
the top pipe (z 1265..3765), one layer of quad interfaces between the bottom pipe's end face and
the packing. Every choice the thesis leaves open is written into the deck's comments; the
post-processing of Tables 7.3 and 7.4 is scripts/postprocess_model_c.py.
"""
import argparse
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from feps_cli import positive, positive_int  # noqa: E402  (argparse types)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

R_IN, R_OUT = 600.0, 715.0
Z_JOINT = 1250.0            # bottom pipe's end face (lower interface layer)
PACKING = 15.0              # packing thickness a (SPEC section 8, derived from Table 7.4)
L_PIPE = 2500.0
Z_TOP_BOTTOM = Z_JOINT + PACKING          # 1265: the top pipe's bottom end
Z_TOP_END = Z_TOP_BOTTOM + L_PIPE         # 3765: the loaded end
Z_SECTION_AA = Z_TOP_BOTTOM + L_PIPE / 2  # 2515: mid-length of the top pipe (thesis Fig. 7.7)
Q = 10.0                                   # MPa on the top end
KN_JOINT, KS_JOINT = 800.0, 400.0          # MPa/mm, the packing/bottom-pipe interface (thesis 6.2)
PHI_JOINT = PSI_JOINT = 20.0               # deg: its friction and dilation angles (thesis 6.2)
BETAS = (0.09, 0.27)
SHEAR_MODULI = (300.0, 900.0)
POISSON = (0.1, 0.4, -0.3)
# stage 2 steps (thesis 6.3 and 6.4): (beta, G_p) -> steps
EQUILIBRIUM_STEPS = 100    # stage s3: at most 100 x 50 iterations, 1 per step once converged
STEPS = {(0.09, 300.0): 250, (0.09, 900.0): 300, (0.27, 300.0): 400, (0.27, 900.0): 500}

# theta grid: 4 x 3 deg on the loaded edge (theta = 0, x = +715: sigma_max is read from elements
# with theta < 6 deg, thesis 7.4.3), then THETA_STEP up to 180. 3 deg (60 elements) because the
# gap front at beta = 0.27 is located between Gauss points: with 6 deg beyond theta = 12 (the
# first decks) Z of C_G300_nu-0.3_b0.27 was 805 mm, with 3 deg 825 and with 1.5 deg 829
# (docs/verification.md, model C mesh sensitivity).
THETA_EDGE = [3.0] * 4
THETA_STEP = 3.0


def theta_steps(theta_step=THETA_STEP):
    """Element sizes (deg) from theta = 0 to 180: 4 x 3 at the loaded edge, then theta_step."""
    n = round(168.0 / theta_step)
    if abs(n * theta_step - 168.0) > 1e-9:
        raise ValueError("the theta step must divide 168 deg")
    return THETA_EDGE + [theta_step] * n
# bottom block z (0 = mid-length of the bottom pipe, a symmetry plane) graded towards the joint
Z_BOTTOM_STEPS = [150.0] * 4 + [100.0] * 3 + [50.0] * 4 + [25.0] * 4 + [12.5] * 4   # 0 .. 1250
PACKING_LAYERS = 2
WALL_ELEMENTS = 2          # hex8 through the pipe wall (--wall-elements: the mesh study)
# top pipe z from 1265, fine at the joint, a node layer at the mid-length section A-A (2515)
Z_TOP_STEPS = [12.5] * 4 + [25.0] * 4 + [50.0] * 4 + [100.0] * 3 + [150.0] * 4 \
    + [150.0] * 5 + [100.0] * 3 + [50.0] * 4                                         # 1265 .. 3765


SOIL_E = 144.0             # MPa (thesis 6.1)


def case_name(G, nu, beta, soil_E=SOIL_E, psi=PSI_JOINT):
    name = f"C_G{G:g}_nu{nu:g}_b{beta:g}"
    if soil_E != SOIL_E:
        name += f"_Es{soil_E:g}"
    return name if psi == PSI_JOINT else name + f"_psi{psi:g}"


def all_cases():
    return [(G, nu, b) for b in BETAS for G in SHEAR_MODULI for nu in POISSON]


def parse_case(name):
    """(G, nu, beta, soil_E, psi) of a case name C_G300_nu0.1_b0.09[_Es1440][_psi0]."""
    parts = name.split("_")
    bad = ValueError(f"case name {name!r} is not C_G<G_p>_nu<nu_p>_b<beta>[_Es<E_s>][_psi<psi>]")
    try:
        if len(parts) < 4 or parts[0] != "C" or not (parts[1].startswith("G") and
                                                     parts[2].startswith("nu") and parts[3].startswith("b")):
            raise bad
        optional = {"Es": SOIL_E, "psi": PSI_JOINT}
        seen = []
        for part in parts[4:]:
            key = next((k for k in optional if part.startswith(k)), None)
            # each suffix once, in the order case_name writes them
            if key is None or key in seen or (seen and list(optional).index(key) < list(optional).index(seen[-1])):
                raise bad
            optional[key] = float(part[len(key):])
            seen.append(key)
        return (float(parts[1][1:]), float(parts[2][2:]), float(parts[3][1:]), optional["Es"],
                optional["psi"])
    except ValueError:
        raise bad from None


def stage2_steps(G, beta):
    """Stage-2 steps: the thesis's (6.3, 6.4) for its four (beta, G_p); otherwise at least 250 and
    one step per 0.27 / 500 deg of misalignment (the thesis's finest: 500 steps at 0.27 deg),
    rounded up to a multiple of 50."""
    if (beta, G) in STEPS:
        return STEPS[(beta, G)]
    return max(250, 50 * math.ceil(500.0 * beta / 0.27 / 50.0 - 1e-9))


def check_parameters(G, nu, beta, soil_E, psi=PSI_JOINT):
    """The ranges a deck can be written for (the materials' own checks are feps's)."""
    if not G > 0.0:
        raise ValueError(f"G_p = {G:g}: the packing's shear modulus must be positive")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu_p = {nu:g}: Poisson's ratio must lie in (-1, 0.5)")
    if not 0.0 < beta < 5.0:
        raise ValueError(f"beta = {beta:g} deg: the misalignment must lie in (0, 5) deg")
    if not soil_E > 0.0:
        raise ValueError(f"E_s = {soil_E:g}: the soil's Young's modulus must be positive")
    if not 0.0 <= psi <= PHI_JOINT:
        raise ValueError(f"psi = {psi:g}: the joint interface's dilation angle must lie in [0, {PHI_JOINT:g}] deg "
                         "(its friction angle)")


def soil_layers(r_soil):
    """Four soil element layers from r = 715 (as model B: 150, 250, 350, 535 scaled)."""
    check_soil_radius(r_soil)
    base = [150.0, 250.0, 350.0, 535.0]
    scale = (r_soil - R_OUT) / sum(base)
    return [b * scale for b in base]


def check_soil_radius(r_soil):
    """The soil's outer radius must lie beyond the pipe's outer radius R_OUT (the soil layers grow
    outwards from it; at or inside it the soil elements turn inside out)."""
    if not (math.isfinite(r_soil) and r_soil > R_OUT):
        raise ValueError(f"soil radius {r_soil:g} mm: the soil's outer radius must exceed the pipe's outer "
                         f"radius {R_OUT:g} mm")


def radius_text(r):
    """A radius for an NSET record (TOL=0.01): one decimal as the decks have always had it ('2000.0'),
    or the digits a radius off the 0.1 mm grid needs to select its nodes."""
    text = f"{r:.1f}"
    return text if float(text) == r else f"{r:.10g}"


def soil_radius_arg(text):
    """argparse type of --soil-radius."""
    try:
        value = float(text)
        check_soil_radius(value)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc) if "soil radius" in str(exc) else f"{text!r} is not a number")
    return value


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
    """Node numbering of the two DATAIN node blocks (theta fastest, then r, then z in each);
    `wall` elements through the pipe wall, every z increment cut into `z_refine`."""

    def __init__(self, r_soil, thetas, wall=WALL_ELEMENTS, z_refine=1):
        self.nt = len(thetas) + 1                          # nodes along theta
        self.r_bottom = [R_IN + (R_OUT - R_IN) * i / wall for i in range(wall + 1)]
        for d in soil_layers(r_soil):
            self.r_bottom.append(self.r_bottom[-1] + d)
        self.nr_bottom = len(self.r_bottom)                # 7 with 2 wall elements
        self.z_bottom = split(Z_BOTTOM_STEPS, z_refine)
        self.z_top = split(Z_TOP_STEPS, z_refine)
        self.packing_layers = PACKING_LAYERS * z_refine
        self.nz_bottom = len(self.z_bottom) + 1            # 20 unrefined
        self.nr_top = wall + 1
        self.nz_top = self.packing_layers + len(self.z_top) + 1
        self.bottom_nodes = self.nt * self.nr_bottom * self.nz_bottom

    def bottom(self, it, ir, iz):
        return 1 + it + self.nt * (ir + self.nr_bottom * iz)

    def top(self, it, ir, iz):
        """Top block: iz = 0 is z = 1250 (the packing's lower face), packing_layers is z = 1265."""
        return self.bottom_nodes + 1 + it + self.nt * (ir + self.nr_top * iz)


def hex_record(node, it, ir, iz):
    """hex8 with its bottom face counter-clockwise seen from +z: (r, t), (r+1, t), (r+1, t+1), (r, t+1)."""
    face = [node(it, ir, iz), node(it, ir + 1, iz), node(it + 1, ir + 1, iz), node(it + 1, ir, iz)]
    top = [node(it, ir, iz + 1), node(it, ir + 1, iz + 1), node(it + 1, ir + 1, iz + 1), node(it + 1, ir, iz + 1)]
    return "A, 8, " + ", ".join(str(n) for n in face + top) + ","


def deck(G, nu, beta, r_soil=2000.0, steps=None, theta_step=THETA_STEP, soil_E=SOIL_E,
         wall=WALL_ELEMENTS, z_refine=1, psi=PSI_JOINT):
    """The deck text of one case; theta_step is the element size (deg) beyond theta = 12, wall the
    elements through the pipe wall, z_refine the number of parts each z element is cut into, psi
    the joint interface's dilation angle (deg)."""
    check_parameters(G, nu, beta, soil_E, psi)
    if steps is not None and steps < 1:
        raise ValueError(f"{steps} stage-2 steps: at least 1 is needed")
    thetas = theta_steps(theta_step)
    m = Mesh(r_soil, thetas, wall, z_refine)
    name = case_name(G, nu, beta, soil_E, psi)
    delta = L_PIPE * math.tan(math.radians(beta))
    nsteps = steps or stage2_steps(G, beta)
    E_p = 2.0 * G * (1.0 + nu)
    ntheta = len(thetas)
    nzb = len(m.z_bottom)
    nzt = len(m.z_top)
    npl = m.packing_layers
    stride_r_b, stride_z_b = m.nt, m.nt * m.nr_bottom
    stride_r_t, stride_z_t = m.nt, m.nt * m.nr_top
    out = [
        f"! feps deck: numerical model C (thesis chapter 6), case {name}: packing G_p = {G:g} MPa,",
        f"! nu_p = {nu:g} (E_p = 2 G_p (1 + nu_p) = {E_p:g} MPa), misalignment beta = {beta:g} deg",
        f"! (delta = L tan(beta) = {delta:.3f} mm, L = {L_PIPE:g}). Written by scripts/make_model_c.py.",
        "!",
        "! Quarter model (theta 0..180, y >= 0; z >= 0) of the symmetric three-pipe system (thesis 6.2,",
        "! Fig. 6.2; SPEC section 8):",
        "! - bottom: half pipe r = 600..715, z = 0..1250 (z = 0 is the mid-length symmetry plane, fixed in",
        f"!   z), in soil r = 715..{r_soil:g} over the same z (4 hex8 layers as model B; the thesis gives no soil",
        "!   extent). Pipe and soil are BONDED (shared nodes): thesis 6.2 says there was just one interface",
        "!   in the model, the one between the packing and the bottom pipe, and 6.3 calls stage 1 linear.",
        f"! - packing: {PACKING:g} mm thick (SPEC 8: derived from Table 7.4's Australian columns), z = 1250..1265,",
        f"!   r = 600..715, {npl} hex8 layers, bonded to the top pipe (shared nodes at z = 1265).",
        "! - one layer of interface-quad4 between the bottom pipe's end face (lower layer, normal +z) and the",
        "!   packing (upper layer): coincident nodes at z = 1250 (two node blocks: the bottom one ends at",
        "!   z = 1250, the top one starts there). Kn = 800, Ks = 400 MPa/mm, " +
        ("phi = psi = 20 deg, c = 0.05 MPa." if psi == PSI_JOINT else
         f"phi = 20, psi = {psi:g} deg (thesis 6.2: 20), c = 0.05 MPa."),
        "! - top pipe: full length 2500 (z = 1265..3765), NOT in soil: thesis 6.2 has soil only around the",
        "!   bottom half pipe ('a half pipe with its surrounding soil at the bottom, a complete pipe on the",
        "!   top'). Its only supports are the joint, the symmetry plane y = 0 and the prescribed x",
        "!   displacement of its upper end.",
        f"! - concrete E = 40000, nu = 0.2; soil E = {soil_E:g}, nu = 0.2 (thesis 6.1{'' if soil_E == SOIL_E else ': E = 144'}); "
        "all elastic.",
        "! - supports (thesis 6.2): soil outer surface fixed in x and y; z = 0 fixed in z; y = 0 fixed in y.",
        f"! - loads: q = {Q:g} MPa uniform on the top end; delta in x on every node of the top end (thesis 6.2:",
        "!   'an equivalent displacement delta in x direction at the upper end'); the end's y and z are free.",
        "!   Stage 1: 20% of q in 1 step, the end held at ux = 0 ('without rotation'); stage 2: the other 80%",
        f"!   and delta together in {nsteps} steps (thesis 6.3/6.4), initial stiffness, at most 10 iterations;",
        "!   stage 3: equilibrium iterations (see the solution controls below).",
        f"! - mesh: hex8, {wall} elements through the wall; theta 4 x 3 deg at the loaded edge (theta = 0,",
        "!   x = +715: sigma_max comes from the elements with theta < 6 deg, thesis 7.4.3), then " + f"{len(thetas) - 4} x {thetas[-1]:g} deg;",
        "!   z graded 150/100/50/25/12.5 mm towards the joint on both sides" +
        ("" if z_refine == 1 else f", each cut into {z_refine}") + "; a node layer at z = 2515, the",
        "!   top pipe's mid-length section A-A of thesis Fig. 7.7.",
        "! The misalignment rotation is about +y: the joint closes at x = +715 (theta = 0) and may open",
        "! towards x = -715 (theta = 180), as thesis Figs. 6.4 and 6.11.",
        f"TITLE, Model C {name}: packing G_p = {G:g}, nu_p = {nu:g}, beta = {beta:g} deg, q = {Q:g} MPa",
        "! the case's parameters, written to the results file as /summary attributes parameter_<name>",
        f"PARAMETERS, G_p={G:g}, nu_p={nu:g}, beta={beta:g}, E_s={soil_E:g}" +
        ("" if psi == PSI_JOINT else f", psi_joint={psi:g}"),
        "",
        "! --- node block 1: bottom pipe and soil (theta fastest, then r, then z) ---",
        f"A, 3, {R_IN:g}., 0., 0.,",
    ]
    # 12 digits: a wall of 3 elements must still end on r = 715 (38.3333 x 3 would not)
    wall_record = f"%, {wall + 1}, {(R_OUT - R_IN) / wall:.12g}, 0., 0.,".ljust(30) + \
        "! pipe wall r = " + ", ".join(f"{r:g}" for r in m.r_bottom[:wall + 1])
    out += direction(thetas, 1, "theta")
    out.append(wall_record)
    for d in soil_layers(r_soil):
        out.append(f"%, -1, {d:.4f}, 0., 0.,".ljust(30) + "! soil layer")
    out += direction(m.z_bottom, 2, "z")
    out += ["E,", "",
            "! --- node block 2: the packing's lower face at z = 1250 (coincident with the bottom pipe's",
            "! end face: the interface's two layers), the packing and the top pipe ---",
            f"A, 3, {R_IN:g}., 0., {Z_JOINT:g}.,"]
    out += direction(thetas, 1, "theta")
    out.append(wall_record)
    out += direction([PACKING / npl] * npl, 2, "z (packing)", start=Z_JOINT)
    out += direction(m.z_top, 2, "z", first=False, start=Z_TOP_BOTTOM)
    out += ["E,", ""]
    out += ["GROUP, bottom_pipe, TYPE=hex8, MATERIAL=concrete", hex_record(m.bottom, 0, 0, 0),
            f"%, {ntheta}, *, 8, 1,", f"%, {wall}, *, 8, {stride_r_b},", f"%, {nzb}, *, 8, {stride_z_b},", "E,", "",
            "GROUP, soil, TYPE=hex8, MATERIAL=soil", hex_record(m.bottom, 0, wall, 0),
            f"%, {ntheta}, *, 8, 1,", f"%, {m.nr_bottom - wall - 1}, *, 8, {stride_r_b},",
            f"%, {nzb}, *, 8, {stride_z_b},", "E,", "",
            "GROUP, packing, TYPE=hex8, MATERIAL=packing", hex_record(m.top, 0, 0, 0),
            f"%, {ntheta}, *, 8, 1,", f"%, {wall}, *, 8, {stride_r_t},", f"%, {npl}, *, 8, {stride_z_t},",
            "E,", "",
            "GROUP, top_pipe, TYPE=hex8, MATERIAL=concrete", hex_record(m.top, 0, 0, npl),
            f"%, {ntheta}, *, 8, 1,", f"%, {wall}, *, 8, {stride_r_t},", f"%, {nzt}, *, 8, {stride_z_t},", "E,", ""]
    lo = [m.bottom(0, 0, nzb), m.bottom(0, 1, nzb), m.bottom(1, 1, nzb), m.bottom(1, 0, nzb)]
    up = [m.top(0, 0, 0), m.top(0, 1, 0), m.top(1, 1, 0), m.top(1, 0, 0)]
    out += ["! lower layer = the bottom pipe's end face (counter-clockwise seen from +z: e1 along r, e2 along",
            "! theta, normal +z), upper layer = the packing's lower face; theta strides agree in both blocks",
            "GROUP, joint, TYPE=interface-quad4, MATERIAL=pipe_packing",
            "A, 8, " + ", ".join(str(n) for n in lo + up) + ",",
            f"%, {ntheta}, *, 8, 1,", f"%, {wall}, *, 8, {m.nt},", "E,",
            "E,", "",
            "MATERIAL, concrete, ELASTIC, E=40000., NU=0.2",
            f"MATERIAL, soil, ELASTIC, E={soil_E:g}{'.' if float(soil_E).is_integer() else ''}, NU=0.2",
            f"MATERIAL, packing, ELASTIC, G={G:g}, NU={nu:g}",
            f"MATERIAL, pipe_packing, INTERFACE, KN={KN_JOINT:g}., KS={KS_JOINT:g}., PHI={PHI_JOINT:g}., "
            f"PSI={psi:g}{'.' if float(psi).is_integer() else ''}, C=0.05",
            "",
            "! --- supports (thesis 6.2) ---",
            f"NSET, soil_outer, CSYS=3, R={radius_text(r_soil)}, TOL=0.01",
            "NSET, symmetry_y, CSYS=2, Y=0., TOL=0.01",
            "NSET, symmetry_z, CSYS=2, Z=0., TOL=0.01",
            "FIX, soil_outer, X, Y", "FIX, symmetry_y, Y", "FIX, symmetry_z, Z", "",
            f"! --- loads: q = {Q:g} MPa on the top end (reference load, applied 20% + 80% by the stages) ---",
            f"FSET, top_end, GROUP=top_pipe, CSYS=2, Z={Z_TOP_END:g}., TOL=0.01",
            f"NSET, top_end_nodes, CSYS=2, Z={Z_TOP_END:g}., TOL=0.01",
            f"PRESSURE, top_end, VALUE={Q:g}", "",
            "! --- solution (thesis 6.3/6.4: initial stiffness, 'several iterations within each step",
            "! depending on convergence and controlled by the program'; no tolerance given: DELTA1 = 1e-4",
            "! as model B). Once the joint slides and a gap opens (beta = 0.27 from stage-2 step ~35) the",
            "! initial stiffness converges at ~0.95 per iteration (Kn, Ks of the interface are "
            f"{KN_JOINT * PACKING / E_p:.2g} and {KS_JOINT * PACKING / G:.2g} x",
            "! this packing layer's E_p/a, G_p/a, and the elastic matrix keeps them at sliding and open points):",
            "! 10 iterations leave up to ~5% of |P| unbalanced, which feps's default DIVERGENCE = 1e-2 turns",
            "! into endless cut-backs. DIVERGENCE = 0.1 lets each step carry its unbalanced force into the",
            "! next (eq. 2.6.4), as the thesis's program did; stage s3 then applies nothing and iterates",
            "! (up to 50 per step) until |R|/|P| < 1e-4, so the final state is in equilibrium. The HDF5",
            "! keeps the end of s2 (step s2_last) and of s3 (final). ---",
            "CONTROLS, METHOD=initial-stiffness, MAXIT=10, DELTA1=1e-4, DIVERGENCE=0.1",
            "! stage 1: 20% of q, 1 step; the top end's ux is prescribed in stage 2, so held at 0 here",
            "STAGE, s1, STEPS=1, LOAD=0.2",
            f"! stage 2: the other 80% and delta = {delta:.4f} mm together",
            f"STAGE, s2, STEPS={nsteps}, LOAD=0.8",
            f"DISPLACE, top_end_nodes, X={delta:.4f}",
            "! stage 3: equilibrium iterations only (no load or displacement increment)",
            f"STAGE, s3, STEPS={EQUILIBRIUM_STEPS}, LOAD=0, MAXIT=50", "",
            "! --- post-processing: scripts/postprocess_model_c.py computes beta*, beta_bar, Z and sigma_max",
            "! (thesis 7.4). These REPORTs give quick views: the slope of w over x = 250..715 on r = 715 of the",
            "! top pipe's mid-length section A-A (beta_bar before the interface's own deformation is taken",
            "! out; negative: w falls towards x = +715; REFERENCE = minus the thesis's beta_bar) and of the",
            "! bottom pipe's end face (thesis Figs. 7.5/7.6) ---"]
    ref = thesis_beta_bar(G, nu, beta) if soil_E == SOIL_E and psi == PSI_JOINT else None
    rep = f"REPORT, ROTATION, NAME=section_AA, GROUP=top_pipe, R={R_OUT:g}., Z={Z_SECTION_AA:g}., FROM=250., TO=715."
    out.append(rep + (f", REFERENCE={-ref:g}" if ref is not None else ""))
    out.append(f"REPORT, ROTATION, NAME=bottom_end, GROUP=bottom_pipe, R={R_OUT:g}., Z={Z_JOINT:g}., "
               "FROM=250., TO=715.")
    out += ["! the force the imposed top-end displacement needs (fx: H = P e / L, the moment of the joint's",
            "! eccentric contact resultant; postprocess_model_c.py --statics drives beam theory with it)",
            "REPORT, REACTION, NAME=top_end, NSET=top_end_nodes"]
    out += ["! postprocess_model_c.py reads the interface's normal stress at the nodes, feps's nodal_interface",
            "FIELDS, all, nodal_interface"]
    out += ["", "SOLVER, cholmod", f"OUTPUT, {name}.h5", ""]
    return "\n".join(out)


_WARNED = []


def thesis_beta_bar(G, nu, beta):
    """beta_bar of thesis Table 7.3 (benchmarks/table7_3.csv), or None when not found. Without the
    table the decks lose their REFERENCE (and differ from input/modelC): say so once on stderr."""
    path = os.path.join(os.environ.get("FEPS_BENCHMARKS", os.path.join(ROOT, "..", "shared", "benchmarks")),
                        "table7_3.csv")
    if not os.path.exists(path):
        if not _WARNED:
            _WARNED.append(path)
            print(f"make_model_c: warning: no {os.path.normpath(path)} (the benchmarks folder, FEPS_BENCHMARKS): "
                  "the thesis's beta_bar is left out of the REPORT records' REFERENCE", file=sys.stderr)
        return None
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("applied"):
                continue
            b, _, bbar, mu, g = (float(v) for v in line.strip().split(","))
            if abs(b - beta) < 1e-9 and abs(mu - nu) < 1e-9 and abs(g - G) < 1e-9:
                return bbar
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--outdir", default=os.path.join(ROOT, "input", "modelC"))
    ap.add_argument("--cases", default="", help="comma-separated case names (default: all 12)")
    ap.add_argument("--steps", type=positive_int, default=None, help="stage-2 steps (default: the thesis's)")
    ap.add_argument("--soil-radius", type=soil_radius_arg, default=2000.0,
                    help=f"the soil's outer radius (mm, beyond the pipe's {R_OUT:g}; default 2000)")
    ap.add_argument("--theta-step", type=positive, default=THETA_STEP,
                    help=f"element size (deg) from theta = 12 to 180 (default {THETA_STEP:g}; it must divide 168)")
    ap.add_argument("--wall-elements", type=positive_int, default=WALL_ELEMENTS,
                    help=f"hex8 elements through the pipe wall (default {WALL_ELEMENTS}; the mesh study)")
    ap.add_argument("--z-refine", type=positive_int, default=1,
                    help="cut every z element (pipes and packing) into this many (default 1; the mesh study)")
    grid = ap.add_argument_group("parametric grid (every combination; any list left out keeps the thesis's values)")
    grid.add_argument("--Gp", type=number_list, help="packing shear moduli G_p (MPa), e.g. 300,600,900")
    grid.add_argument("--nup", type=number_list, help="packing Poisson's ratios nu_p, e.g. 0.1,0.4,-0.3")
    grid.add_argument("--beta", type=number_list, help="applied misalignment angles (deg), e.g. 0.09,0.18")
    grid.add_argument("--soil-E", type=number_list, help=f"soil Young's moduli (MPa; default {SOIL_E:g})")
    grid.add_argument("--psi", type=number_list,
                      help=f"dilation angles of the joint interface (deg, 0..{PHI_JOINT:g}; default {PSI_JOINT:g})")
    args = ap.parse_args(attach_negative_lists(sys.argv[1:]))
    try:
        theta_steps(args.theta_step)
    except ValueError as e:
        ap.error(str(e))
    lists = (args.Gp, args.nup, args.beta, args.soil_E, args.psi)
    if args.cases and any(v is not None for v in lists):
        ap.error("give either --cases or the grid lists (--Gp, --nup, --beta, --soil-E, --psi), not both")
    try:
        if args.cases:
            cases = [parse_case(c) for c in args.cases.split(",") if c]
        elif any(v is not None for v in lists):
            cases = [(G, nu, b, e, psi) for psi in (args.psi or [PSI_JOINT]) for e in (args.soil_E or [SOIL_E])
                     for b in (args.beta or BETAS) for G in (args.Gp or SHEAR_MODULI) for nu in (args.nup or POISSON)]
        else:
            cases = [c + (SOIL_E, PSI_JOINT) for c in all_cases()]
        for c in cases:
            check_parameters(*c)
    except ValueError as e:
        ap.error(str(e))
    os.makedirs(args.outdir, exist_ok=True)
    for G, nu, beta, soil_E, psi in cases:
        with open(os.path.join(args.outdir, f"{case_name(G, nu, beta, soil_E, psi)}.dat"), "w") as f:
            f.write(deck(G, nu, beta, args.soil_radius, args.steps, args.theta_step, soil_E,
                         args.wall_elements, args.z_refine, psi))
    print(f"wrote {len(cases)} decks to {args.outdir}")


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


def number_list(text):
    """'300,600,900' -> [300.0, 600.0, 900.0] (argparse type)."""
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a comma-separated list of numbers") from None
    if not values:
        raise argparse.ArgumentTypeError("empty list")
    return values


if __name__ == "__main__":
    main()
