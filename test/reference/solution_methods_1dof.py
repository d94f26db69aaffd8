#!/usr/bin/env python3
"""The thesis 2.6 solution methods as feps documents them (docs/input-format.md, CONTROLS), written
again from the documentation on a one-DOF problem: the reference for test/test_solution_methods.f90.

Kept in test/reference/ as a deliberately independent implementation: written from the
documentation, not from src/analysis, so that the test holds the code to what the docs say.

    python3 test/reference/solution_methods_1dof.py          # the paths of test/data/slide_1dof*.dat

The problem (test/data/slide_1dof.dat): an elastic-perfectly plastic interface in shear (stiffness
Ks A = 100 N/mm, yield force c A = 100 N, closest-point return from the committed force) in
parallel with springs kb = 25 N/mm whose far ends may be displaced by d: internal force
F(u) = tau(u) + kb (u - d). feps sees four equal free DOFs; the norms below are those of its
vectors: |R| = |P - F| / 2, and |P| = max(|P| / 2, |(tau, kb (u - d))| / 2) (the applied load on
the free DOFs, or the support reactions when larger).

Per step (and per sub-step after a cut-back, h = 1/2, 1/4, ... of the step):
- stiffness: euler, modified-euler, newton-raphson: the tangent of the committed state, every
  (sub)step; modified-newton-raphson: refactorized when the relative residual at the end of the
  last step exceeds DELTA3 (and after a cut-back, then elastic); initial-stiffness: the elastic
  one, factorized once; full-newton-raphson: the tangent of every iterate.
- residual: P_{n+1} - F(u_n) (the unbalanced force of step n carried, eq. 2.6.4), except Euler,
  which starts from the load increment alone.
- iterations until |R| / |P| < DELTA1, at most MAXIT (1, 1, 50, 10, 10, 50); divergence: a
  non-finite residual, 10^4-fold growth, Newton-Raphson not converged, or a final relative
  residual above DIVERGENCE (above 1 for the Euler methods): halve and retry, up to CUTBACKS.
"""
import math

KSA, CA, KB = 100.0, 100.0, 25.0
MAXIT = {'euler': 1, 'modified-euler': 1, 'newton-raphson': 50, 'modified-newton-raphson': 10,
         'initial-stiffness': 10, 'full-newton-raphson': 50}
METHODS = list(MAXIT)


def update(tau_c, du):
    """Interface force from the committed force tau_c and the increment du: force, tangent."""
    t = tau_c + KSA * du
    if abs(t) > CA:
        return math.copysign(CA, t), 0.0
    return t, KSA


def run(method, stages, delta1=1e-6, delta3=1e-3, divergence=1e-2, max_cut=10):
    """stages: (force per step, steps, spring-end displacement per step). One record per step:
    u, iterations, relative residual, factorizations and cut-backs so far."""
    maxit = MAXIT[method]
    u = tau = d = p = 0.0
    ktan = KSA
    have_factor = factor_elastic = elastic_retry = False
    rel_prev = 0.0
    k = 0.0
    nfact = ncut = 0
    out = []
    for df_step, nsteps, dd_step in stages:
        for _ in range(nsteps):
            done, h, cut, its_step = 0.0, 1.0, 0, 0
            while done < 1.0 - 1e-12:
                h = min(h, 1.0 - done)
                if method == 'initial-stiffness':
                    need = not (have_factor and factor_elastic)
                elif method == 'modified-newton-raphson':
                    need = not have_factor or rel_prev > delta3
                else:
                    need = True
                if need:
                    factor_elastic = method == 'initial-stiffness' or elastic_retry
                    k = KSA + KB if factor_elastic else ktan + KB
                    nfact += 1
                    have_factor, elastic_retry = True, False
                pt, dt = p + df_step * h, d + dd_step * h
                ut, taut, kt = u, tau, ktan
                r = pt - (taut + KB * (ut - dt))
                if method == 'euler':
                    r -= p - (tau + KB * (u - d))
                r_scale = abs(r) / 2
                ok, r_first, its = True, -1.0, 0
                for m in range(1, maxit + 1):
                    if method == 'full-newton-raphson' and m > 1:
                        k = kt + KB
                        nfact += 1
                    ut += r / k
                    taut, kt = update(tau, ut - u)
                    r = pt - (taut + KB * (ut - dt))
                    rnorm = abs(r) / 2
                    pnorm = max(abs(pt) / 2, math.hypot(taut, KB * (ut - dt)) / 2, 5e-324)
                    if pnorm <= 1e-8 * r_scale:
                        pnorm = r_scale
                    its, rel = m, rnorm / pnorm
                    r_first = rnorm if r_first < 0 else r_first
                    if rel < delta1:
                        break
                    if m > 1 and rnorm > 1e4 * r_first:
                        ok = False
                        break
                if ok:
                    if method in ('newton-raphson', 'full-newton-raphson'):
                        ok = rel < delta1
                    elif method in ('euler', 'modified-euler'):
                        ok = rel < max(1.0, divergence)
                    else:
                        ok = rel < max(divergence, delta1)
                its_step += its
                if ok:
                    done += h
                    rel_prev = rel
                    u, tau, ktan, p, d = ut, taut, kt, pt, dt
                else:
                    cut += 1
                    ncut += 1
                    if cut > max_cut:
                        raise RuntimeError(f'{method}: the step does not converge after {max_cut} cut-backs')
                    h /= 2
                    if method != 'initial-stiffness':
                        rel_prev = math.inf
                    elastic_retry = method == 'modified-newton-raphson'
            out.append(dict(u=u, iterations=its_step, residual=rel_prev, factorizations=nfact, cutbacks=ncut))
    return out


def main():
    cases = {'slide_1dof.dat': [(30.0, 10, 0.0)], 'slide_1dof_displaced.dat': [(0.0, 10, 1.05)]}
    for deck, stages in cases.items():
        print(deck)
        for method in METHODS:
            path = run(method, stages)
            print(f'  {method:24s} factorizations {path[-1]["factorizations"]:3d}  cut-backs {path[-1]["cutbacks"]:3d}')
            print('    u          ', ', '.join(f'{s["u"]:.15g}' for s in path))
            print('    iterations ', ', '.join(str(s['iterations']) for s in path))


if __name__ == '__main__':
    main()
