#!/usr/bin/env python3
"""Capacity of a pipe joint for design (issue 27 item 4): the jacking force at first cracking and
at failure against the misalignment angle and the packing's stiffness, beside the Australian
model's allowable force.

    python3 scripts/capacity_curves.py FEPS [--angles 0.05,0.1,0.2] [--packing-G 100,300,1000]
        [--ft 4 --fc 40 --gf N/mm] [--allowable-stress MPa] [--q-max MPa] [--seat 0.05] [--steps 40]
        [--outdir capacity] [--plot capacity.png] [-- GENERATOR OPTIONS]

For every angle beta and packing G_p, scripts/make_pipe_joint.py writes the joint (model C: two
pipes and the packing, the bottom pipe in soil; any pipe, packing and soil through the generator's
own options after `--`) with `--capacity`: the misalignment is applied with a seating load
(--seat, 5 % of --q-max), then held while the jacking stress grows to --q-max (default 1.2 FC) in --steps steps,
full Newton-Raphson. Two runs of each deck:

- elastic pipes: the jacking force at **first cracking** is where the largest principal stress in
  the pipes first reaches FT (linear between the two steps that straddle it; 0 when the seating
  load already cracks them: "at seating");
- cracking pipes (`--concrete FT FC GF`: CONCRETE, isotropic damage, Matsuoka-Nakai in
  compression with PHI = PSI = 35): the force at **failure** is that of the last state in
  equilibrium, which feps's stop line names (the run stops where a step does not converge after
  its cut-backs: under load control the limit of the load-controlled path; while the misalignment
  is imposed, the onset of an unstable crack, whose place hangs on GF: docs/verification.md,
  "What the seating stops are"), or "> q-max" when every step converged.

The **Australian model** (thesis 7.2.1, `feps joint`: the library's model) gives the joint's
largest normal stress sigma_max for a load P and deflection beta; its allowable force is the P at
which sigma_max reaches --allowable-stress (default FC / 2: an assumption, set your code's value;
the table prints the one used), found by bisection. The model takes beta as the joint's own
deflection, here the imposed misalignment.

The force is the whole pipe's: the jacking stress times the end's area pi (r_o^2 - r_i^2) (the
deck's applied end force over the part of the ring it models). Prints a table (also
OUTDIR/capacity.csv) and with --plot draws force against beta, one colour per packing.
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from feps_results import components, open_result, steps  # noqa: E402

from make_pipe_joint import L_PIPE, PACKING, R_IN, R_OUT, SEAT_STEPS, model_code_gf  # noqa: E402

PIPES = ("bottom_pipe", "top_pipe")


def floats(text):
    return [float(v) for v in text.split(",") if v]


def write_deck(path, beta, G, args, extra, concrete):
    """The generator's deck for one case."""
    cmd = [sys.executable, os.path.join(HERE, "make_pipe_joint.py"), "-o", path, "--angle", f"{beta:g}",
           "--packing-G", f"{G:g}", "--capacity", f"{args.seat:g}", "--jacking-stress", f"{args.q_max:g}",
           "--steps", str(args.steps)] + extra
    if concrete:
        cmd += ["--concrete", f"{args.ft:g}", f"{args.fc:g}", f"{args.gf:g}"]
    subprocess.run(cmd, check=True, capture_output=True, text=True)


def run(feps, deck):
    """Run a deck; (results path or None, the stop line or None, the progress lines)."""
    out = deck[:-4] + ".h5"
    proc = subprocess.run([feps, deck, "--fields", "all,point_state", "--output", out],
                          capture_output=True, text=True)
    if proc.returncode == 0:
        return out, None, proc.stdout
    return None, (proc.stderr.strip().splitlines() or [f"exit {proc.returncode}"])[-1], proc.stdout


def end_force(group):
    """The applied end force at a step on the part of the ring the deck models (N, along -z);
    main scales it to the whole pipe's q pi (r_o^2 - r_i^2)."""
    return -float(np.sum(group["applied_force"][:, 2]))


def first_cracking(h5, ft, scale):
    """Force at which the pipes' largest principal stress first reaches ft (linear between steps),
    the step that reached it (0: none), and the stress history."""
    with open_result(h5) as f:
        forces, s1 = [0.0], [0.0]
        for name in steps(f):
            g = f["steps"][name]
            forces.append(scale * end_force(g))
            s1.append(max(float(np.max(g["principal"][p][:, components(g["principal"][p]).index("most_tensile")]))
                          for p in PIPES))
    for k in range(1, len(s1)):
        if s1[k] >= ft:
            if k == 1:
                return 0.0, k, forces, s1   # the seating load's first step already cracks: no earlier step
            t = (ft - s1[k - 1]) / (s1[k] - s1[k - 1])
            return forces[k - 1] + t * (forces[k] - forces[k - 1]), k, forces, s1
    return math.inf, 0, forces, s1


def failure(stop, progress, q_max, seat, area):
    """Force at failure: the last state in equilibrium, which the stop line names ("stage NAME,
    step k, load factor X": X is the completed stages plus the fraction of this one, the accepted
    parts of the cut-back step included), else the last fully converged step's, from the progress
    lines (a failed run writes no results; low by at most one step); inf when the run went through
    (stop None)."""
    if stop is None:
        return math.inf
    m = re.search(r"stage (seat|jack), step \d+, load factor ([0-9.Ee+-]+)", stop)
    last = re.search(r"last state in equilibrium: load factor ([0-9.Ee+-]+)", stop)
    if m:
        fraction = float(last.group(1) if last else m.group(2)) % 1.0
        q = seat * q_max * fraction if m.group(1) == "seat" else seat * q_max + (1.0 - seat) * q_max * fraction
        return q * area
    names = re.findall(r"^stage (\w+): \d+ steps", progress, re.M)   # in order (a geostatic stage first)
    q = 0.0
    for line in progress.splitlines():
        m = re.match(r"stage +(\d+) +step +(\d+)/(\d+) ", line)
        if m and int(m.group(1)) <= len(names):
            stage, k, n = names[int(m.group(1)) - 1], int(m.group(2)), int(m.group(3))
            if stage == "seat":
                q = seat * q_max * k / n
            elif stage == "jack":
                q = seat * q_max + (1.0 - seat) * q_max * k / n
    return q * area


def australian_allowable(feps, beta, a, E_p, geom, sigma_allow):
    """P at which the Australian model's sigma_max reaches sigma_allow at deflection beta."""
    def sigma(P):
        out = subprocess.run([feps, "joint", "--beta", f"{beta:.12g}", "--a", f"{a:g}", "--Ep", f"{E_p:.12g}",
                              "--P", f"{P:.12g}", "--L", f"{geom['L']:g}", "--Ec", "40000", "--R", f"{geom['R']:g}",
                              "--r", f"{geom['r']:g}", "--json"], check=True, capture_output=True, text=True).stdout
        return json.loads(out)["australian"]["sigma_max"]
    lo, hi = 1.0, 1.0e6
    while sigma(hi) < sigma_allow:
        hi *= 2.0
    for _ in range(60):
        mid = math.sqrt(lo * hi)
        if sigma(mid) < sigma_allow:
            lo = mid
        else:
            hi = mid
        if hi / lo < 1.0 + 1e-6:
            break
    return hi


def plot(rows, sigma_allow, path):
    """Force against beta, one colour per packing: first cracking, failure, the Australian force."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, G in enumerate(sorted({r["G_p"] for r in rows})):
        sel = [r for r in rows if r["G_p"] == G]
        b = [r["beta_deg"] for r in sel]
        colour = f"C{k}"
        ax.plot(b, [r["first_cracking_N"] / 1e3 if math.isfinite(r["first_cracking_N"]) else np.nan for r in sel],
                "o-", color=colour, label=f"G_p {G:g}: first crack")
        ax.plot(b, [r["failure_N"] / 1e3 if math.isfinite(r["failure_N"]) else np.nan for r in sel], "s--",
                color=colour, label=f"G_p {G:g}: failure")
        ax.plot(b, [r["australian_allowable_N"] / 1e3 for r in sel], ":", color=colour,
                label=f"G_p {G:g}: Australian, {sigma_allow:g} MPa")
    ax.set_xlabel("misalignment beta (deg)")
    ax.set_ylabel("jacking force (kN)")
    ax.set_yscale("log")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=150)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("feps")
    ap.add_argument("--angles", default="0.05,0.1,0.2", help="misalignment angles beta (deg)")
    ap.add_argument("--packing-G", default="100,300,1000", help="packing shear moduli G_p (MPa)")
    ap.add_argument("--packing-nu", type=float, default=0.1)
    ap.add_argument("--ft", type=float, default=4.0, help="the concrete's tensile strength (MPa)")
    ap.add_argument("--fc", type=float, default=40.0, help="its compressive strength (MPa)")
    ap.add_argument("--gf", type=float, help="its fracture energy (N/mm; default the fib Model Code 2010's "
                    "0.073 FC^0.18)")
    ap.add_argument("--allowable-stress", type=float, help="the Australian model's allowable joint stress (MPa; "
                    "default FC / 2, an assumption)")
    ap.add_argument("--q-max", type=float, help="the largest jacking stress tried (MPa; default 1.2 FC: the "
                    "section crushes at FC, so the failure lies below it)")
    ap.add_argument("--steps", type=int, default=40, help="steps of stage jack")
    ap.add_argument("--seat", type=float, default=0.05, help="the seating load, a fraction of --q-max applied "
                    "with the whole misalignment in 5 steps (default 0.05)")
    ap.add_argument("--outdir", default="capacity")
    ap.add_argument("--plot", help="draw the curves to this image")
    argv = sys.argv[1:]
    split = argv.index("--") if "--" in argv else len(argv)
    args = ap.parse_args(argv[:split])
    extra = argv[split + 1:]   # after --: make_pipe_joint.py's options (pipe, packing thickness, soil, mesh)
    feps = os.path.abspath(args.feps)
    sigma_allow = args.allowable_stress or args.fc / 2.0
    args.gf = model_code_gf(args.fc) if args.gf is None else args.gf
    args.q_max = args.q_max or 1.2 * args.fc
    os.makedirs(args.outdir, exist_ok=True)
    gen = argparse.ArgumentParser(add_help=False)
    # the generator's geometry options and defaults, read from what goes to it
    for opt, default in (("--inner-diameter", 2 * R_IN), ("--wall", R_OUT - R_IN), ("--pipe-length", L_PIPE),
                         ("--packing", PACKING)):
        gen.add_argument(opt, type=float, default=default)
    known, _ = gen.parse_known_args(extra)
    r, R = known.inner_diameter / 2.0, known.inner_diameter / 2.0 + known.wall
    area = math.pi * (R * R - r * r)
    geom = {"L": known.pipe_length, "R": R, "r": r}
    rows = []
    print(f"concrete FT = {args.ft:g}, FC = {args.fc:g} MPa, GF = {args.gf:.4g} N/mm; q up to {args.q_max:g} MPa")
    print(f"{'beta':>6} {'G_p':>6}  {'first cracking (kN)':>20}  {'failure (kN)':>14}  "
          f"{'Australian, sigma_max = ' + format(sigma_allow, 'g') + ' MPa (kN)':>40}  note")
    for G in floats(args.packing_G):
        for beta in floats(args.angles):
            case = f"cap_b{beta:g}_G{G:g}"
            elastic = os.path.join(args.outdir, case + "_elastic.dat")
            cracking = os.path.join(args.outdir, case + "_cracking.dat")
            write_deck(elastic, beta, G, args, extra, False)
            write_deck(cracking, beta, G, args, extra, True)
            h5, stop, _ = run(feps, elastic)
            note = []
            if h5 is None:
                first = float("nan")
                note.append(f"elastic run stopped: {stop}")
            else:
                with open_result(h5) as f:
                    q_ref = end_force(f["steps"][steps(f)[-1]])   # at q_max on the modelled part
                scale = args.q_max * area / q_ref
                first, k, _, _ = first_cracking(h5, args.ft, scale)
                if 0 < k <= SEAT_STEPS:
                    note.append(f"first crack in stage seat (step {k}), while the misalignment is applied")
            _, stopc, progress = run(feps, cracking)
            fail = failure(stopc, progress, args.q_max, args.seat, area)
            if stopc:
                note.append(f"the cracking run stopped: {stopc.split(': the step')[0]}")
            E_p = 2.0 * G * (1.0 + args.packing_nu)
            allow = australian_allowable(feps, beta, known.packing, E_p, geom, sigma_allow)
            rows.append({"beta_deg": beta, "G_p": G, "first_cracking_N": first, "failure_N": fail,
                         "australian_allowable_N": allow})
            fmt = (lambda v: "at seating" if v == 0.0 else ("> q-max" if math.isinf(v) else
                                                              ("-" if math.isnan(v) else f"{v / 1e3:.0f}")))
            print(f"{beta:6g} {G:6g}  {fmt(first):>20}  {fmt(fail):>14}  {allow / 1e3:40.0f}  {'; '.join(note)}")
    with open(os.path.join(args.outdir, "capacity.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    if args.plot:
        plot(rows, sigma_allow, args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
