#!/usr/bin/env python3
"""Write the decks of thesis model B (chapter 5): input/modelB/<case>.dat for the 18 cases
SE1-3, SD1-3 (elastic soil), FE1-3, FD1-3 (interfaces pipe/soil), PE1-3, PD1-3 (Matsuoka soil),
and input/modelB.dat (= FE1, the README's main job). A preset of scripts/make_pipe_joint.py (one
pipe in soil, --packing 0), which writes the decks; this script holds the thesis's cases.

    python3 scripts/make_model_b.py [--soil-radius 2000] [--outdir input/modelB] [--cases SE1,FD2,...]

Geometry and loads follow SPEC section 8; the choices the thesis leaves open are written into
each deck's comments. Case numbers: 1 typical soil (E = 144), 2 soft (14.4), 3 stiff (1440).

Parametric campaigns beyond the thesis's cases (soil stiffness, pipe-soil friction): give lists,
and a deck is written for every combination of kind (S elastic soil, F interfaces pipe/soil, P
Matsuoka soil), load (E edge, D diagonal), soil E and friction angle:

    python3 scripts/make_model_b.py --outdir input/sweepB --kinds F --loads E --soil-E 50,144,500 \
                                    --phi 10,15,25 [--psi ...]

Case names <kind><load>_Es<E>[_phi<phi>[_psi<psi>]] (phi for F and P only; psi when it differs
from phi), e.g. FE_Es144_phi15, the thesis's FE1. The interface stiffnesses scale with the soil
as the thesis's three soils do (Ks = 50 E_s / 144, Kn = 2 Ks MPa/mm); c = 0.05 MPa throughout.
Then `scripts/campaign.sh NAME input/sweepB/*.dat` runs them and gathers one CSV.

Mesh convergence (scripts/study_mesh_modelB.py runs it): `--refine k` splits every element of the
decks' mesh into k x k x k, and `--element hex20` uses 20-node hexahedra and 8-pair interfaces on
that element layout; the decks are then named <case>_<element>_r<k>.dat:

    python3 scripts/make_model_b.py --outdir /tmp/mesh --cases SE1,FE1 --refine 2 --element hex20
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# the pipe-joint generator writes the deck; this preset holds the thesis's cases
from make_pipe_joint import ELEMENTS, half_pipe_deck, mesh_suffix, number_list, soil_radius_arg  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SOILS = {1: ("typical", 144.0, 50.0, 100.0), 2: ("soft", 14.4, 5.0, 10.0), 3: ("stiff", 1440.0, 500.0, 1000.0)}
THESIS_EDGE_ANGLE = {1: 0.0502, 2: 0.0544, 3: 0.0370}          # Table 7.1, FE cases
THESIS_DIAGONAL = {1: (0.2521, 0.2080), 2: (2.116, 2.071), 3: (0.0587, 0.0238)}  # Table 7.2, FD cases
PHI = 15.0                 # deg: friction and dilation angles of the pipe-soil interface and the Matsuoka soil


def parse_case(case):
    """(kind, load, number or None, soil E, Ks, Kn, phi, psi) of a thesis case id (FE1) or a
    parametric one (FE_Es144_phi15[_psi15], SD_Es14.4)."""
    bad = ValueError(f"case {case!r} is neither a thesis case (S|F|P, E|D, 1|2|3) nor "
                     "<S|F|P><E|D>_Es<E>[_phi<phi>[_psi<psi>]]")
    if len(case) < 2 or case[0] not in "SFP" or case[1] not in "ED":
        raise bad
    kind, load = case[0], case[1]
    if len(case) == 3 and case[2] in "123":
        number = int(case[2])
        _, es, ks, kn = SOILS[number]
        return kind, load, number, es, ks, kn, PHI, PHI
    fields = case[2:].split("_")
    if fields[0] != "":
        raise bad
    values = {}
    for f in fields[1:]:
        key = next((k for k in ("Es", "phi", "psi") if f.startswith(k)), None)
        try:
            values[key] = float(f[len(key):]) if key and key not in values else None
        except ValueError:
            values[key] = None
        if values[key] is None:
            raise bad
    if "Es" not in values or (kind == "S" and ("phi" in values or "psi" in values)):
        raise bad
    es = values["Es"]
    phi = values.get("phi", PHI)
    psi = values.get("psi", phi)
    check_parameters(es, phi, psi)
    ks = 50.0 * es / 144.0
    return kind, load, None, es, ks, 2.0 * ks, phi, psi


def parametric_name(kind, load, es, phi, psi):
    name = f"{kind}{load}_Es{es:g}"
    if kind != "S":
        name += f"_phi{phi:g}" + ("" if psi == phi else f"_psi{psi:g}")
    return name


def check_parameters(es, phi, psi):
    if not es > 0.0:
        raise ValueError(f"E_s = {es:g}: the soil's Young's modulus must be positive")
    if not 0.0 < phi < 90.0:
        raise ValueError(f"phi = {phi:g}: the friction angle must lie in (0, 90) deg")
    if not 0.0 <= psi <= phi:
        raise ValueError(f"psi = {psi:g}: the dilation angle must lie in [0, phi] deg")


def deck(case, r_soil=2000.0, refine=1, element="hex8"):
    """The deck of `case` (make_pipe_joint.half_pipe_deck with the thesis's pipe); `refine` and
    `element` as there: the defaults give the thesis decks."""
    kind, load, number, es, ks, kn, phi, psi = parse_case(case)
    refs = ((THESIS_EDGE_ANGLE[number],) if load == "E" else THESIS_DIAGONAL[number]) if number else ()
    return half_pipe_deck(kind, load, es, ks, kn, phi, psi, r_soil, refine, element, case=case,
                          soil_name=SOILS[number][0] if number else f"E_s = {es:g} MPa", refs=refs,
                          output=f"modelB_{case}{mesh_suffix(refine, element)}", writer="make_model_b.py")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--soil-radius", type=soil_radius_arg, default=2000.0,
                    help="the soil's outer radius (mm, beyond the pipe's 715; default 2000)")
    ap.add_argument("--outdir", default=os.path.join(ROOT, "input", "modelB"))
    ap.add_argument("--cases", default="", help="comma-separated case ids (default: all 18)")
    ap.add_argument("--refine", type=int, default=1,
                    help="split every element into refine^3 (mesh convergence study; default 1)")
    ap.add_argument("--element", choices=ELEMENTS, default="hex8",
                    help="hex8 (the decks), hex20 with 8-pair interfaces, each hexahedron cut into "
                         "two wedge6 or wedge15, or six tet4 or tet10 (kinds S and P only; default hex8)")
    grid = ap.add_argument_group("parametric grid (every combination)")
    grid.add_argument("--kinds", default="F", help="soil models: S elastic, F interfaces, P Matsuoka (default F)")
    grid.add_argument("--loads", default="E", help="E edge, D diagonal (default E)")
    grid.add_argument("--soil-E", type=number_list, help="soil Young's moduli (MPa), e.g. 50,144,500")
    grid.add_argument("--phi", type=number_list, help=f"friction angles (deg; default {PHI:g})")
    grid.add_argument("--psi", type=number_list, help="dilation angles (deg; default: equal to phi)")
    args = ap.parse_args()
    parametric = any(v is not None for v in (args.soil_E, args.phi, args.psi))
    if parametric and args.cases:
        ap.error("give either --cases or the grid lists (--soil-E, --phi, --psi), not both")
    if parametric and not args.soil_E:
        ap.error("a parametric grid needs --soil-E")
    if any(k not in "SFP" for k in args.kinds.replace(",", "")) or any(l not in "ED" for l in args.loads.replace(",", "")):
        ap.error("--kinds takes letters of SFP, --loads letters of ED")
    try:
        if parametric:
            cases = []
            for kind in args.kinds.replace(",", ""):
                for load in args.loads.replace(",", ""):
                    for es in args.soil_E:
                        for phi in ([PHI] if kind == "S" else args.phi or [PHI]):
                            for psi in ([phi] if kind == "S" or not args.psi else args.psi):
                                cases.append(parametric_name(kind, load, es, phi, psi))
        else:
            cases = [c for c in args.cases.split(",") if c] or [f"{k}{l}{n}" for k in "SFP" for l in "ED"
                                                                  for n in (1, 2, 3)]
        for case in dict.fromkeys(cases):
            parse_case(case)
    except ValueError as e:
        ap.error(str(e))
    if args.refine < 1:
        ap.error(f"--refine {args.refine}: must be 1 or more")
    cases = list(dict.fromkeys(cases))
    suffix = mesh_suffix(args.refine, args.element)
    try:    # every deck before any file: a case the element cannot mesh writes nothing
        texts = [deck(case, args.soil_radius, args.refine, args.element) for case in cases]
    except ValueError as e:
        ap.error(f"--element {args.element}: {e}")
    os.makedirs(args.outdir, exist_ok=True)
    for case, text in zip(cases, texts):
        with open(os.path.join(args.outdir, f"{case}{suffix}.dat"), "w") as f:
            f.write(text)
    if not args.cases and not suffix and args.soil_radius == 2000.0 and args.outdir == os.path.join(ROOT, "input", "modelB"):
        text = deck("FE1").replace("OUTPUT, modelB_FE1.h5", "OUTPUT, modelB.h5")
        with open(os.path.join(ROOT, "input", "modelB.dat"), "w") as f:
            f.write(text)
    print(f"wrote {len(cases)} decks to {args.outdir}")


if __name__ == "__main__":
    main()
