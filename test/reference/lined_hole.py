#!/usr/bin/env python3
"""A pipe in elastic ground: the lined-hole closed form (plane strain), its self-checks, the feps
decks of the benchmark and the comparison of a feps result with it.

Kept in test/reference/ as a deliberately independent check: the closed form (Airy stress
functions, a 6 x 6 system) is written here in numpy, apart from test/test_lined_hole.f90's own and
from feps's elements, so that the benchmark's reference does not share code with what it checks.

An elastic ring a <= r <= b (the pipe) in an infinite elastic medium (the soil), far-field stress
sigma_yy = -p, sigma_xx = -K p, the ring bonded to the soil or in full slip (zero shear traction at
r = b, normal traction and radial displacement continuous). The far field is split into its mean
part S_m = -(1 + K) p / 2 (axisymmetric, Lame) and its deviatoric part S_d = (1 - K) p / 2
(Airy function f(r) cos 2 theta: f = A r^2 + B r^4 + C r^-2 + D in the ring, A' r^2 + C' r^-2 + D'
in the soil with A' = -S_d / 2), whose constants solve a 6 x 6 linear system. Displacements of the
Airy terms (plane strain, kappa = 3 - 4 nu), 2 mu u_r / cos 2t and 2 mu u_t / sin 2t:
r^2: -2 r, 2 r; r^4: (kappa - 3) r^3, (kappa + 3) r^3; r^-2: 2 r^-3, 2 r^-3; 1: (kappa + 1) / r,
-(kappa - 1) / r.

  lined_hole.py [--K 0.5 --p 0.1 --Es 144 --nus 0.2 ...]        the reference at r = a and r = b
  lined_hole.py --check                                          the reference's self-checks
  lined_hole.py --decks DIR [--level 1|2] [--dim 2|3] ...        feps decks (bonded, slip, friction)
  lined_hole.py RESULT.h5 [RESULT.h5 ...]                        feps against the reference
"""
import argparse
import math
import os
import sys

import numpy as np

A_BORE, B_OUT = 600.0, 715.0


class LinedHole:
    """The exact plane-strain solution; r, theta arrays, region 'ring' or 'soil'."""

    def __init__(self, a=A_BORE, b=B_OUT, Er=40000.0, nur=0.2, Es=144.0, nus=0.2, p=0.1, K=0.5,
                 bond="bonded"):
        if bond not in ("bonded", "slip"):
            raise ValueError("bond must be bonded or slip")
        self.a, self.b, self.p, self.K, self.bond = a, b, p, K, bond
        self.mu = {"ring": Er / (2 * (1 + nur)), "soil": Es / (2 * (1 + nus))}
        self.nu = {"ring": nur, "soil": nus}
        self.kappa = {k: 3 - 4 * v for k, v in self.nu.items()}
        self.Sm = -(1 + K) * p / 2
        self.Sd = (1 - K) * p / 2
        self._solve()

    # --- axisymmetric part: s_rr = al + be / r^2, s_tt = al - be / r^2,
    #     2 mu u_r = (1 - 2 nu) al r - be / r
    def _axi_rows(self):
        a, b = self.a, self.b
        mr, ms, nr, ns = self.mu["ring"], self.mu["soil"], self.nu["ring"], self.nu["soil"]
        # unknowns al1, be1, be2 (al2 = Sm)
        m = np.array([[1.0, 1 / a**2, 0.0],
                      [1.0, 1 / b**2, -1 / b**2],
                      [(1 - 2 * nr) * b / (2 * mr), -1 / (b * 2 * mr), 1 / (b * 2 * ms)]])
        rhs = np.array([0.0, self.Sm, (1 - 2 * ns) * self.Sm * b / (2 * ms)])
        return m, rhs

    # --- cos 2 theta part: rows of the stress and displacement amplitudes in the constants
    @staticmethod
    def _srr(r):      # s_rr / cos 2t  from A, B, C, D
        return [-2.0, 0.0, -6 / r**4, -4 / r**2]

    @staticmethod
    def _stt(r):
        return [2.0, 12 * r**2, 6 / r**4, 0.0]

    @staticmethod
    def _srt(r):      # s_rt / sin 2t
        return [2.0, 6 * r**2, -6 / r**4, -2 / r**2]

    def _ur(self, r, region):    # u_r / cos 2t
        k, mu = self.kappa[region], self.mu[region]
        return [v / (2 * mu) for v in (-2 * r, (k - 3) * r**3, 2 / r**3, (k + 1) / r)]

    def _ut(self, r, region):    # u_t / sin 2t
        k, mu = self.kappa[region], self.mu[region]
        return [v / (2 * mu) for v in (2 * r, (k + 3) * r**3, 2 / r**3, -(k - 1) / r)]

    def _dev_rows(self):
        """Rows of the 6 x 6 system in A B C D (ring) and C' D' (soil); the soil's far-field term
        A' = -S_d / 2 goes to the right-hand side."""
        a, b = self.a, self.b
        A2 = -self.Sd / 2
        m = np.zeros((6, 6))
        rhs = np.zeros(6)
        m[0, :4] = self._srr(a)                          # s_rr(a) = 0
        m[1, :4] = self._srt(a)                          # s_rt(a) = 0

        def continuous(i, ring_row, soil_row):          # ring - soil = 0 at r = b
            m[i, :4] = ring_row
            m[i, 4:] = [-v for v in soil_row[2:4]]
            rhs[i] = soil_row[0] * A2
        continuous(2, self._srr(b), self._srr(b))
        continuous(3, self._ur(b, "ring"), self._ur(b, "soil"))
        if self.bond == "bonded":
            continuous(4, self._srt(b), self._srt(b))
            continuous(5, self._ut(b, "ring"), self._ut(b, "soil"))
        else:
            m[4, :4] = self._srt(b)                      # s_rt(b-) = 0
            m[5, 4:] = self._srt(b)[2:4]                 # s_rt(b+) = 0
            rhs[5] = -self._srt(b)[0] * A2
        return m, rhs

    def _solve(self):
        m, rhs = self._axi_rows()
        self.axi = np.linalg.solve(m, rhs)
        self.axi_residual = np.max(np.abs(m @ self.axi - rhs)) / max(np.max(np.abs(rhs)), 1e-300)
        m, rhs = self._dev_rows()
        if self.Sd == 0.0:
            self.dev = np.zeros(6)
        else:
            self.dev = np.linalg.solve(m, rhs)
        self.dev_residual = np.max(np.abs(m @ self.dev - rhs)) / max(np.max(np.abs(rhs)), 1e-300)
        self.A2 = -self.Sd / 2

    def _consts(self, region):
        if region == "ring":
            al, be = self.axi[0], self.axi[1]
            abcd = self.dev[:4]
        else:
            al, be = self.Sm, self.axi[2]
            abcd = np.array([self.A2, 0.0, self.dev[4], self.dev[5]])
        return al, be, abcd

    def stress(self, r, t, region):
        """(s_rr, s_tt, s_rt) at r, theta (radians)."""
        r, t = np.asarray(r, float), np.asarray(t, float)
        al, be, c = self._consts(region)
        c2, s2 = np.cos(2 * t), np.sin(2 * t)
        amp = lambda rows: sum(ci * ri for ci, ri in zip(c, rows))
        srr = al + be / r**2 + amp(self._srr(r)) * c2
        stt = al - be / r**2 + amp(self._stt(r)) * c2
        srt = amp(self._srt(r)) * s2
        return srr, stt, srt

    def displacement(self, r, t, region):
        """(u_r, u_theta) at r, theta (radians)."""
        r, t = np.asarray(r, float), np.asarray(t, float)
        al, be, c = self._consts(region)
        mu, nu = self.mu[region], self.nu[region]
        ur = ((1 - 2 * nu) * al * r - be / r) / (2 * mu)
        ur = ur + sum(ci * ri for ci, ri in zip(c, self._ur(r, region))) * np.cos(2 * t)
        ut = sum(ci * ri for ci, ri in zip(c, self._ut(r, region))) * np.sin(2 * t)
        return ur, ut

    def thrust_moment(self, t):
        """Hoop thrust N = int s_tt dr (N/mm, compression negative) and bending moment
        M = int s_tt (r - (a + b) / 2) dr (N mm/mm) of the ring at theta t: 10-point Gauss."""
        x, w = np.polynomial.legendre.leggauss(10)
        h = (self.b - self.a) / 2
        r = self.a + h * (1 + x)
        stt = self.stress(r, t, "ring")[1]
        return h * np.sum(w * stt), h * np.sum(w * stt * (r - (self.a + self.b) / 2))

    def region(self, r):
        return np.where(np.asarray(r) <= self.b, "ring", "soil")


# ----------------------------------------------------------------------------- self-checks

def kirsch(a, Sm, Sd, r, t):
    """Kirsch's hole of radius a in a plate under s_xx = Sm + Sd, s_yy = Sm - Sd."""
    q = (a / r)**2
    c2, s2 = np.cos(2 * t), np.sin(2 * t)
    srr = Sm * (1 - q) + Sd * (1 - 4 * q + 3 * q * q) * c2
    stt = Sm * (1 + q) - Sd * (1 + 3 * q * q) * c2
    srt = -Sd * (1 + 2 * q - 3 * q * q) * s2
    return srr, stt, srt


def strains(ref, r, t, region, h=1e-6):
    """Strains from the displacements by central differences, and from Hooke's law."""
    ur, ut = ref.displacement(r, t, region)
    urp, utp = ref.displacement(r * (1 + h), t, region)
    urm, utm = ref.displacement(r * (1 - h), t, region)
    urtp, uttp = ref.displacement(r, t + h, region)
    urtm, uttm = ref.displacement(r, t - h, region)
    err = (urp - urm) / (2 * r * h)
    ett = (ur + (uttp - uttm) / (2 * h)) / r
    grt = (urtp - urtm) / (2 * h) / r + (utp - utm) / (2 * r * h) - ut / r
    srr, stt, srt = ref.stress(r, t, region)
    mu, nu = ref.mu[region], ref.nu[region]
    err_h = ((1 - nu) * srr - nu * stt) / (2 * mu)
    ett_h = ((1 - nu) * stt - nu * srr) / (2 * mu)
    grt_h = srt / mu
    return np.array([err - err_h, ett - ett_h, grt - grt_h])


def equilibrium(ref, r, t, region, h=1e-6):
    """Residuals of the polar equilibrium equations by central differences (per unit volume)."""
    srr, stt, srt = ref.stress(r, t, region)
    dr = [(x - y) / (2 * r * h) for x, y in zip(ref.stress(r * (1 + h), t, region), ref.stress(r * (1 - h), t, region))]
    dt = [(x - y) / (2 * h) for x, y in zip(ref.stress(r, t + h, region), ref.stress(r, t - h, region))]
    e1 = dr[0] + dt[2] / r + (srr - stt) / r
    e2 = dr[2] + dt[1] / r + 2 * srt / r
    return np.array([e1, e2])


def self_checks(verbose=True):
    """The reference's checks; returns the number of failures."""
    fails = 0

    def report(name, value, tol):
        nonlocal fails
        ok = value <= tol
        fails += not ok
        if verbose:
            print(f"  {'ok  ' if ok else 'FAIL'} {name}: {value:.3e} (tolerance {tol:.0e})")

    t = np.linspace(0.0, math.pi / 2, 19)
    cases = [dict(Es=144.0, nus=0.2, K=0.5), dict(Es=1440.0, nus=0.3, K=0.5), dict(Es=144.0, nus=0.45, K=0.0),
             dict(Es=1440.0, nus=0.45, K=1.0)]
    for c in cases:
        for bond in ("bonded", "slip"):
            ref = LinedHole(bond=bond, **c)
            tag = f"{bond} Es={c['Es']:g} nus={c['nus']:g} K={c['K']:g}"
            report(f"{tag}: the linear systems' residuals", max(ref.axi_residual, ref.dev_residual), 1e-13)
            a, b, p = ref.a, ref.b, ref.p
            srr, stt, srt = ref.stress(a, t, "ring")
            report(f"{tag}: bore traction-free", np.max(np.abs([srr, srt])) / p, 1e-12)
            sr1, _, st1 = ref.stress(b, t, "ring")
            sr2, _, st2 = ref.stress(b, t, "soil")
            report(f"{tag}: s_rr continuous at r = b", np.max(np.abs(sr1 - sr2)) / p, 1e-12)
            if bond == "bonded":
                report(f"{tag}: s_rt continuous at r = b", np.max(np.abs(st1 - st2)) / p, 1e-12)
            else:
                report(f"{tag}: s_rt = 0 on both sides of r = b", np.max(np.abs([st1, st2])) / p, 1e-12)
            u1, v1 = ref.displacement(b, t, "ring")
            u2, v2 = ref.displacement(b, t, "soil")
            uscale = p * b / ref.mu["soil"]
            report(f"{tag}: u_r continuous at r = b", np.max(np.abs(u1 - u2)) / uscale, 1e-12)
            if bond == "bonded":
                report(f"{tag}: u_theta continuous at r = b", np.max(np.abs(v1 - v2)) / uscale, 1e-12)
            far = 1e5 * b
            srr, stt, srt = ref.stress(far, t, "soil")
            sxx_far = srr * np.cos(t)**2 + stt * np.sin(t)**2 - 2 * srt * np.sin(t) * np.cos(t)
            syy_far = srr * np.sin(t)**2 + stt * np.cos(t)**2 + 2 * srt * np.sin(t) * np.cos(t)
            report(f"{tag}: far field s_xx = -K p, s_yy = -p",
                   max(np.max(np.abs(sxx_far + ref.K * p)), np.max(np.abs(syy_far + p))) / p, 1e-9)
            worst_eq, worst_c = 0.0, 0.0
            for region, rr in (("ring", np.linspace(a, b, 5)), ("soil", np.linspace(b, 5 * b, 5))):
                for r in rr:
                    tt = t[1:-1]
                    worst_eq = max(worst_eq, np.max(np.abs(equilibrium(ref, r, tt, region))) * r / p)
                    mu = ref.mu[region]
                    worst_c = max(worst_c, np.max(np.abs(strains(ref, r, tt, region))) * mu / p)
            report(f"{tag}: equilibrium (finite differences, x r / p)", worst_eq, 1e-6)
            report(f"{tag}: strains of the displacements = Hooke's (finite differences, x mu / p)", worst_c, 1e-6)
    # ring = soil, bonded: Kirsch's hole of radius a
    for nu, K in ((0.2, 0.5), (0.3, 0.0), (0.45, 1.0)):
        ref = LinedHole(Er=144.0, nur=nu, Es=144.0, nus=nu, K=K, bond="bonded")
        worst = 0.0
        for region, rr in (("ring", np.linspace(ref.a, ref.b, 4)), ("soil", np.linspace(ref.b, 4 * ref.b, 4))):
            for r in rr:
                got = np.array(ref.stress(r, t, region))
                want = np.array(kirsch(ref.a, ref.Sm, ref.Sd, r, t))
                worst = max(worst, np.max(np.abs(got - want)) / ref.p)
        report(f"ring = soil (nu {nu:g}, K {K:g}), bonded: Kirsch's stresses", worst, 1e-12)
    # K = 1: slip and bond coincide, and the composite Lame cylinder
    for Es, nus in ((144.0, 0.2), (1440.0, 0.45)):
        r1 = LinedHole(Es=Es, nus=nus, K=1.0, bond="bonded")
        r2 = LinedHole(Es=Es, nus=nus, K=1.0, bond="slip")
        r_, t_ = np.array([600.0, 650.0, 715.0]), np.array([0.0, 0.7, 1.3])
        d = max(np.max(np.abs(np.array(r1.stress(r_, t_, "ring")) - np.array(r2.stress(r_, t_, "ring")))), 0.0) / r1.p
        report(f"K = 1 (Es {Es:g}): bonded = slip", d, 1e-14)
        # composite cylinder by hand: the soil's radial pressure q on the ring (q > 0 compressive)
        # from u_ring(b) under q (Lame) = u_soil(b) under q at b and p at infinity
        a, b, p = r1.a, r1.b, r1.p
        mr, nr, ms, ns = r1.mu["ring"], r1.nu["ring"], r1.mu["soil"], r1.nu["soil"]
        ring_c = -b * (b * b * (1 - 2 * nr) + a * a) / (2 * mr * (b * b - a * a))   # u_ring(b) / q
        # soil: s_rr = -p + (p - q) b^2 / r^2, 2 mu u(b) = -(1 - 2 nu) p b - (p - q) b = u_ring(b)
        q = p * ((1 - 2 * ns) + 1) / (2 * ms) / (1 / (2 * ms) - ring_c / b)
        srr_b = r1.stress(b, 0.0, "ring")[0]
        report(f"K = 1 (Es {Es:g}): contact pressure = composite Lame cylinder", abs(srr_b + q) / p, 1e-12)
    return fails


# ----------------------------------------------------------------------------- decks

def graded(r0, r1, n, first):
    """n element sizes from r0 to r1, geometric, the first about `first` (uniform if it fits)."""
    if first * n >= r1 - r0:
        return [(r1 - r0) / n] * n
    lo, hi = 1.0, 10.0
    for _ in range(200):
        q = 0.5 * (lo + hi)
        if first * (q**n - 1) / (q - 1) > r1 - r0:
            hi = q
        else:
            lo = q
    h = [first * q**i for i in range(n)]
    s = (r1 - r0) / sum(h)
    return [x * s for x in h]


def node_block(r0, sizes, nt, nz_layers=None, dz=None):
    """DATAIN node block of a polar lattice (theta fastest, then r, then z), quadratic elements:
    2 nt + 1 nodes over 90 degrees, 2 len(sizes) + 1 in r, 3 in z for a slice."""
    lines = [f"A, 3, {r0:.10f}, 0., 0.,", f"%, {2 * nt + 1}, 0., {45.0 / nt:.12g}, 0.,"]
    first = True
    for h in sizes:
        if first:
            lines.append(f"%, 3, {h / 2:.12g}, 0., 0.,")
            first = False
        else:
            lines.append(f"%, -2, {h / 2:.12g}, 0., 0.,")
    if dz is not None:
        lines.append(f"%, 3, 0., 0., {dz / 2:.12g},")
    lines.append("E,")
    return lines


def tri6_blocks(first_node, nt, nr, row0):
    """The two tri6 element blocks of radial element rows row0 .. row0 + nr - 1 of a lattice."""
    NT = 2 * nt + 1
    nid = lambda i, j: first_node + j + NT * i
    i, j = 2 * row0, 0
    lo = [nid(i, j), nid(i + 2, j), nid(i + 2, j + 2), nid(i + 1, j), nid(i + 2, j + 1), nid(i + 1, j + 1)]
    up = [nid(i, j), nid(i + 2, j + 2), nid(i, j + 2), nid(i + 1, j + 1), nid(i + 1, j + 2), nid(i, j + 1)]
    out = []
    for e in (lo, up):
        out += ["A, 6, " + ", ".join(map(str, e)) + ",", f"%, {nr}, *, 6, {2 * NT},", f"%, {nt}, *, 6, 2,", "E,"]
    return out


def hex20_block(first_node, nt, nrad, nr, row0):
    """hex20 block of radial rows row0 .. of a lattice with 2 nrad + 1 radial and 3 z nodes."""
    NT, NR = 2 * nt + 1, 2 * nrad + 1
    nid = lambda i, j, k: first_node + j + NT * i + NT * NR * k
    i = 2 * row0
    c = lambda k: [nid(i, 0, k), nid(i + 2, 0, k), nid(i + 2, 2, k), nid(i, 2, k)]
    m = lambda k: [nid(i + 1, 0, k), nid(i + 2, 1, k), nid(i + 1, 2, k), nid(i, 1, k)]
    e = c(0) + c(2) + m(0) + m(2) + c(1)
    return ["A, 20, " + ", ".join(map(str, e[:10])) + ",", ", ".join(map(str, e[10:])) + ",",
            f"%, {nr}, *, 20, {2 * NT},", f"%, {nt}, *, 20, 2,", "E,"]


def ref_tractions(ref, R):
    """The exact tractions on r = R (soil) as feps TRACTION records' values:
    s_rr = c0 + c2 (x / R)^2, s_rt = c3 (x / R)(y / R)."""
    srr0 = ref.stress(R, 0.0, "soil")[0]                 # S + D
    srr90 = ref.stress(R, math.pi / 2, "soil")[0]        # S - D
    srt45 = ref.stress(R, math.pi / 4, "soil")[2]        # T
    D = (srr0 - srr90) / 2
    return srr90, 2 * D, 2 * srt45


def write_deck(path, dim, bond, level, Es, nus, K, p, phi=None, rout_factor=10.0, far="exact", nodal=False):
    ref = LinedHole(Es=Es, nus=nus, K=K, p=p, bond="slip" if bond != "bonded" else "bonded")
    a, b = A_BORE, B_OUT
    R = rout_factor * b
    nr_ring, nt = 2 * level, 12 * level
    ns = 8 * level
    ring_sizes = [(b - a) / nr_ring] * nr_ring
    soil_sizes = graded(b, R, ns, (b - a) / nr_ring)
    dz = 50.0
    L = ["! A pipe in elastic ground (test/reference/lined_hole.py): ring a = 600 .. b = 715 mm in soil to "
         f"R = {R:g} mm, quarter model,",
         f"! far field s_yy = -p, s_xx = -K p; {bond}; " + ("plane strain, tri6" if dim == 2 else
                                                            "a hex20 slice, uz held") + f"; mesh level {level}.",
         "! Outer boundary: " + ("the exact solution's tractions (no truncation error)." if far == "exact"
                                 else "the uniform far-field tractions (truncation error ~ (b / R)^2)."),
         f"TITLE, lined hole {bond} {dim}D level {level}",
         f"PARAMETERS, a={a:g}, b={b:g}, p={p:g}, K={K:g}, bond={bond}, "
         f"far={far}, R_out={R:g}"]
    nodes = []
    if bond == "bonded":
        nodes += node_block(a, ring_sizes + soil_sizes, nt, dz=dz if dim == 3 else None)
        first_soil, soil_row0 = 1, nr_ring
        nrad_ring = nrad_soil = nr_ring + ns
    else:
        nodes += node_block(a, ring_sizes, nt, dz=dz if dim == 3 else None)
        nodes += node_block(b, soil_sizes, nt, dz=dz if dim == 3 else None)
        nz = 3 if dim == 3 else 1
        first_soil = 1 + (2 * nt + 1) * (2 * nr_ring + 1) * nz
        soil_row0 = 0
        nrad_ring, nrad_soil = nr_ring, ns
    L += nodes
    if dim == 2:
        L += ["GROUP, ring, TYPE=tri6, MATERIAL=concrete"] + tri6_blocks(1, nt, nr_ring, 0)
        L += ["GROUP, soil, TYPE=tri6, MATERIAL=soil"] + tri6_blocks(first_soil, nt, ns, soil_row0)
    else:
        L += ["GROUP, ring, TYPE=hex20, MATERIAL=concrete"] + hex20_block(1, nt, nrad_ring, nr_ring, 0)
        L += ["GROUP, soil, TYPE=hex20, MATERIAL=soil"] + hex20_block(first_soil, nt, nrad_soil, ns, soil_row0)
    if bond != "bonded":
        NT = 2 * nt + 1
        if dim == 2:
            # lower layer: the ring's outer nodes in decreasing theta (normal +r); upper: the soil's
            io = 1 + NT * 2 * nr_ring
            e = [io + 2, io, io + 1, first_soil + 2, first_soil, first_soil + 1]
            L += ["! lower layer: the ring at r = b, listed in decreasing theta (normal +r, tau = -s_rtheta)",
                  f"GROUP, contact, TYPE=interface-line3{'-nodal' if nodal else ''}, MATERIAL=contact",
                  "A, 6, " + ", ".join(map(str, e)) + ",", f"%, {nt}, *, 6, 2,", "E,"]
        else:
            NRr, NRs = 2 * nr_ring + 1, 2 * ns + 1
            lo = lambda j, k: 1 + j + NT * 2 * nr_ring + NT * NRr * k
            up = lambda j, k: first_soil + j + NT * NRs * k
            order = [(0, 0), (2, 0), (2, 2), (0, 2), (1, 0), (2, 1), (1, 2), (0, 1)]
            e = [lo(j, k) for j, k in order] + [up(j, k) for j, k in order]
            L += ["! lower layer: the ring at r = b, s1 along +theta, s2 along +z (normal +r, tau1 = s_rtheta)",
                  f"GROUP, contact, TYPE=interface-quad8{'-nodal' if nodal else ''}, MATERIAL=contact",
                  "A, 16, " + ", ".join(map(str, e[:8])) + ",", ", ".join(map(str, e[8:])) + ",",
                  f"%, {nt}, *, 16, 2,", "E,"]
    L.append("E,")
    L.append("MATERIAL, concrete, ELASTIC, E=40000., NU=0.2")
    L.append(f"MATERIAL, soil, ELASTIC, E={Es:g}, NU={nus:g}")
    if bond == "slip":
        L.append("! full slip: phi = c = 0 leaves tau = 0 exactly at every point in compression")
        L.append("MATERIAL, contact, INTERFACE, KN=1000., KS=1000., PHI=0., C=0.")
    elif bond == "bilateral":
        L.append("! full slip that also holds in tension: no shear stiffness, and with phi = 0, c > 0 the")
        L.append("! interface never reaches its gap zone (c - sigma_n tan phi <= 0), so it never opens")
        L.append("MATERIAL, contact, INTERFACE, KN=1000., KS=0., PHI=0., C=1.")
    elif bond == "friction":
        L.append(f"MATERIAL, contact, INTERFACE, KN=1000., KS=1000., PHI={phi:g}, C=0.")
    L += ["NSET, xzero, X=0.", "NSET, yzero, Y=0.", "FIX, xzero, X", "FIX, yzero, Y"]
    if dim == 3:
        L += ["NSET, all, Z=0.:100.", "FIX, all, Z"]
    L.append(f"FSET, outer, GROUP=soil, CSYS=3, R={R:.10g}, TOL=0.01")
    if far == "exact":
        c0, c2, c3 = ref_tractions(ref, R)
        L += [f"TRACTION, outer, CSYS=3, R={c0:.15e}",
              f"TRACTION, outer, CSYS=3, R={c2:.15e}, VARY=X, ZERO=0., PEAK={R:.10g}, VARY2=X, ZERO2=0., "
              f"PEAK2={R:.10g}",
              f"TRACTION, outer, CSYS=3, T={c3:.15e}, VARY=X, ZERO=0., PEAK={R:.10g}, VARY2=Y, ZERO2=0., "
              f"PEAK2={R:.10g}"]
    else:
        L += [f"TRACTION, outer, X={-K * p:.15e}, VARY=X, ZERO=0., PEAK={R:.10g}",
              f"TRACTION, outer, Y={-p:.15e}, VARY=Y, ZERO=0., PEAK={R:.10g}"]
    if bond == "bonded":
        pass
    elif bond in ("slip", "bilateral"):
        L.append("STAGE, load, STEPS=1, METHOD=full-newton-raphson")
    else:
        L.append("! stick and slip: full Newton with the line search; with the Gauss rule (not -nodal) it cycles on the")
        L.append("! level-1 mesh for phi = 15 (docs/verification.md, \"A pipe in elastic ground\")")
        L.append("STAGE, load, STEPS=10, METHOD=full-newton-raphson, LINESEARCH=energy")
    L.append("FIELDS, all, nodal_stress, nodal_interface")
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")


# ----------------------------------------------------------------------------- comparison

def polar_stress(s, t):
    """(s_rr, s_tt, s_rt) of rows sxx syy szz syz sxz sxy at angles t."""
    sxx, syy, sxy = s[:, 0], s[:, 1], s[:, 5]
    c, n = np.cos(t), np.sin(t)
    srr = sxx * c * c + syy * n * n + 2 * sxy * c * n
    stt = sxx * n * n + syy * c * c - 2 * sxy * c * n
    srt = (syy - sxx) * c * n + sxy * (c * c - n * n)
    return srr, stt, srt


def compare(path, quiet=False):
    """Errors of a feps result against the reference: dict quantity -> (max error / scale, scale)."""
    import h5py
    f = h5py.File(path, "r")
    pa = f["summary"].attrs
    par = lambda k: float(pa[f"parameter_{k}"])
    bond = pa["parameter_bond"]
    bond = bond.decode() if isinstance(bond, bytes) else str(bond)
    mat = f["materials/soil"].attrs
    refs = {k: LinedHole(a=par("a"), b=par("b"), Es=float(mat["e"]), nus=float(mat["nu"]), p=par("p"), K=par("K"),
                         bond=k) for k in ("bonded", "slip")}
    ref = refs["slip" if bond in ("slip", "bilateral") else "bonded"]
    last = max(f["steps"], key=int)
    st = f["steps"][last]
    x = f["mesh/coordinates"][...]
    r = np.hypot(x[:, 0], x[:, 1])
    t = np.arctan2(x[:, 1], x[:, 0])
    u = st["displacement"][...]
    ur = u[:, 0] * np.cos(t) + u[:, 1] * np.sin(t)
    used = lambda g: np.unique(f[f"mesh/groups/{g}/connectivity"][...].ravel() - 1)
    ring_nodes, soil_nodes = used("ring"), used("soil")
    on = lambda nodes, rad: nodes[np.abs(r[nodes] - rad) < 1e-6 * rad]
    out = {}
    if bond not in ("bonded", "slip", "bilateral"):
        return key_values(f, st, ref, refs, r, t, ur, ring_nodes, on, quiet)

    def add(name, got, want, scale):
        scale = scale if scale > 1e-9 * ref.p else ref.p     # an exact zero (K = 1): relative to p
        out[name] = (np.max(np.abs(got - want)) / scale, scale)

    p = ref.p
    bore, ring_b, soil_b = on(ring_nodes, ref.a), on(ring_nodes, ref.b), on(soil_nodes, ref.b)
    sr = st["nodal_stress/ring"][...]
    ss = st["nodal_stress/soil"][...]
    for nodes, s, region, tag in ((bore, sr, "ring", "bore"), (ring_b, sr, "ring", "ring r=b"),
                                  (soil_b, ss, "soil", "soil r=b")):
        got = polar_stress(s[nodes], t[nodes])
        want = ref.stress(r[nodes], t[nodes], region)
        add(f"s_tt {tag}", got[1], want[1], np.max(np.abs(want[1])))
        if tag != "bore":
            add(f"s_rr {tag}", got[0], want[0], np.max(np.abs(want[0])))
            if ref.bond == "bonded":
                add(f"s_rt {tag}", got[2], want[2], np.max(np.abs(want[2])))
            else:
                add(f"s_rt {tag} (exact 0; / p)", got[2], want[2], p)
    if "nodal_interface" in st and "contact" in st["nodal_interface"]:
        ni = st["nodal_interface/contact"][...]
        sn, tau = ni[ring_b, -1], ni[ring_b, 0]
        want = ref.stress(r[ring_b], t[ring_b], "ring")
        add("interface s_n", sn, want[0], np.max(np.abs(want[0])))
        add("interface tau (/ p)", np.abs(tau), np.abs(want[2]), p)
    want_u = ref.displacement(r[bore], t[bore], "ring")[0]
    add("u_r bore", ur[bore], want_u, np.max(np.abs(want_u)))
    for deg in (0.0, 90.0):
        line = ring_nodes[(np.abs(t[ring_nodes] - math.radians(deg)) < 1e-9)]
        line = np.unique(np.round(r[line], 9), return_index=True)[1], line
        nodes = line[1][line[0]]
        nodes = nodes[np.argsort(r[nodes])]
        if len(nodes) % 2 == 1 and len(nodes) >= 3:
            stt = polar_stress(sr[nodes], t[nodes])[1]
            rr = r[nodes]
            h = (rr[-1] - rr[0]) / (len(rr) - 1)
            wts = np.ones(len(rr))
            wts[1:-1:2], wts[2:-1:2] = 4, 2
            n_fe = h / 3 * np.sum(wts * stt)
            m_fe = h / 3 * np.sum(wts * stt * (rr - (ref.a + ref.b) / 2))
            n_ex, m_ex = ref.thrust_moment(math.radians(deg))
            out[f"thrust N {deg:g} deg"] = (abs(n_fe - n_ex) / abs(n_ex), n_ex)
            out[f"moment M {deg:g} deg"] = (abs(m_fe - m_ex) / abs(m_ex), m_ex)
    if not quiet:
        print(f"{path}: {bond}, K = {ref.K:g}, soil E = {float(mat['e']):g} nu = {float(mat['nu']):g}; "
              f"max |feps - exact| over the nodes / max |exact| on the arc")
        for k, (e, s) in out.items():
            print(f"  {k:32s} {e:10.2e}   (scale {s:.5g})")
    return out


def key_values(f, st, ref, refs, r, t, ur, ring_nodes, on, quiet):
    """A frictional interface has no closed form: its values at theta = 0 and 90 degrees beside
    the bonded and the full-slip ones. Returns {name: (feps, bonded, slip)}."""
    sr = st["nodal_stress/ring"][...]
    out = {}
    for tag, rad in (("bore", ref.a), ("r=b", ref.b)):
        nodes = on(ring_nodes, rad)
        for deg in (0.0, 90.0):
            n = nodes[np.argmin(np.abs(t[nodes] - math.radians(deg)))]
            got = polar_stress(sr[n:n + 1], t[n:n + 1])[1][0]
            out[f"s_tt {tag} {deg:g} deg"] = (got,) + tuple(float(refs[k].stress(rad, t[n], "ring")[1]) for k in refs)
            if tag == "bore":
                out[f"u_r {tag} {deg:g} deg"] = (ur[n],) + tuple(float(refs[k].displacement(rad, t[n], "ring")[0])
                                                              for k in refs)
    if not quiet:
        print(f"{f.filename}: frictional interface (phi = {float(f['materials/contact'].attrs['phi']):g}), "
              f"no closed form: feps, bonded, full slip (closed forms)")
        for k, (g, b, s_) in out.items():
            inside = min(b, s_) <= g <= max(b, s_)
            print(f"  {k:20s} {g:12.5g} {b:12.5g} {s_:12.5g}  {'between' if inside else 'OUTSIDE'}")
    return out


def print_reference(ref):
    print(f"lined hole, {ref.bond}: a = {ref.a:g}, b = {ref.b:g}, p = {ref.p:g}, K = {ref.K:g}, "
          f"ring mu = {ref.mu['ring']:.6g} nu = {ref.nu['ring']:g}, soil mu = {ref.mu['soil']:.6g} nu = {ref.nu['soil']:g}")
    print(f"{'theta':>6} {'s_tt(a)':>14} {'s_tt(b-)':>14} {'s_rr(b)':>14} {'s_rt(b)':>14} {'s_tt(b+)':>14} {'u_r(a)':>14}")
    for deg in (0.0, 22.5, 45.0, 67.5, 90.0):
        t = math.radians(deg)
        sa = ref.stress(ref.a, t, "ring")
        sb = ref.stress(ref.b, t, "ring")
        so = ref.stress(ref.b, t, "soil")
        ua = ref.displacement(ref.a, t, "ring")[0]
        print(f"{deg:6.1f} {sa[1]:14.7e} {sb[1]:14.7e} {sb[0]:14.7e} {sb[2]:14.7e} {so[1]:14.7e} {ua:14.7e}")
    for deg in (0.0, 90.0):
        n, m = ref.thrust_moment(math.radians(deg))
        print(f"ring at theta = {deg:g}: thrust N = {n:.7e} N/mm, moment M = {m:.7e} N mm/mm")
    print("constants: axisymmetric al1 be1 be2 =", " ".join(f"{v:.10e}" for v in ref.axi))
    print("           cos 2theta A B C D C' D' =", " ".join(f"{v:.10e}" for v in ref.dev))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="*", help="feps results files to compare")
    ap.add_argument("--check", action="store_true", help="run the reference's self-checks")
    ap.add_argument("--decks", metavar="DIR", help="write the benchmark's decks into DIR")
    ap.add_argument("--level", type=int, default=1)
    ap.add_argument("--dim", type=int, default=2, choices=(2, 3))
    ap.add_argument("--bond", default="bonded", choices=("bonded", "slip", "bilateral", "friction"),
                    help="bonded (shared nodes); slip (PHI = C = 0: opens in tension); bilateral (KS = 0, "
                         "PHI = 0, C = 1: slip that holds in tension); friction (--phi)")
    ap.add_argument("--phi", type=float, default=20.0)
    ap.add_argument("--rout", type=float, default=10.0, help="outer radius / b")
    ap.add_argument("--far", default="exact", choices=("exact", "uniform"))
    ap.add_argument("--nodal", action="store_true", help="nodal (Lobatto) integration of the interface")
    ap.add_argument("--name", help="deck file name (default from the case)")
    ap.add_argument("--Es", type=float, default=144.0)
    ap.add_argument("--nus", type=float, default=0.2)
    ap.add_argument("--K", type=float, default=0.5)
    ap.add_argument("--p", type=float, default=0.1)
    args = ap.parse_args(argv)
    if args.check:
        n = self_checks()
        print(f"{'all checks pass' if n == 0 else f'{n} checks FAIL'}")
        return 1 if n else 0
    if args.decks:
        os.makedirs(args.decks, exist_ok=True)
        name = args.name or f"lined_{args.bond}_{args.dim}d_l{args.level}.dat"
        path = os.path.join(args.decks, name)
        write_deck(path, args.dim, args.bond, args.level, args.Es, args.nus, args.K, args.p, phi=args.phi,
                   rout_factor=args.rout, far=args.far, nodal=args.nodal)
        print(path)
        return 0
    if args.results:
        for path in args.results:
            if not os.path.isfile(path):
                print(f"lined_hole: {path}: no such results file", file=sys.stderr)
                return 2
            compare(path)
        return 0
    for bond in ("bonded", "slip"):
        print_reference(LinedHole(Es=args.Es, nus=args.nus, K=args.K, p=args.p, bond=bond))
    return 0


if __name__ == "__main__":
    sys.exit(main())
