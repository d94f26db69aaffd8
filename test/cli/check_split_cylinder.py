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
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
