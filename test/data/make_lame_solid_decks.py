"""Write test/data/lame_{tet4,tet10,wedge6,wedge15}.dat: the Lame cylinder of lame_hex20.dat (its node
lattice) meshed with tetrahedra and wedges (test/test_lame_solids.f90). Usage: python3
test/data/make_lame_solid_decks.py test/data"""
import itertools
NR, NT = 9, 17          # lattice nodes in r and theta (z: 3 layers)
def P(a, b, c):
    return 1 + a + NR * b + NR * NT * c

def mid(p, q):
    return tuple((x + y) // 2 for x, y in zip(p, q))

HEAD = """! Lame thick cylinder under internal pressure, {t}, plane strain (z held everywhere): the
! lattice of lame_hex20.dat (a = 600, b = 715 mm, a quarter annulus, one layer 50 mm thick in z),
! {how}. Symmetry and plane strain through nodal
! cylindrical systems: every node is held in the hoop and axial directions.
TITLE, Lame cylinder {t}, p = 10 MPa
A, 3, 600., 0., 0.,
%, 9, 14.375, 0., 0.,
%, 17, 0., 5.625, 0.,
%, 3, 0., 0., 25.,
E,
GROUP, wall, TYPE={t}, MATERIAL=concrete
"""
TAIL = """E,
MATERIAL, concrete, ELASTIC, E=40000., NU=0.2
NSET, everything, CSYS=3, R=600.:715., TOL=0.01
FIX, everything, T, Z, CSYS=3
FSET, bore, GROUP=wall, CSYS=3, R=600., TOL=0.01
PRESSURE, bore, VALUE=10.
"""

def block(nodes, step, cells):
    """An element block: first element's nodes (lattice points), repeated over cells."""
    ids = [P(*n) for n in nodes]
    k = len(ids)
    lines = ["A, %d, " % k + ", ".join(str(i) for i in ids[:8]) + ","]
    rest = ids[8:]
    while rest:
        lines.append(", ".join(str(i) for i in rest[:10]) + ",")
        rest = rest[10:]
    nr, nt, nz = cells
    lines.append("%%, %d, *, %d, %d," % (nr, k, step))
    lines.append("%%, %d, *, %d, %d," % (nt, k, step * NR))
    if nz > 1:
        lines.append("%%, %d, *, %d, %d," % (nz, k, step * NR * NT))
    lines.append("E,")
    return "\n".join(lines) + "\n"

def kuhn(s):
    """The six Kuhn tetrahedra of the cube [0, s]^3 (corners), positively oriented."""
    out = []
    for perm in itertools.permutations(range(3)):
        v = [(0, 0, 0)]
        cur = [0, 0, 0]
        for axis in perm:
            cur[axis] = s
            v.append(tuple(cur))
        # parity: odd permutations are negatively oriented with this vertex order
        inv = sum(1 for i in range(3) for j in range(i + 1, 3) if perm[i] > perm[j])
        if inv % 2:
            v[1], v[2] = v[2], v[1]
        out.append(v)
    return out

def tet10(v):
    a, b, c, d = v
    return [a, b, c, d, mid(a, b), mid(b, c), mid(c, a), mid(a, d), mid(b, d), mid(c, d)]

def wedges(s):
    """Two wedges of the cell [0, s]^2 x [0, s] split along its (r, theta) diagonal."""
    A = [(0, 0), (s, 0), (s, s)]
    B = [(0, 0), (s, s), (0, s)]
    return [[(x, y, 0) for x, y in t] + [(x, y, s) for x, y in t] for t in (A, B)]

def wedge15(w):
    b, t = w[:3], w[3:]
    return w + [mid(b[0], b[1]), mid(b[1], b[2]), mid(b[2], b[0]),
                mid(t[0], t[1]), mid(t[1], t[2]), mid(t[2], t[0]),
                mid(b[0], t[0]), mid(b[1], t[1]), mid(b[2], t[2])]

decks = {
    "tet4": ("8 x 16 x 2 lattice cells each cut into its six Kuhn tetrahedra (one element block each)",
             [block(v, 1, (8, 16, 2)) for v in kuhn(1)]),
    "tet10": ("4 x 8 x 1 cells of two lattice steps each cut into six Kuhn tetrahedra, whose mid-edge\n"
              "! nodes are the lattice points between (every lattice node is used)",
              [block(tet10(v), 2, (4, 8, 1)) for v in kuhn(2)]),
    "wedge6": ("8 x 16 x 2 lattice cells each cut into two wedges along its (r, theta) diagonal",
               [block(w, 1, (8, 16, 2)) for w in wedges(1)]),
    "wedge15": ("4 x 8 x 1 cells of two lattice steps (the hex20 mesh) each cut into two wedges along\n"
                "! its (r, theta) diagonal",
                [block(wedge15(w), 2, (4, 8, 1)) for w in wedges(2)]),
}
import sys
for t, (how, blocks) in decks.items():
    with open(f"{sys.argv[1]}/lame_{t}.dat", "w") as f:
        f.write(HEAD.format(t=t, how=how) + "".join(blocks) + TAIL)
