#!/usr/bin/env python3
"""Stability at the extremes, slow cases (the fast ones are `fpm test` groups nonlinear,
matsuoka and analysis): each run must end converged and agree with its finer reference within
the stated tolerance, or stop with feps's clear message; never NaN, never a hang.

    python3 scripts/stability_extremes.py [--feps PATH] [--out results/extremes] [--only NAME ...]

feps is fpm's release build unless --feps names an executable; --only takes the case names below.

Cases (variants of the thesis decks, written into OUT/<name>/deck.dat):

  modelc_open   model C G_p = 900, nu_p = 0.4 with beta = 0.5 deg (delta = 21.8 mm): about two
                thirds of the joint opens; sigma_max (thesis 7.4.3) at 250 stage-2 steps against
                500 steps, tolerance 2%; the open fraction must exceed 50%
  kn8, kn8e5    model B FE1 with the interface stiffness Kn = 8 / 8e5 MPa/mm (Ks = Kn / 2):
                deflection angle at 100 steps against 400 steps, tolerance 1%
  phi54_psi0    chapter 9 CR (Matsuoka phi = 54.9 deg) with psi = 0 and with psi = phi: largest
  phi54_psi54   principal stress at the deck's 400 steps against 1000, tolerance 2%
  giant_step    model B PE1 (Matsuoka soil): one load step (Newton-Raphson, up to 200
                iterations) against 1000 steps, deflection angle, tolerance 1%
  tension_cp_5  chapter 9 CR with TENSION=closest-point: 5 full-Newton steps against the
                deck's 400, largest principal stress, tolerance 0.5% (the thesis's proportional
                rule needs 1 403 iterations and 24 cut-backs for 10 such steps)
  tension_cp_psi0_10  the same with psi = 0 (LU tangents): 10 full-Newton steps against 400

Every run has a time limit (--timeout, default 1800 s): a run that passes it counts as a hang.
A run that stops with feps's clear message (exit 1: "the step does not converge after N
cut-backs" or "the residual is not finite", naming stage, step, load factor and DOF) counts as a clear stop (reported, not a
failure). Writes OUT/summary.csv and prints one line per case; exit status 1 if any case
failed (NaN, hang, crash, disagreement beyond its tolerance).
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import postprocess_model_c as pmc  # noqa: E402
from feps_cli import Error, feps_option, guard, positive  # noqa: E402


def model_c_deck():
    """The model C deck this study was made with, C_G900_nu0.4_b0.27 with 6 deg elements beyond
    theta = 12 (the decks in input/modelC now use 3 deg; docs/verification.md, model C mesh
    sensitivity)."""
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import make_model_c
    return make_model_c.deck(900.0, 0.4, 0.27, theta_step=6.0)


def variant(deck, subs):
    """Deck text (a path in the repository, or a function giving the text) with regex
    substitutions applied (each must match); INCLUDE made absolute."""
    text = deck() if callable(deck) else open(os.path.join(ROOT, deck)).read()
    for pattern, repl in subs:
        text, n = re.subn(pattern, repl, text, flags=re.MULTILINE | re.IGNORECASE)
        if n == 0:
            raise SystemExit(f"stability_extremes: {deck}: no match for {pattern!r}")
    folder = ROOT if callable(deck) else os.path.dirname(os.path.join(ROOT, deck))
    text = re.sub(r"(?im)^INCLUDE, (.+)$", lambda m: "INCLUDE, " + os.path.join(folder, m.group(1).strip()), text)
    return re.sub(r"(?im)^OUTPUT,.*$", "", text)


def steps_sub(stage, n):
    return (rf"^(STAGE,\s*{stage},\s*)STEPS=\d+", rf"\g<1>STEPS={n}")


def last_step(f):
    return f["steps"][sorted(f["steps"], key=int)[-1]]


def non_finite(f):
    """Names of datasets of the last step holding NaN or Inf."""
    bad = []
    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f" and not np.all(np.isfinite(obj[...])):
            bad.append(name)
    last_step(f).visititems(visit)
    return bad


def q_deflection(f):
    return float(f["summary"].attrs["rotation_deflection_deg"])


def q_max_s1(f):
    """Largest most-tensile principal stress over every solid group."""
    principal = last_step(f)["principal"]
    return float(max(np.max(principal[g][:, 0]) for g in principal))


def q_sigma_max(f):
    # sigma_max as the interface's normal stress (the reading these studies were made with; Table
    # 7.4 reads the packing's szz, a few per cent lower: docs/verification.md, model C)
    st = last_step(f)
    return float(pmc.edge_stress(f["mesh/coordinates"][...], f["mesh/groups/joint/connectivity"][...],
                                 st["interface/joint"][...])[0])


def open_fraction(f):
    return float(np.mean(last_step(f)["interface/joint"][:, 3] >= 2))


DELTA_05 = 2500.0 * math.tan(math.radians(0.5))
FULL_NEWTON = (r"^CONTROLS, METHOD=modified-newton-raphson, MAXIT=10", "CONTROLS, METHOD=full-newton-raphson, MAXIT=30")
CASES = {
    "modelc_open": dict(deck=model_c_deck, quantity=q_sigma_max, tol=0.02, extra=open_fraction,
                        subs=[(r"^(DISPLACE, top_end_nodes, X=)[-0-9.eE+]+", rf"\g<1>{DELTA_05:.4f}")],
                        coarse=[steps_sub("s2", 250)], fine=[], what="sigma_max (MPa)"),
    "kn8": dict(deck="input/modelB/FE1.dat", quantity=q_deflection, tol=0.01,
                subs=[(r"KN=100, KS=50", "KN=8, KS=4")], coarse=[steps_sub("load", 100)], fine=[],
                what="deflection (deg)"),
    "kn8e5": dict(deck="input/modelB/FE1.dat", quantity=q_deflection, tol=0.01,
                  subs=[(r"KN=100, KS=50", "KN=8e5, KS=4e5")], coarse=[steps_sub("load", 100)], fine=[],
                  what="deflection (deg)"),
    "phi54_psi0": dict(deck="input/chapter9/CR.dat", quantity=q_max_s1, tol=0.02,
                       subs=[(r"PSI=54\.9", "PSI=0")], coarse=[], fine=[steps_sub("load", 1000)],
                       what="max s1 (MPa)"),
    "phi54_psi54": dict(deck="input/chapter9/CR.dat", quantity=q_max_s1, tol=0.02, subs=[],
                        coarse=[], fine=[steps_sub("load", 1000)], what="max s1 (MPa)"),
    "giant_step": dict(deck="input/modelB/PE1.dat", quantity=q_deflection, tol=0.01, subs=[],
                       coarse=[(r"^STAGE, load, STEPS=400, METHOD=initial-stiffness, MAXIT=10",
                                "STAGE, load, STEPS=1, METHOD=newton-raphson, MAXIT=200")],
                       fine=[(r"^STAGE, load, STEPS=400, METHOD=initial-stiffness, MAXIT=10",
                              "STAGE, load, STEPS=1000, METHOD=modified-newton-raphson, MAXIT=20")],
                       what="deflection (deg)"),
    "tension_cp_5": dict(deck="input/chapter9/CR.dat", quantity=q_max_s1, tol=0.005,
                         subs=[(r"(FT=5\.)", r"\1, TENSION=closest-point")],
                         coarse=[FULL_NEWTON, steps_sub("load", 5)], fine=[], what="max s1 (MPa)"),
    "tension_cp_psi0_10": dict(deck="input/chapter9/CR.dat", quantity=q_max_s1, tol=0.005,
                               subs=[(r"PSI=54\.9", "PSI=0"), (r"(FT=5\.)", r"\1, TENSION=closest-point")],
                               coarse=[FULL_NEWTON, steps_sub("load", 10)], fine=[], what="max s1 (MPa)"),
}


def run(feps, deck_text, folder, timeout, resume=False):
    os.makedirs(folder, exist_ok=True)
    deck = os.path.join(folder, "deck.dat")
    h5 = os.path.join(folder, "run.h5")
    wall_file = os.path.join(folder, "wall.txt")
    if resume and os.path.exists(h5) and os.path.exists(wall_file) and open(deck).read() == deck_text:
        return dict(status="ok", wall=float(open(wall_file).read()), h5=h5)
    with open(deck, "w") as fh:
        fh.write(deck_text)
    if os.path.exists(h5):
        os.remove(h5)
    t0 = time.perf_counter()
    try:
        proc = subprocess.run([feps, deck, "--output", h5], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(status="HANG", wall=time.perf_counter() - t0)
    wall = time.perf_counter() - t0
    if proc.returncode == 0:
        with open(wall_file, "w") as fh:
            fh.write(f"{wall:.3f}\n")
    with open(os.path.join(folder, "log.txt"), "w") as fh:
        fh.write(proc.stdout + proc.stderr)
    if proc.returncode != 0:
        msg = (proc.stderr.strip().splitlines() or ["?"])[-1]
        clear = proc.returncode == 1 and ("does not converge" in msg or "residual is not finite" in msg)
        return dict(status="stopped" if clear else "CRASH", wall=wall, message=msg)
    return dict(status="ok", wall=wall, h5=h5)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--feps", default=None, help="feps executable (default: fpm's release build, built if needed)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "extremes"))
    ap.add_argument("--only", nargs="+", choices=list(CASES), metavar="NAME",
                    help=f"run only these cases, of {', '.join(CASES)}")
    ap.add_argument("--timeout", type=positive, default=1800.0, help="seconds a run may take (default 1800)")
    ap.add_argument("--resume", action="store_true",
                    help="reuse a finished run whose deck is unchanged (OUT/<case>/<level>/run.h5)")
    args = ap.parse_args()
    feps = feps_option(args.feps)
    rows, failed = [], 0
    for name, c in CASES.items():
        if args.only and name not in args.only:
            continue
        results = {}
        for level in ("coarse", "fine"):
            text = variant(c["deck"], c["subs"] + c[level])
            r = run(feps, text, os.path.join(args.out, name, level), args.timeout, args.resume)
            if r["status"] == "ok":
                with h5py.File(r["h5"], "r") as f:
                    bad = non_finite(f)
                    r["status"] = "NaN in " + " ".join(bad) if bad else "ok"
                    if not bad:
                        r["value"] = c["quantity"](f)
                        a = f["summary"].attrs
                        r.update(steps=int(a["steps"]), iterations=int(a["iterations"]),
                                 unconverged=int(a["unconverged_steps"]),
                                 condition=float(a.get("condition_estimate", float("nan"))))
                        if "extra" in c:
                            r["open_fraction"] = c["extra"](f)
            results[level] = r
        co, fi = results["coarse"], results["fine"]
        verdict, rel = "pass", float("nan")
        if "ok" == co["status"] == fi["status"]:
            rel = (co["value"] - fi["value"]) / fi["value"]
            if abs(rel) > c["tol"]:
                verdict = "FAIL (disagree)"
            if "open_fraction" in fi and fi["open_fraction"] <= 0.5:
                verdict = "FAIL (less than half the joint open)"
        elif any(r["status"] in ("HANG", "CRASH") or r["status"].startswith("NaN") for r in (co, fi)):
            verdict = "FAIL (" + ", ".join(r["status"] for r in (co, fi)) + ")"
        else:
            verdict = "clear stop (" + "; ".join(r.get("message", r["status"]) for r in (co, fi))[:100] + ")"
        failed += verdict.startswith("FAIL")
        row = dict(case=name, quantity=c["what"], coarse=co.get("value", ""), fine=fi.get("value", ""),
                   rel_diff=rel, tol=c["tol"], verdict=verdict,
                   coarse_wall_s=round(co["wall"], 1), fine_wall_s=round(fi["wall"], 1),
                   coarse_iterations=co.get("iterations", ""), fine_iterations=fi.get("iterations", ""),
                   unconverged_steps=f"{co.get('unconverged', '')}/{fi.get('unconverged', '')}",
                   condition_estimate=fi.get("condition", ""), open_fraction=fi.get("open_fraction", ""))
        rows.append(row)
        print(f"{name:<12} {c['what']:<18} coarse {row['coarse']!s:>10.8} fine {row['fine']!s:>10.8} "
              f"diff {rel:+.2e} (tol {c['tol']:g})  {verdict}  [{row['coarse_wall_s']} s, {row['fine_wall_s']} s; "
              f"cond {row['condition_estimate']!s:.9}; open {row['open_fraction']!s:.5}]", flush=True)
    os.makedirs(args.out, exist_ok=True)
    if rows:
        with open(os.path.join(args.out, "summary.csv"), "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(guard(main))
