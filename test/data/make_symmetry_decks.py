#!/usr/bin/env python3
"""Write a coarse model B (elastic soil, edge load) as the half model (theta 0..180, y = 0
symmetry plane) and as the full 360-degree model: test/data/symmetry_half.dat and
test/data/symmetry_full.dat. The full ring is closed by a last column of elements that reuses
the nodes at theta = 0 (the DATAIN block's duplicate nodes at 360 deg stay unused).
The symmetric half must give the full model's displacements (fpm test checks 1e-6).

    python3 test/data/make_symmetry_decks.py [--outdir test/data]

Without options it rewrites the two decks fpm test reads (the same bytes); --outdir writes them
elsewhere.
"""
import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
NR = 7                      # r = 600, 657.5, 715, 865, 1115, 1465, 2000
NZ = 9                      # z nodes: 0, 100, 200, 725, 1250, 1775, 2300, 2400, 2500
DTH = 15.0


def deck(full):
    nth = (24 if full else 12) + 1          # theta nodes (the full one repeats 0 at 360)
    layer = NR * nth
    lines = [f"! Coarse model B SE1 ({'full 360 deg' if full else 'half, y = 0 symmetry'}): test/data/make_symmetry_decks.py",
             f"TITLE, symmetry check, {'full' if full else 'half'} model",
             "A, 3, 600., 0., 0.,", "%, 3, 57.5, 0., 0.,", "%, -1, 150., 0., 0.,", "%, -1, 250., 0., 0.,",
             "%, -1, 350., 0., 0.,", "%, -1, 535., 0., 0.,",
             f"%, {nth}, 0., {DTH}, 0.,",
             "%, 3, 0., 0., 100.,", "%, -4, 0., 0., 525.,", "%, -2, 0., 0., 100.,", "E,"]
    def solid(name, r0, nr_el, mat):
        out = [f"GROUP, {name}, TYPE=hex8, MATERIAL={mat}"]
        first = [r0, r0 + 1, r0 + 1 + NR, r0 + NR]
        out.append("A, 8, " + ", ".join(str(n) for n in first + [n + layer for n in first]) + ",")
        out += [f"%, {nr_el}, *, 8, 1,", f"%, {nth - 1 - (1 if full else 0)}, *, 8, {NR},", f"%, {NZ - 1}, *, 8, {layer},", "E,"]
        if full:
            # closing column: from theta index nth-2 back to theta index 0
            a = r0 + (nth - 2) * NR
            first = [a, a + 1, r0 + 1, r0]
            out.append("A, 8, " + ", ".join(str(n) for n in first + [n + layer for n in first]) + ",")
            out += [f"%, {nr_el}, *, 8, 1,", f"%, {NZ - 1}, *, 8, {layer},", "E,"]
        return out
    lines += solid("pipe", 1, 2, "concrete")
    lines += solid("soil", 3, 4, "soil")
    lines += ["E,", "MATERIAL, concrete, ELASTIC, E=40000., NU=0.2", "MATERIAL, soil, ELASTIC, E=144., NU=0.2",
              "NSET, soil_outer, CSYS=3, R=2000., TOL=0.01",
              "NSET, anchor, CSYS=3, R=2000., THETA=0., Z=1250., TOL=0.01",
              "FIX, soil_outer, X, Y", "FIX, anchor, Z"]
    if not full:
        lines += ["NSET, symmetry, Y=0., TOL=0.01", "FIX, symmetry, Y"]
    total = "1.0e6" if not full else "2.0e6"
    lines += ["FSET, end_low, GROUP=pipe, Z=0., TOL=0.01", "FSET, end_high, GROUP=pipe, Z=2500., TOL=0.01",
              f"PRESSURE, end_low, TOTAL={total}, VARY=X, ZERO=-220., PEAK=-715.",
              f"PRESSURE, end_high, TOTAL={total}, VARY=X, ZERO=-220., PEAK=-715.", ""]
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--outdir", default=os.path.join(ROOT, "test", "data"),
                    help="folder for symmetry_half.dat and symmetry_full.dat (default test/data, the decks fpm "
                         "test reads)")
    args = ap.parse_args()
    try:
        os.makedirs(args.outdir, exist_ok=True)
        for full in (False, True):
            with open(os.path.join(args.outdir, f"symmetry_{'full' if full else 'half'}.dat"), "w") as f:
                f.write(deck(full))
    except OSError as exc:
        print(f"make_symmetry_decks: {exc.filename}: {exc.strerror}", file=sys.stderr)
        return 1
    print(f"wrote symmetry_half.dat and symmetry_full.dat to {args.outdir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
