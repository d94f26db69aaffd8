#!/usr/bin/env python3
"""The laboratory tests of thesis chapter 8 (issue 27 item 3, scripts/make_lab_test.py).

    python3 test/cli/check_lab_tests.py FEPS [WORKDIR]

Checks:
- the generator writes a deck for every pipe of Tables 8.4-8.8 whose set-up the thesis text
  defines (1, 3 and 25) and names a reason for each of the other 20, and every deck passes
  `feps --check`, and the decks in input/chapter8 are the generator's;
- pipe 1 (plate A, frictionless): the force levels off at the uniaxial plastic limit FC x A of the
  section (closed form; the fixed base's confinement adds about 1 %): to 2 %;
- pipe 3 (plate B): the predicted normalised strength lies within the issue's 15 % of the measured
  one (Table 8.4: 42.98 %).
Pipe 25's prediction misses by 34 % and is not asserted (docs/verification.md says why).
Exit status 1 when a check fails.
"""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import make_lab_test as lab  # noqa: E402

failures = 0


def check(ok, what):
    global failures
    print(("ok   " if ok else "FAIL ") + what)
    failures += 0 if ok else 1


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    feps = os.path.abspath(sys.argv[1])
    work = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp(prefix="feps_lab_")
    os.makedirs(work, exist_ok=True)
    out = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_lab_test.py"), "--outdir", work],
                         capture_output=True, text=True, check=True).stdout
    written = [line for line in out.splitlines() if ": wrote " in line]
    skipped = [line for line in out.splitlines() if ": not modelled: " in line]
    table = lab.read_table()
    check(len(written) == 3 and len(skipped) == len(table) - 3 and all(line.split(": not modelled: ")[1]
                                                                        for line in skipped),
          f"make_lab_test.py: {len(written)} decks (pipes 1, 3, 25), a reason for each of the other "
          f"{len(skipped)} pipes")
    for pipe in (1, 3, 25):
        with open(os.path.join(work, f"lab_{pipe}.dat")) as a, \
                open(os.path.join(ROOT, "input", "chapter8", f"lab_{pipe}.dat")) as b:
            check(a.read() == b.read(), f"input/chapter8/lab_{pipe}.dat is the generator's deck")
        rc = subprocess.run([feps, "--check", f"lab_{pipe}.dat"], cwd=work, capture_output=True).returncode
        check(rc == 0, f"lab_{pipe}.dat passes feps --check")

    (travel, force), stop = lab.run(feps, os.path.join(work, "lab_1.dat"), "A")
    limit = lab.FC_PER_CUBE * lab.cube(1) * lab.AREA
    check(stop is None and abs(force.max() / limit - 1.0) < 0.02,
          f"pipe 1, plate A: plateau {force.max():.1f} N against FC A = {limit:.1f} N "
          f"({force.max() / limit - 1.0:+.2%}, 2 % allowed)")

    curve, stop = lab.run(feps, os.path.join(work, "lab_3.dat"), "B")
    peak = curve[1].max()
    predicted = 100.0 * peak / (lab.AREA * lab.cube(3))
    measured = float(table[3]["normalized_strength_pct"])
    check(abs(predicted / measured - 1.0) < 0.15 and curve[1][-1] < peak,
          f"pipe 3, plate B: predicted {predicted:.2f} % against Table 8.4's {measured:.2f} % "
          f"({predicted / measured - 1.0:+.1%}, 15 % allowed), past the peak")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
