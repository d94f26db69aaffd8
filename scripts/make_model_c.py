#!/usr/bin/env python3
"""Write the decks of thesis model C (chapter 6): input/modelC/<case>.dat for the 12 cases
C_G<G_p>_nu<nu_p>_b<beta> (G_p = 300, 900 MPa; nu_p = 0.1, 0.4, -0.3; beta = 0.09, 0.27 deg).
A preset of scripts/make_pipe_joint.py (any pipe), which writes the decks; this script holds the
thesis's cases and their names.

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
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from feps_cli import positive, positive_int  # noqa: E402  (argparse types)
# the pipe-joint generator writes the deck; this preset holds the thesis's cases
from make_pipe_joint import (PHI_JOINT, PSI_JOINT, R_OUT, THETA_STEP, WALL_ELEMENTS, attach_negative_lists,  # noqa: E402
                             default_steps, joint_deck, number_list, soil_radius_arg, theta_steps)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

BETAS = (0.09, 0.27)
SHEAR_MODULI = (300.0, 900.0)
POISSON = (0.1, 0.4, -0.3)
# stage 2 steps (thesis 6.3 and 6.4): (beta, G_p) -> steps
STEPS = {(0.09, 300.0): 250, (0.09, 900.0): 300, (0.27, 300.0): 400, (0.27, 900.0): 500}
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
    """Stage-2 steps: the thesis's (6.3, 6.4) for its four (beta, G_p); otherwise
    make_pipe_joint.default_steps (one step per 0.27 / 500 deg, at least 250)."""
    return STEPS.get((beta, G)) or default_steps(beta)


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


def deck(G, nu, beta, r_soil=2000.0, steps=None, theta_step=THETA_STEP, soil_E=SOIL_E,
         wall=WALL_ELEMENTS, z_refine=1, psi=PSI_JOINT):
    """The deck text of one case (make_pipe_joint.joint_deck with the thesis's pipe and joint)."""
    check_parameters(G, nu, beta, soil_E, psi)
    if steps is not None and steps < 1:
        raise ValueError(f"{steps} stage-2 steps: at least 1 is needed")
    ref = thesis_beta_bar(G, nu, beta) if soil_E == SOIL_E and psi == PSI_JOINT else None
    return joint_deck(G, nu, beta, r_soil, steps or stage2_steps(G, beta), theta_step, soil_E, wall, z_refine, psi,
                      name=case_name(G, nu, beta, soil_E, psi), reference=ref, writer="make_model_c.py")


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


if __name__ == "__main__":
    main()
