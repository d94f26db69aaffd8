#!/usr/bin/env python3
"""The split-cylinder (Brazilian) test against its closed form (issue 27 item 2):
test/data/split_cylinder.dat (written by test/data/make_split_cylinder.py, whose docstring gives
the model).

    python3 test/cli/check_split_cylinder.py FEPS [WORKDIR]

Closed form (Hondros 1959, this script's own): a radial pressure p over arcs 2 alpha at both ends
of a diameter of a disk puts sigma_x = 2 p (sin 2 alpha - alpha) / pi at its centre, the most
tensile stress in the disk, so the concrete cracks first there when that reaches FT. Checks:
- the deck is the generator's;
- at each of the 100 steps to the closed form's cracking pressure (step k: k / 100 of it) the
  disk's largest principal stress is at the Gauss point nearest the centre and equals k / 100 FT
  to 2e-4 (the closed form is the centre's; the point lies at x = -0.94, y = 0.89 mm, and the
  closed form for a point load falls by 6e-4 at that x: the mesh gives 4e-5), and no point has
  cracked;
- one step more, to 1.0005 times the cracking pressure: points have cracked, all in the middle
  column of elements (|x| < 4 mm) within 5 mm of the centre.

Then the peak (test/data/split_cylinder_peak.dat, `make_split_cylinder.py --peak`: DAMAGE=TENSILE,
10 steps to the cracking pressure, then the middle column's opening at the centre grows by
0.05 mm in 200 steps), with GF = 0.1 N/mm and, written by the generator here, GF = 0.03. The
cohesive-crack theory of the test (Rocco, Guinea, Planas and Elices, Materials and Structures 32,
1999) puts the splitting strength above the elastic onset by an amount that grows with
l_ch / D (l_ch = E GF / FT^2, 333 and 100 mm here against D = 150 mm) and tends to the onset
as l_ch / D falls. Checks, for both: the decks are the generator's, every step converges, the
load (the supports' reaction) rises past the closed form's onset to a peak inside the opening
stage and falls past it to below 70 % of the peak; at the peak the cracked points of the middle
column run from the centre (y < 2 mm) upwards (the splitting crack). And the ordering the theory
gives: GF = 0.03's peak within 0.5 % of the onset, GF = 0.1's above it, and GF = 0.1's crack at
the peak the longer (the process zone at the peak grows with l_ch).
Exit status 1 when a check fails.
"""
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from feps_results import components, gauss_points, steps  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "test", "data"))
import make_split_cylinder as generator  # noqa: E402  (the deck's steps and mesh, not the closed form)

R, B, FT = 75.0, 12.0, 3.0
failures = 0


def check(ok, what):
    global failures
    print(("ok   " if ok else "FAIL ") + what)
    failures += 0 if ok else 1


def column(step, name, component):
    """One component of a Gauss-point field of the disk at a step, by its schema name."""
    d = step[name]["disk"]
    return d[:, components(d).index(component)]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    feps = os.path.abspath(sys.argv[1])
    work = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp(prefix="feps_split_")
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "split_cylinder.dat")
    subprocess.run([sys.executable, os.path.join(ROOT, "test", "data", "make_split_cylinder.py"), "-o", deck],
                   check=True)
    with open(deck) as a, open(os.path.join(ROOT, "test", "data", "split_cylinder.dat")) as b:
        check(a.read() == b.read(), "test/data/split_cylinder.dat is the generator's deck")
    alpha = math.asin(B / 2.0 / R)
    p_crack = math.pi * FT / (2.0 * (math.sin(2.0 * alpha) - alpha))
    out = os.path.join(work, "split_cylinder.h5")
    run = subprocess.run([feps, deck, "--quiet", "--fields", "all,point_state", "--output", out],
                         capture_output=True, text=True)
    check(run.returncode == 0, f"the run ends (exit {run.returncode}) {run.stderr.strip()}")
    if run.returncode != 0:
        sys.exit(1)
    with h5py.File(out) as f:
        gp = gauss_points(f, "disk")
        names = steps(f)
        centre = int(np.argmin(np.hypot(gp[:, 0], gp[:, 1])))
        worst, located, cracked = 0.0, True, 0
        for k, name in enumerate(names[:100], start=1):
            g = f["steps"][name]
            s1 = column(g, "principal", "most_tensile")
            located &= int(np.argmax(s1)) == centre
            worst = max(worst, abs(s1.max() / (k / 100.0 * FT) - 1.0))
            cracked += int(np.sum(column(g, "point_state", "state") == 4))
        check(len(names) == 101 and located and worst < 2e-4 and cracked == 0,
              f"steps 1-100 (to the closed form's p = {p_crack:.6f} MPa): the largest principal stress at "
              f"the point nearest the centre ({np.hypot(*gp[centre, :2]):.2f} mm from it), k/100 FT to "
              f"{worst:.1e} (2e-4 allowed), nothing cracked")
        ps = column(f["steps"][names[-1]], "point_state", "state")
        at = gp[ps == 4]
        check(len(at) > 0 and np.all(np.abs(at[:, 0]) < 4.0) and np.all(np.hypot(at[:, 0], at[:, 1]) < 5.0),
              f"1.0005 p: {len(at)} points cracked, all in the middle column within 5 mm of the centre")
    peaks = {gf: peak(feps, work, gf) for gf in (0.1, 0.03)}
    if None not in peaks.values():
        (p1, c1), (p3, c3) = peaks[0.1], peaks[0.03]
        check(p3 - 1.0 < 5e-3 and p1 > p3 and c1 > c3,
              f"the strength tends to the onset as l_ch / D falls: GF = 0.03 {p3:.5f}, GF = 0.1 {p1:.5f} times "
              f"the onset; the crack at the peak {c3:.1f} and {c1:.1f} mm long")
    sys.exit(1 if failures else 0)


PEAK_LOAD_STEPS = generator.PEAK_LOAD_STEPS
MIDDLE_HALF_WIDTH = generator.R * generator.U_EDGE / 3.0   # the middle column's half width at y = 0 (its widest)


def peak(feps, work, gf):
    """Run the peak deck with `gf`; its peak load over the closed form's onset and the middle
    column's crack length at the peak (None if the run fails)."""
    deck = os.path.join(work, f"split_cylinder_peak_{gf:g}.dat")
    subprocess.run([sys.executable, os.path.join(ROOT, "test", "data", "make_split_cylinder.py"), "--peak",
                    "--gf", f"{gf:g}", "-o", deck], check=True)
    if gf == 0.1:
        with open(deck) as a, open(os.path.join(ROOT, "test", "data", "split_cylinder_peak.dat")) as b:
            check(a.read() == b.read(), "test/data/split_cylinder_peak.dat is the generator's deck")
    out = os.path.join(work, f"split_cylinder_peak_{gf:g}.h5")
    run = subprocess.run([feps, deck, "--quiet", "--fields", "all,point_state", "--output", out],
                         capture_output=True, text=True)
    check(run.returncode == 0, f"GF = {gf:g}: the run through the peak ends (exit {run.returncode}) "
          f"{run.stderr.strip()}")
    if run.returncode != 0:
        return None
    with h5py.File(out) as f:
        names = steps(f)
        gp = gauss_points(f, "disk")
        force = np.array([f["steps"][n]["reaction"][:, 1].sum() for n in names])
        ratio = force / force[PEAK_LOAD_STEPS - 1]     # the onset: the closed form's pressure
        top = int(np.argmax(ratio))
        check(top >= PEAK_LOAD_STEPS - 1 and ratio[top] >= 1.0 and ratio[-1] < 0.7 * ratio[top],
              f"GF = {gf:g}: the load peaks at {ratio[top]:.5f} times the onset (step {top + 1}) and falls to "
              f"{ratio[-1]:.5f} ({len(names)} steps, each converged)")
        ps = column(f["steps"][names[top]], "point_state", "state")
        at = gp[(ps == 4) & (np.abs(gp[:, 0]) < MIDDLE_HALF_WIDTH)]
        check(len(at) > 0 and at[:, 1].min() < 2.0,
              f"GF = {gf:g}: at the peak the middle column has cracked from y = {at[:, 1].min():.1f} to "
              f"{at[:, 1].max():.1f} mm" if len(at) else f"GF = {gf:g}: no crack at the peak")
        return float(ratio[top]), float(at[:, 1].max()) if len(at) else 0.0


if __name__ == "__main__":
    main()
