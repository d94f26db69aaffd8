#!/usr/bin/env python3
"""Independent reference for test/test_matsuoka.f90 "numpy_reference_returns": the modified
Matsuoka-Nakai stress update of thesis 2.4.2 (zeta = 9 + 8 tan^2, SPEC 5) computed without
feps's Lode-angle reduction. It works in principal stresses with the thesis's cubic yield
function f = I1* I2* - zeta I3* (sigma* = M - sigma, tension positive, sign turned so that
f > 0 outside) and the thesis's potential g (eq. 2.4.6-2.4.8: zeta*, apex M* from g = 0 at the
current stress; psi = 0: its limit, the deviator), solves the backward-Euler return
sigma = sigma_tr - dlambda Dp n_g(sigma), f(sigma) = 0 by damped Newton from several starts on
the surface (the solutions must agree), and for the proportional tension rule (most tensile
principal trial stress >= M) scales the trial onto the surface by bisection on the cubic.
Prints the returned Voigt stresses of the test's trials as Fortran literals.

Kept in test/reference/ as a deliberately independent implementation (principal stresses, no
Lode-angle reduction): it must not share code with src/materials/feps_matsuoka_nakai.f90.

    python3 test/reference/matsuoka_reference.py

Needs numpy only. Written for the materials audit of 2026-11-23 (docs/verification.md).
"""
import numpy as np

E = 30000.0

# phi, psi (deg), nu, tension rule (1 proportional, 2 closest-point), ft, trial stress (Voigt)
CASES = [
    (26.57, 26.57, 0.2, 1, 6.0, [-30.0, -5.0, 2.0, 4.0, -3.0, 6.0]),
    (26.57, 0.0, 0.2, 1, 6.0, [-30.0, -5.0, 2.0, 4.0, -3.0, 6.0]),
    (26.57, 13.0, -0.9, 1, 6.0, [-12.0, -20.0, -3.0, 7.0, 1.0, -2.0]),
    (54.9, 54.9, 0.45, 1, 5.0, [-150.0, 5.0, -10.0, 0.0, 15.0, 0.0]),
    (54.9, 20.0, 0.22, 2, 5.0, [12.0, -25.0, -30.0, 2.0, 0.0, 1.0]),
    (15.0, 15.0, 0.3, 2, 0.2, [0.5, 0.45, 0.4, 0.02, 0.0, 0.01]),
    (40.0, 10.0, 0.0, 1, 3.0, [-1.0e4, 2.0e3, -5.0e3, 3.0e3, -1.0e3, 4.0e3]),
    (35.0, 35.0, 0.2, 1, 3.0, [9.0, -4.0, -6.0, 1.0, 2.0, -1.0]),
]


def apex_of(ft, phi):
    return 0.5 * ft * (1 + 1 / np.sin(np.radians(phi)))


def to_tensor(v):
    return np.array([[v[0], v[5], v[4]], [v[5], v[1], v[3]], [v[4], v[3], v[2]]])


def to_voigt(t):
    return np.array([t[0, 0], t[1, 1], t[2, 2], t[1, 2], t[0, 2], t[0, 1]])
def zeta(angle):
    return 9.0 + 8.0 * np.tan(np.radians(angle)) ** 2


def cubic(a, z):
    i1 = a.sum()
    i2 = a[0] * a[1] + a[1] * a[2] + a[0] * a[2]
    i3 = a.prod()
    return i1 * i2 - z * i3


def f_principal(sp, m, phi):
    """Scaled yield value f / I1*^2 (stress units, zero on the surface, > 0 outside)."""
    a = m - sp
    return cubic(a, zeta(phi)) / a.sum() ** 2


def grad_cubic_sigma(b, z):
    """d/dsigma of (J1 J2 - z J3)(b = M* - sigma), principal components."""
    j1 = b.sum()
    j2 = b[0] * b[1] + b[1] * b[2] + b[0] * b[2]
    g = np.empty(3)
    for i in range(3):
        j, k = [x for x in range(3) if x != i]
        g[i] = -(j2 + j1 * (b[j] + b[k]) - z * b[j] * b[k])
    return g


def m_star(sp, psi):
    """Largest x > max(sp) with g(x - sp) = 0 (the branch through sp); inf for psi = 0."""
    z = zeta(psi)
    if z - 9.0 < 1e-12:
        return np.inf
    lo = sp.max()
    scale = max(np.abs(sp).max(), 1e-300)
    hi = lo + scale
    while cubic(hi - sp, z) > 0:
        hi = lo + 2 * (hi - lo)
    for _ in range(300):
        mid = 0.5 * (lo + hi)
        if cubic(mid - sp, z) > 0:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-16 * abs(hi):
            break
    return 0.5 * (lo + hi)


def flow_dir(sp, psi):
    """Unit plastic flow direction dg/dsigma (principal) of the thesis potential at sp."""
    ms = m_star(sp, psi)
    if np.isinf(ms):
        s = sp - sp.mean()
        n = s
    else:
        n = grad_cubic_sigma(ms - sp, zeta(psi))
    return n / np.linalg.norm(n)


def yield_normal(sp, m, phi):
    n = grad_cubic_sigma(m - sp, zeta(phi))
    return n / np.linalg.norm(n)


def principal_d(e, nu):
    lam = e * nu / ((1 + nu) * (1 - 2 * nu))
    mu = e / (2 * (1 + nu))
    return lam * np.ones((3, 3)) + 2 * mu * np.eye(3)


def surface_point(sp_tr, p0, m, phi):
    """The point p0 + t s_hat (s_hat: unit deviator of the trial) on the surface, t by bisection."""
    s = sp_tr - sp_tr.mean()
    ns = np.linalg.norm(s)
    sh = s / ns if ns > 0 else np.array([1.0, -0.5, -0.5]) / np.sqrt(1.5)
    lo, hi = 0.0, (m - p0) * 10 + 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        x = p0 + mid * sh
        if (m - x).min() > 0 and f_principal(x, m, phi) < 0:
            lo = mid
        else:
            hi = mid
    return p0 + lo * sh


def solve_return_multi(sp_tr, m, phi, psi, e, nu):
    """solve_return from several starts on the surface (independent of feps); the solutions
    found must agree. Returns (sigma, dl, ok, n_converged, spread)."""
    s = sp_tr - sp_tr.mean()
    ns = np.linalg.norm(s)
    p_tr = sp_tr.mean()
    dp = principal_d(e, nu)
    sols = []
    for p0 in [p_tr, m - ns / 3, m - ns, m - 3 * ns, m - 0.1 * ns, m - 10 * ns]:
        if not p0 < m:
            continue
        x0 = surface_point(sp_tr, p0, m, phi)
        ng = flow_dir(x0, psi)
        dl0 = max(np.dot(sp_tr - x0, dp @ ng) / np.dot(dp @ ng, dp @ ng), 1e-12)
        sp, dl, ok = solve_return(sp_tr, m, phi, psi, e, nu, start=np.r_[x0, dl0])
        if ok:
            sols.append((sp, dl))
    if not sols:
        return None, None, False, 0, 0.0
    spread = max(np.abs(a[0] - sols[0][0]).max() for a in sols) / (np.abs(sp_tr).max() + m)
    return sols[0][0], sols[0][1], True, len(sols), spread


def solve_return(sp_tr, m, phi, psi, e, nu, start=None):
    """Backward-Euler return sigma = sigma_tr - dl Dp n_g(sigma), f(sigma) = 0 by damped Newton
    (finite-difference Jacobian). Returns (sigma, dl, ok)."""
    dp = principal_d(e, nu)
    scale = np.abs(sp_tr).max() + m

    def res(x):
        s, dl = x[:3], x[3]
        a = m - s
        if a.sum() <= 0:
            return None
        try:
            ng = flow_dir(s, psi)
        except Exception:
            return None
        r = np.empty(4)
        r[:3] = (s - sp_tr + dl * dp @ ng) / scale
        r[3] = f_principal(s, m, phi) / scale
        return r

    if start is None:
        ng = flow_dir(sp_tr, psi) if m - sp_tr.max() > 0 or True else None
        nf = yield_normal(sp_tr, m, phi)
        f0 = f_principal(sp_tr, m, phi)
        # linearised multiplier along D n_g (gradient of the scaled f by FD)
        h = 1e-7 * scale
        gf = np.array([(f_principal(sp_tr + h * np.eye(3)[i], m, phi) - f_principal(sp_tr - h * np.eye(3)[i], m, phi)) / (2 * h) for i in range(3)])
        dl0 = f0 / max(gf @ dp @ ng, 1e-300)
        x = np.concatenate([sp_tr - dl0 * dp @ ng, [dl0]])
        # keep the start inside the shifted octant
        k = 0
        while (m - x[:3]).min() <= 0 and k < 60:
            x[:3] = 0.5 * (x[:3] + np.minimum(sp_tr, m - 1e-3 * scale))
            k += 1
    else:
        x = np.array(start, float)
    r = res(x)
    if r is None:
        return x[:3], x[3], False
    for it in range(200):
        nr = np.linalg.norm(r)
        if nr < 1e-14:
            break
        jac = np.empty((4, 4))
        for j in range(4):
            hj = 1e-7 * (scale if j < 3 else max(abs(x[3]), 1e-12 * scale / e))
            xp = x.copy(); xp[j] += hj
            xm = x.copy(); xm[j] -= hj
            rp, rm = res(xp), res(xm)
            if rp is None or rm is None:
                return x[:3], x[3], False
            jac[:, j] = (rp - rm) / (2 * hj)
        try:
            dx = np.linalg.solve(jac, -r)
        except np.linalg.LinAlgError:
            return x[:3], x[3], False
        t = 1.0
        while t > 1e-8:
            xn = x + t * dx
            rn = res(xn)
            if rn is not None and np.linalg.norm(rn) < (1 - 1e-4 * t) * nr:
                break
            t *= 0.5
        else:
            return x[:3], x[3], False
        x, r = xn, rn
    ok = np.linalg.norm(r) < 1e-11 and x[3] > 0 and (m - x[:3]).min() > -1e-12 * scale
    return x[:3], x[3], ok


def proportional(sp_tr, m, phi):
    """alpha in (0, 1] with f(alpha sigma_tr) = 0 (first crossing from zero stress)."""
    if (m - sp_tr).min() > 0 and f_principal(sp_tr, m, phi) <= 0:
        return 1.0
    ts = np.linspace(0, 1, 2001)
    prev = 0.0
    for t in ts[1:]:
        a = m - t * sp_tr
        if a.sum() <= 0 or f_principal(t * sp_tr, m, phi) > 0 or a.min() < 0:
            lo, hi = prev, t
            break
        prev = t
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        a = m - mid * sp_tr
        if a.min() >= 0 and f_principal(mid * sp_tr, m, phi) <= 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main():
    for phi, psi, nu, rule, ft, trial in CASES:
        m = apex_of(ft, phi)
        w, v = np.linalg.eigh(to_tensor(np.array(trial)))
        if (m - w).min() > 0 and f_principal(w, m, phi) < 0:
            raise SystemExit(f'trial {trial} is elastic')
        if rule == 1 and w.max() >= m:
            sig = proportional(w, m, phi) * np.array(trial)
            kind = 'tension zone'
        else:
            sp, dl, ok, nconv, spread = solve_return_multi(w, m, phi, psi, E, nu)
            if not ok or spread > 1e-12:
                raise SystemExit(f'trial {trial}: no unique return ({nconv} starts converged, spread {spread})')
            sig = to_voigt(v @ np.diag(sp) @ v.T)
            kind = 'return'
        print(f'! phi {phi}, psi {psi}, nu {nu}, rule {rule}, ft {ft}: {kind}')
        print('[' + ', '.join('%.16e_dp' % x for x in sig) + ']')


if __name__ == '__main__':
    main()
