"""Write test/data/lists_lame_hex20.dat: the Lame cylinder of lame_hex20.dat with its mesh as explicit
lists (NODES, ELEMENTS, NSET LIST) read from a results file of lame_hex20.dat, renumbered so that
the numbers are neither 1..N nor in the DATAIN order: node i becomes 3 (N - i) + 5 (reversed, with
gaps), element e becomes 2 (n - e) + 101; the rows come in reverse order and every element row goes
on over a second line (as Abaqus writes C3D20 rows). test/test_lists.f90 holds its displacements to
those of the DATAIN deck. Usage:
  feps test/data/lame_hex20.dat --output /tmp/lame.h5
  python3 test/data/make_lists_decks.py /tmp/lame.h5 test/data/lists_lame_hex20.dat"""
import sys
import h5py

HEAD = """! Lame thick cylinder under internal pressure, hex20, plane strain: lame_hex20.dat with its
! mesh as explicit lists (written by make_lists_decks.py): nodes renumbered 3 (N - i) + 5,
! elements 2 (n - e) + 101, rows in reverse order, each element row over two lines.
TITLE, Lame cylinder (lists), p = 10 MPa
MATERIAL, concrete, ELASTIC, E=40000., NU=0.2
GROUP, wall, TYPE=hex20, MATERIAL=concrete
"""
TAIL = """FIX, everything, T, Z, CSYS=3
FSET, bore, GROUP=wall, CSYS=3, R=600., TOL=0.01
PRESSURE, bore, VALUE=10.
"""

def main(results, deck):
    with h5py.File(results, "r") as f:
        xyz = f["mesh/coordinates"][...]
        conn = f["mesh/groups/wall/connectivity"][...]
    n, nel = len(xyz), len(conn)
    node = lambda i: 3 * (n - i) + 5          # i 1-based
    out = [HEAD, "NODES\n"]
    for i in range(n, 0, -1):
        out.append("%d, %s\n" % (node(i), ", ".join(repr(float(c)) for c in xyz[i - 1])))
    out.append("ELEMENTS, wall\n")
    for e in range(nel, 0, -1):
        ids = [node(int(k)) for k in conn[e - 1]]
        out.append("%d, %s,\n" % (2 * (nel - e) + 101, ", ".join(map(str, ids[:15]))))
        out.append("%s\n" % ", ".join(map(str, ids[15:])))
    out.append("NSET, everything, LIST\n")
    ids = sorted(node(i) for i in range(1, n + 1))
    for k in range(0, len(ids), 16):
        out.append(", ".join(map(str, ids[k:k + 16])) + "\n")
    out.append(TAIL)
    open(deck, "w").write("".join(out))



def face_deck(results, box_deck, deck):
    """Write DECK: BOX_DECK with its FSET bore (a coordinate box) given as FSET, bore, LIST rows
    (element, face) read from the results of BOX_DECK (/sets/faces/bore). Usage:
      feps test/data/lame_tet10.dat --output /tmp/t.h5
      python3 test/data/make_lists_decks.py faces /tmp/t.h5 test/data/lame_tet10.dat test/data/lists_faces_tet10.dat"""
    with h5py.File(results, "r") as f:
        rows = f["sets/faces/bore"][...]
    out = []
    for line in open(box_deck):
        if line.startswith("FSET, bore,"):
            out.append("FSET, bore, LIST, GROUP=wall\n")
            out.extend("%d, %d\n" % (e, k) for e, k in rows)
        elif line.startswith("! ") and not out:
            out.append("! " + box_deck.split("/")[-1] + " with its bore faces as FSET LIST rows (element, face),\n"
                       "! written by make_lists_decks.py faces; test/test_lists.f90 holds the two to one another.\n")
            out.append(line)
        else:
            out.append(line)
    open(deck, "w").write("".join(out))


if __name__ == "__main__":
    if sys.argv[1] == "faces":
        face_deck(*sys.argv[2:])
    else:
        main(*sys.argv[1:])
