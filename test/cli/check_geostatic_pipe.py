#!/usr/bin/env python3
"""Model B with its weight and 4 m of cover, cohesionless interfaces, pushed to full slip (issue 26
item 2): the GEOSTATIC stage, then an axial push of the pipe.

    python3 test/cli/check_geostatic_pipe.py FEPS [WORKDIR] [--methods=all|m1,m2,...]

The deck is model B FE1's (scripts/make_model_b.py: half pipe r 600..715, L 2500, in soil to
r = 2000 through pipe/soil interfaces) with: gravity along -x (the model's symmetry plane is
y = 0, so the crown is theta = 0, x = +715), soil gamma = 2e-5 N/mm3 with K0 = 0.5, concrete
gamma = 2.4e-5, the ground surface 4000 mm above the crown (SURFACE=4715), interfaces with
c = 0 (phi = 15 deg, psi = 0), the soil's end faces on rollers in z, and the pipe's end z = 0
pushed 2 mm along z in 10 steps: the soft soil (E 144 MPa) follows the pipe elastically for
about 0.4 mm (tau R ln(2000 / 715) / G) before the whole interface slides, and beyond that the
shear of every sliding point turns axial (the circumferential shear left by the pipe's settling
fades as the axial slip grows).

Checks:
- the GEOSTATIC stage (4 steps) runs with c = 0 (the in-situ stress closes the interfaces from
  the start) with full Newton-Raphson (converged to DELTA1 = 1e-7) and with the other methods
  asked for (CI: BFGS and the thesis's newton-raphson, which needs DELTA1 = 1e-5 and MAXIT
  1000 here; --methods=all: the other presets too), whose integral of the interface's normal
  stress must agree with full Newton-Raphson's to 1e-3 (the Euler methods, one pass a step,
  must run; their drift is printed);
- at full slip (full Newton-Raphson with LINESEARCH=energy) the jacking force (the z reaction
  of the pushed face) equals tan(phi) times the integral of the interface's normal stress, to
  1e-3. The integral is this script's own: the 2 x 2 Gauss rule of the bilinear interface quads
  on the pipe's outer face, from the node coordinates in the results file (an independent check
  of the library's interface forces).
It prints the force beside Ripley's estimate (thesis eq. 1.5.2): F = pi R (sigma_vc + sigma_hc)
tan(phi) per unit length, half of it for the half model, from the in-situ stresses at the pipe
centre, and the ratio (the pipe's weight and the ground's arching around the stiff pipe make
the difference; docs/verification.md).
Exit status 1 when a check fails.
"""
import math
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PHI, GAMMA_SOIL, K0, COVER, R_OUT, LENGTH = 15.0, 2.0e-5, 0.5, 4000.0, 715.0, 2500.0
GEOSTATIC_STEPS = 4
PUSH_METHOD = 'full-newton-raphson'
METHODS = {
    'initial-stiffness': 'METHOD=initial-stiffness, MAXIT=200',
    'euler': 'METHOD=euler',
    'modified-euler': 'METHOD=modified-euler',
    # the step's start tangent (elastic in step 1) stalls near a relative residual of 4e-6
    # while interface points open and close: its own DELTA1 and room to get there
    'newton-raphson': 'METHOD=newton-raphson, MAXIT=1000, DELTA1=1e-5',
    'modified-newton-raphson': 'METHOD=modified-newton-raphson, MAXIT=100',
    'full-newton-raphson': 'METHOD=full-newton-raphson, MAXIT=50, LINESEARCH=energy',
    'bfgs': 'METHOD=initial-stiffness, ACCELERATION=bfgs, MAXIT=100',
}


def pipe_deck(fe1_text, method, push):
    """FE1's deck with the weight, the in-situ stress and (push) the push (see the module's text)."""
    keep = []
    for line in fe1_text.splitlines():
        if re.match(r'(PRESSURE|STAGE|REPORT|OUTPUT|NSET, anchor|FIX, anchor)\b', line):
            continue
        line = line.replace('MATERIAL, concrete, ELASTIC, E=40000., NU=0.2',
                            'MATERIAL, concrete, ELASTIC, E=40000., NU=0.2, GAMMA=2.4e-5')
        line = re.sub(r'^(MATERIAL, soil, ELASTIC, .*)$', r'\1, GAMMA=%g, K0=%g' % (GAMMA_SOIL, K0), line)
        line = re.sub(r'^(MATERIAL, pipe_soil, INTERFACE, .*), PHI=[^,]*, PSI=[^,]*, C=.*$',
                      r'\1, PHI=%g, PSI=0., C=0.' % PHI, line)
        keep.append(line)
    controls = METHODS[method] + ('' if 'DELTA1=' in METHODS[method] else ', DELTA1=1e-7')
    keep += [
        'NSET, soil_end0, GROUP=soil, CSYS=2, Z=0., TOL=0.01',
        'NSET, soil_end1, GROUP=soil, CSYS=2, Z=%g, TOL=0.01' % LENGTH,
        'FIX, soil_end0, Z',
        'FIX, soil_end1, Z',
        'NSET, push, GROUP=pipe, CSYS=2, Z=0., TOL=0.01',
        'STAGE, geostatic, STEPS=%d, ' % GEOSTATIC_STEPS + controls,
        'GRAVITY, X=-1.',
        'GEOSTATIC, SURFACE=%g' % (R_OUT + COVER),
    ]
    if push:
        keep += ['STAGE, push, STEPS=10, OUTPUT=10, ' + controls, 'DISPLACE, push, Z=2.']
    text = '\n'.join(keep) + '\n'
    assert 'GAMMA=2.4e-5' in text and 'K0=' in text and 'C=0.' in text, 'FE1 deck changed: update this check'
    return text


def interface_normal_force(f, step):
    """Integral of the interface's normal stress over its lower face (the pipe's outer surface):
    2 x 2 Gauss points of each bilinear quad, this script's own rule."""
    coords = f['mesh/coordinates'][()]
    conn = f['mesh/groups/contact/connectivity'][()] - 1
    sn = f['steps/%s/interface/contact' % step][()][:, 2].reshape(len(conn), 4)
    g = 1.0 / math.sqrt(3.0)
    total = 0.0
    for e, nodes in enumerate(conn):
        x = coords[nodes[:4]]
        for q, (s, t) in enumerate([(-g, -g), (g, -g), (g, g), (-g, g)]):
            ds = 0.25 * np.array([-(1 - t), (1 - t), (1 + t), -(1 + t)])
            dt = 0.25 * np.array([-(1 - s), -(1 + s), (1 + s), (1 - s)])
            jac = np.linalg.norm(np.cross(ds @ x, dt @ x))
            total += sn[e, q] * jac
    return total


def run_deck(feps, work, name, text):
    """Write and run a deck; the results file, or None (and a FAIL line) when the run fails."""
    deck = os.path.join(work, name + '.dat')
    out = os.path.join(work, name + '.h5')
    open(deck, 'w').write(text)
    run = subprocess.run([feps, deck, '--quiet', '--output', out], capture_output=True, text=True)
    if run.returncode != 0:
        print('FAIL %s: exit %d: %s' % (name, run.returncode, run.stderr.strip()))
        return None
    return out


def main():
    args = [a for a in sys.argv[1:] if not a.startswith('--')]
    feps = os.path.abspath(args[0])
    work = args[1] if len(args) > 1 else tempfile.mkdtemp()
    methods = ['full-newton-raphson', 'bfgs', 'newton-raphson']     # CI's; --methods=all for docs/verification.md
    for a in sys.argv[1:]:
        if a == '--methods=all':
            methods = list(METHODS)
        if a.startswith('--methods=') and a != '--methods=all':
            methods = a.split('=', 1)[1].split(',')
    subprocess.run([sys.executable, os.path.join(ROOT, 'scripts', 'make_model_b.py'), '--outdir', work,
                    '--cases', 'FE1'], check=True, stdout=subprocess.DEVNULL)
    fe1 = open(os.path.join(work, 'FE1.dat')).read()
    tan_phi = math.tan(math.radians(PHI))
    depth_centre = COVER + R_OUT
    ripley = math.pi * R_OUT * (1 + K0) * GAMMA_SOIL * depth_centre * tan_phi * LENGTH / 2
    failed = 0
    # the in-situ state of every method, against full Newton-Raphson's
    states = {}
    for m in [PUSH_METHOD] + [m for m in methods if m != PUSH_METHOD]:
        out = run_deck(feps, work, 'geostatic_' + m, pipe_deck(fe1, m, push=False))
        if out is None:
            failed += 1
            continue
        with h5py.File(out) as f:
            last = sorted(f['steps'])[-1]
            states[m] = (-interface_normal_force(f, last), f['steps/%s/displacement' % last][()])
            converged = int(f['summary'].attrs['converged'])
        ref_force, ref_u = states[PUSH_METHOD]
        force, u = states[m]
        rel = abs(force - ref_force) / ref_force
        du = np.abs(u - ref_u).max() / np.abs(ref_u).max()
        # the jacking force hangs on the integral of sigma_n: it must agree to 1e-3 (the
        # methods other than full Newton-Raphson stop at MAXIT short of DELTA1 = 1e-7: printed);
        # the Euler methods make one pass a step and carry the rest by design: they must run,
        # and their drift is printed
        ok = (rel < 1e-3 or m in ('euler', 'modified-euler')) and (m != PUSH_METHOD or converged == 1)
        failed += not ok
        print('%s geostatic stage, %s, c = 0: converged %d, integral of sigma_n %.6e N (%.1e from %s), '
              'displacements %.1e from it (largest %.4f mm)' % ('ok  ' if ok else 'FAIL', m, converged, force, rel,
                                                               PUSH_METHOD, du, np.abs(u).max()))
    # the push to full slip
    out = run_deck(feps, work, 'push', pipe_deck(fe1, PUSH_METHOD, push=True))
    if out is None:
        sys.exit(1)
    with h5py.File(out) as f:
        last = sorted(f['steps'])[-1]
        coords = f['mesh/coordinates'][()]
        react = f['steps/%s/reaction' % last][()]
        pipe_nodes = np.unique(f['mesh/groups/pipe/connectivity'][()] - 1)
        face = pipe_nodes[np.abs(coords[pipe_nodes, 2]) < 0.01]
        jacking = react[face, 2].sum()   # the support pushes the pipe along +z
        normal = -interface_normal_force(f, last)
        sliding = np.mean(f['steps/%s/interface/contact' % last][()][:, 3] != 0)
    rel = abs(jacking - tan_phi * normal) / (tan_phi * normal)
    ok = rel < 1e-3
    failed += not ok
    print('%s push to full slip (%s): jacking force %.6e N, tan(phi) x integral of sigma_n %.6e N (rel. %.1e), '
          '%.1f%% of the points sliding or open; Ripley (thesis eq. 1.5.2) %.6e N, ratio %.4f; the in-situ '
          'integral of sigma_n %.6e N is %.4f of Ripley\'s pi R (sigma_vc + sigma_hc) L / 2' % (
              'ok  ' if ok else 'FAIL', PUSH_METHOD, jacking, tan_phi * normal, rel, 100 * sliding, ripley,
              jacking / ripley, states[PUSH_METHOD][0], states[PUSH_METHOD][0] * tan_phi / ripley))
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
