#!/usr/bin/env python3
"""Checks of scripts/make_pipe_joint.py and its presets make_model_b.py and make_model_c.py (issue
26 item 4), run by .ci/run on the release build (its runs take 1.5 min there, 3.5 min in debug):

- the presets write byte for byte the decks that the generators before the merge wrote (commit
  OLD, read with git show): every thesis case of models B and C and the mesh-study and grid
  options. Byte-identical decks give bit-identical results;
- the generator's own command line with the thesis's values writes the presets' model (every
  record but comments, TITLE, OUTPUT and REPORT);
- a DN 2400 deck (another radius, wall, length and packing) runs, and its mesh is the pipe's;
- --gamma decks hold the gravity, GEOSTATIC, GAMMA and K0 records with their computed values; the
  soil below --water-table is the group soil_wet (checked element by element on the run's mesh);
- --misalignment diagonal --full (model C, the full ring turned by 45 deg) gives the answer of the
  edge deck's full ring (--full) at the same angle and force, and both that of the quarter model;
  --misalignment diagonal alone (the quarter model turned by 45 deg, its symmetry plane held in a
  turned CSYS) that of the diagonal full ring and of the edge quarter model (REPORT JOINT's
  sigma_max, contact width, opening, load and deflection; docs/verification.md, "Diagonal
  misalignment (issue 26 item 4)");
- --soil-around-top: the soil's layers round the packing and the top pipe (element counts and
  extent); under gravity alone the applied weight and the support reactions equal the weight of
  soil, pipes and packing from the geometry (1e-9); with the joint loaded, REPORT JOINT's answers
  move against the soil-round-the-bottom deck's as the bonded soil's restraint says
  (docs/verification.md, "Soil round the top pipe (issue 26 item 4)"); with --interface frictional
  the soil meets the pipes and packing through interfaces only, and the top body's axial balance
  holds (the jacking force = the joint's normal force + the interfaces' axial shear, 1e-7), also
  in the ground's weight with cohesionless interfaces (c = 0), whose in-situ normal force on the
  top body is Ripley's estimate's to 3 %;
- bad options stop with exit status 2 naming the option.

    python3 test/cli/check_pipe_joint.py --feps FEPS [--tmp FOLDER]

FOLDER keeps the decks and results (default: a temporary folder, removed at the end).

Prints one line per check ('  ok   ...' or '  FAIL ...'); exit status 1 when any failed.
"""
import argparse
import filecmp
import math
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OLD = "8e0eca4b1eaabb8ee0304d4f3d0102f0bb2c89a7"   # main before the merge: the two generators of their own
GEN = os.path.join(ROOT, "scripts", "make_pipe_joint.py")
FAILED = []


def check(name, good, detail=""):
    print(f"  {'ok  ' if good else 'FAIL'} {name}" + ("" if good else f": {detail}"))
    if not good:
        FAILED.append(name)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def model_lines(path):
    """The deck's records but comments, TITLE, OUTPUT and REPORT (names and thesis references)."""
    with open(path) as f:
        return [ln for ln in f if not re.match(r"!|TITLE|OUTPUT|REPORT", ln)]


def identity(tmp):
    """The presets against the generators of commit OLD, on every case and option set."""
    old = os.path.join(tmp, "old", "scripts")
    os.makedirs(old, exist_ok=True)
    for name in ("make_model_b.py", "make_model_c.py", "feps_cli.py"):
        got = run(["git", "-C", ROOT, "show", f"{OLD}:scripts/{name}"])
        if got.returncode != 0:
            check(f"git show {OLD[:7]}:scripts/{name}", False, got.stderr.strip())
            return
        with open(os.path.join(old, name), "w") as f:
            f.write(got.stdout)
    env = dict(os.environ, FEPS_BENCHMARKS=os.environ.get("FEPS_BENCHMARKS")
               or os.path.join(ROOT, "..", "shared", "benchmarks"))
    sets = [("make_model_b.py", []), ("make_model_b.py", ["--refine", "2", "--element", "hex20", "--cases", "FE1,FD2"]),
            ("make_model_b.py", ["--element", "wedge6", "--cases", "PE3,SD1,FE2"]),
            ("make_model_b.py", ["--element", "wedge15", "--cases", "FD3"]),
            ("make_model_b.py", ["--soil-radius", "2345.67", "--cases", "FE1,SD2"]),
            ("make_model_b.py", ["--kinds", "S,F,P", "--loads", "E,D", "--soil-E", "50", "--phi", "25", "--psi", "5"]),
            ("make_model_c.py", []), ("make_model_c.py", ["--theta-step", "6", "--wall-elements", "3", "--z-refine", "2",
                                                          "--cases", "C_G300_nu0.1_b0.09,C_G900_nu-0.3_b0.27"]),
            ("make_model_c.py", ["--soil-radius", "3000", "--steps", "7", "--theta-step", "1.5"]),
            ("make_model_c.py", ["--Gp", "600", "--nup", "-0.3", "--beta", "0.18", "--soil-E", "1440", "--psi", "0,10"])]
    decks = 0
    for i, (script, args) in enumerate(sets):
        dirs = [os.path.join(tmp, f"id{i}_{w}") for w in ("old", "new")]
        for d, folder in zip(dirs, (old, os.path.join(ROOT, "scripts"))):
            got = run([sys.executable, os.path.join(folder, script), "--outdir", d] + args, env=env)
            if got.returncode != 0:
                check(f"{script} {' '.join(args)} ({d})", False, got.stderr.strip()[-300:])
                return
        names = sorted(os.listdir(dirs[0]))
        same = names == sorted(os.listdir(dirs[1])) and all(
            filecmp.cmp(os.path.join(dirs[0], n), os.path.join(dirs[1], n), shallow=False) for n in names)
        check(f"{script} {' '.join(args) or '(the thesis cases)'}: {len(names)} decks byte for byte as at {OLD[:7]}",
              same and names, f"{names[:3]}...")
        decks += len(names)
    print(f"       ({decks} decks compared)")


def generic(tmp, feps):
    """The generator's command line: the thesis's model, a DN 2400 run, gravity, bad options."""
    def gen(name, *args):
        out = os.path.join(tmp, name)
        got = run([sys.executable, GEN, "-o", out] + list(args))
        return out if got.returncode == 0 else None

    pairs = [("thesis.dat", [], "input/modelC/C_G300_nu0.1_b0.09.dat"),
             ("thesisE.dat", ["--packing-E", "660", "--jacking-force", str(10.0 * math.pi * (715.0 ** 2 - 600.0 ** 2))],
              "input/modelC/C_G300_nu0.1_b0.09.dat"),
             ("fe1.dat", ["--packing", "0", "--interface", "frictional"], "input/modelB/FE1.dat"),
             ("pd3.dat", ["--packing", "0", "--misalignment", "diagonal", "--soil-phi", "15", "--soil-E", "1440"],
              "input/modelB/PD3.dat"),
             ("se2.dat", ["--packing", "0", "--soil-E", "14.4", "--jacking-force", "2e6"], "input/modelB/SE2.dat")]
    for name, args, ref in pairs:
        out = gen(name, *args)
        check(f"make_pipe_joint.py {' '.join(args) or '(defaults)'}: the model of {os.path.basename(ref)}",
              out and model_lines(out) == model_lines(os.path.join(ROOT, ref)))
    # DN 2400: radius, wall, length and packing all off the thesis's; a coarse mesh and 2 steps
    out = gen("dn2400.dat", "--inner-diameter", "2400", "--wall", "200", "--pipe-length", "3000", "--packing", "25",
              "--angle", "0.2", "--theta-step", "24", "--steps", "2")
    text = open(out).read().replace("STAGE, s3, STEPS=100,", "STAGE, s3, STEPS=1,") if out else ""
    h5 = os.path.join(tmp, "dn2400.h5")
    with open(os.path.join(tmp, "dn2400.dat"), "w") as f:
        f.write(text)
    got = run([feps, os.path.join(tmp, "dn2400.dat"), "--quiet", "--output", h5, "--method", "full-newton-raphson",
               "--maxit", "100"])
    check("a DN 2400 deck (r 1200..1400, L 3000, a 25) runs", got.returncode == 0, got.stderr[-300:])
    if got.returncode == 0:
        sys.path.insert(0, os.path.join(ROOT, "scripts"))
        import postprocess_model_c as pmc
        with h5py.File(h5) as f:
            x = f["mesh/coordinates"][...]
            geo = pmc.geometry(f)
            top = np.unique(f["mesh/groups/top_pipe/connectivity"][...]) - 1
        r = np.hypot(x[:, 0], x[:, 1])
        want = (1200.0, 1400.0, 3000.0, 25.0, 800.0)
        check("... its mesh is the pipe's: r 1200..1400 in the pipes, soil to 2000 x 1400 / 715 = 3916.1, "
              "z to 1500 + 25 + 3000; /summary names the pipe",
              tuple(geo) == want and abs(r[top].min() - 1200) < 1e-6 and abs(r[top].max() - 1400) < 1e-6
              and abs(r.max() - 3916.1) < 1e-6 and abs(x[:, 2].max() - 4525.0) < 1e-6, f"{geo}, {r.max()}")
        res = pmc.postprocess(h5, verbose=False)
        # delta: the mean ux of the top end (z = 4525) is the prescribed L tan(beta), L = 3000 (4 decimals)
        delta = 3000.0 * math.tan(math.radians(0.2))
        check(f"... postprocess_model_c.py reads it with its geometry: Z = {res['Z']:.0f} mm in (0, 2800], "
              f"delta = {res['delta']:.4f} mm = 3000 tan(0.2 deg) = {delta:.4f}",
              0.0 < res["Z"] <= 2800.0 and abs(res["delta"] - delta) < 1e-4, f"{res['Z']}, {res['delta']}")
    out = gen("cap.dat", "--theta-step", "24", "--angle", "0.1", "--capacity", "0.05", "--jacking-stress", "40",
              "--steps", "40", "--concrete", "4", "40", "0.1")
    text = open(out).read() if out else ""
    check("--capacity 0.05 --concrete 4 40 0.1: stage seat (5 % of q and the misalignment, 5 steps), stage jack "
          "(the rest, 40 steps), full Newton with the line search, the pipes' CONCRETE",
          "CONTROLS, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-6, LINESEARCH=energy\n" in text
          and "STAGE, seat, STEPS=5, LOAD=0.05, OUTPUT=1\nDISPLACE, top_end_nodes, X=4.3633\n" in text
          and "STAGE, jack, STEPS=40, LOAD=0.95, OUTPUT=1\n" in text and "STAGE, s2" not in text
          and "MATERIAL, concrete, CONCRETE, E=40000., NU=0.2, FT=4, FC=40, GF=0.1, PHI=35, PSI=35\n" in text)
    got = run([feps, out or "", "--check"])
    check("... and passes feps --check", got.returncode == 0, got.stderr[-300:])
    gravity(tmp, feps, gen)
    diagonal(tmp, feps, gen)
    for args, words in ((["--gamma", "2e-5", "--soil-phi", "30"], "--gamma needs --cover"),
                        (["--gamma", "2e-5", "--soil-phi", "30", "--cover", "500"], "--cover 500"),
                        (["--gamma", "2e-5", "--cover", "5000"], "--gamma needs --k0"),
                        (["--k0", "0.5"], "need --gamma"),
                        (["--full", "--packing", "0"], "--full is model C's"),
                        (["--soil-around-top", "--packing", "0"], "--soil-around-top is model C's"),
                        (["--theta-step", "5"], "must divide 168"),
                        (["--capacity", "0.05", "--packing", "0"], "--capacity is model C's"),
                        (["--concrete", "4", "40", "0.1", "--packing", "0"], "--concrete is model C's"),
                        (["--capacity", "1.5"], "--capacity 1.5"),
                        (["--concrete", "40", "4", "0.1"], "FT 40 must be below FC 4"),
                        (["--wall", "-3"], "argument --wall")):
        got = run([sys.executable, GEN, "-o", os.path.join(tmp, "bad.dat")] + args)
        check(f"make_pipe_joint.py {' '.join(args)}: exit 2 naming '{words}'",
              got.returncode == 2 and words in got.stderr and not os.path.exists(os.path.join(tmp, "bad.dat")),
              f"exit {got.returncode}: {got.stderr[-200:]}")


def gravity(tmp, feps, gen):
    """--gamma: the records and their values; the wet soil by its elements' centres."""
    args = ["--inner-diameter", "1000", "--wall", "100", "--theta-step", "24", "--steps", "1", "--gamma", "2e-5",
            "--soil-phi", "30", "--cover", "1500", "--water-table", "800"]
    out = gen("wet.dat", *args)
    text = open(out).read() if out else ""
    # surface 600 + 1500 = 2100, water table 2100 - 800 = 1300; K0 = 1 - sin 30 = 0.5; 2e-5 - 9.81e-6
    want = ["STAGE, geostatic, STEPS=4, LOAD=0, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-6, LINESEARCH=energy\n"
            "GRAVITY, X=-1.\nGEOSTATIC, SURFACE=2100., WATER=1300.\n",
            "MATERIAL, soil, MATSUOKA, E=144, NU=0.2, PHI=30., PSI=30., C=0.05, GAMMA=2e-05, K0=0.5\n",
            "MATERIAL, soil_wet, MATSUOKA, E=144, NU=0.2, PHI=30., PSI=30., C=0.05, GAMMA=1.019e-05, K0=0.5\n",
            "NSET, soil_end1, CSYS=3, R=601.:1678.3, Z=1250., TOL=0.01\nFIX, soil_end1, Z\n"]
    check("--gamma 2e-5 --soil-phi 30 --cover 1500 --water-table 800: GRAVITY, GEOSTATIC (SURFACE = 600 + 1500), "
          "GAMMA, submerged GAMMA, K0 = 1 - sin 30, rollers", all(w in text for w in want),
          str([w for w in want if w not in text]))
    # the wet deck runs with its in-situ stress (the dry and the submerged soil meet at WATER=)
    runnable = text
    deck, h5 = os.path.join(tmp, "wet_run.dat"), os.path.join(tmp, "wet_run.h5")
    with open(deck, "w") as f:
        f.write(runnable.replace("STAGE, s3, STEPS=100,", "STAGE, s3, STEPS=1,"))
    got = run([feps, deck, "--quiet", "--output", h5])
    check("... it runs: the GEOSTATIC stage with the soil's two unit weights",
          got.returncode == 0, got.stderr[-300:])
    if got.returncode == 0:
        with h5py.File(h5) as f:
            x = f["mesh/coordinates"][...]
            cx = {g: x[f[f"mesh/groups/{g}/connectivity"][...] - 1, 0].mean(axis=1) for g in ("soil", "soil_wet")}
            applied = f["summary"].attrs["applied_force"] if "applied_force" in f["summary"].attrs else None
        check(f"... {len(cx['soil'])} soil elements centred above x = 1300, {len(cx['soil_wet'])} below",
              cx["soil"].min() > 1300.0 and cx["soil_wet"].max() < 1300.0 and len(cx["soil_wet"]) > 0,
              f"{cx['soil'].min()}, {cx['soil_wet'].max()}, applied {applied}")
    out = gen("b_wet.dat", "--packing", "0", "--interface", "frictional", "--gamma", "2e-5", "--k0", "0.6",
              "--cover", "2000", "--water-table", "1000", "--soil-c", "0")
    text = open(out).read() if out else ""
    check("--packing 0 (model B) --gamma: a geostatic stage before the load, K0 = 0.6, both ends on rollers",
          "LINESEARCH=energy\nGRAVITY, X=-1.\nGEOSTATIC, SURFACE=2715., WATER=1715.\n" in text
          and "GAMMA=1.019e-05, K0=0.6" in text and "FIX, soil_end2, Z" in text and ", LOAD=1, DIVERGENCE=1" in text)
    with open(deck, "w") as f:
        f.write(text)
    got = run([feps, deck, "--check"])
    check("... and passes feps --check", got.returncode == 0, got.stderr[-300:])


def diagonal(tmp, feps, gen):
    """--misalignment diagonal against the edge misalignment. Without the ground's weight the problem
    is rotationally symmetric about the pipe's axis but for the misalignment's direction, and the
    diagonal deck's mesh is the --full edge deck's turned by 45 deg (node for node, element for
    element): the joint's answers agree to rounding. Coarse mesh (12 deg, one element through the
    wall), beta = 0.27 deg (the joint opens), 2 load steps and full Newton-Raphson to 1e-8 (converged states, so no iteration count
    cut-off can tell the decks apart): about 20 s for the four runs on a release build."""
    keys = ("sigma_max", "contact_width", "opening", "load", "deflection_deg")
    res = {}
    for name, args in (("diag_edge", ["--full"]), ("diag_45", ["--misalignment", "diagonal", "--full"]),
                       ("diag_half", ["--misalignment", "diagonal"]), ("diag_quarter", []),
                       ("top_soil", ["--soil-around-top"])):
        out = gen(f"{name}.dat", "--theta-step", "12", "--wall-elements", "1", "--steps", "2", "--angle", "0.27",
                  *args)
        if not out:
            check(f"make_pipe_joint.py {' '.join(args)} writes its deck", False)
            return
        text = open(out).read()
        if name == "diag_45":
            check("--misalignment diagonal: the ring starts at theta = 45 deg, the top end moves along (1, 1) / sqrt 2 "
                  "(CSYS 4), REPORT JOINT's edge at 45 deg, no y = 0 symmetry plane",
                  "A, 3, 600., 45., 0.," in text and "DISPLACE, top_end_nodes, X=11.7811, CSYS=4" in text
                  and "CSYS, 4, CARTESIAN, 0., 0., 0., 0.7071067811865476, 0.7071067811865475, 0.," in text
                  and ", EDGE=45." in text and "symmetry_y" not in text and "symmetry_plane" not in text)
        if name == "diag_half":
            check("--misalignment diagonal (no --gamma): the quarter ring theta 45..225, its symmetry plane y = 0 of "
                  "CSYS 4 (turned by 45 deg) held in y, every support in CSYS 4",
                  "A, 3, 600., 45., 0.," in text and "ring=half" in text and "NSET, symmetry_plane, CSYS=4, Y=0., TOL=0.01"
                  in text and "FIX, symmetry_plane, Y, CSYS=4\nFIX, symmetry_z, Z, CSYS=4" in text
                  and "FIX, soil_outer, X, Y, CSYS=4" in text and "DISPLACE, top_end_nodes, X=11.7811, CSYS=4" in text)
        with open(out, "w") as f:
            f.write(text.replace("STAGE, s3, STEPS=100,", "STAGE, s3, STEPS=1,").replace("DELTA1=1e-4", "DELTA1=1e-8"))
        h5 = os.path.join(tmp, f"{name}.h5")
        got = run([feps, out, "--quiet", "--output", h5, "--method", "full-newton-raphson", "--maxit", "100"])
        if got.returncode != 0:
            check(f"{name}: the deck runs", False, got.stderr[-300:])
            return
        with h5py.File(h5) as f:
            a = f["summary"].attrs
            res[name] = [float(a[f"joint_design_{k}"]) for k in keys] + [int(a["converged"])]
            res[name].append(len(f["mesh/groups/joint/connectivity"]))
            if name == "top_soil":
                x = f["mesh/coordinates"][...]
                soil = x[np.unique(f["mesh/groups/soil/connectivity"][...]) - 1]
                res[name].append((len(f["mesh/groups/soil/connectivity"]), np.hypot(soil[:, 0], soil[:, 1]).min(),
                                  soil[:, 2].max()))

    def rel(x, y):
        return max(abs(u - v) / abs(v) for u, v in zip(x, y))

    # with the ground's weight along -x the diagonal ring's soil splits by the water table element by
    # element (the dry elements are no longer the first of each ring, as in the quarter model)
    out = gen("diag_wet.dat", "--misalignment", "diagonal", "--inner-diameter", "1000", "--wall", "100", "--theta-step",
              "24", "--steps", "1", "--gamma", "2e-5", "--soil-phi", "30", "--cover", "1500", "--water-table", "800")
    with open(out) as f:
        text = f.read()
    with open(out, "w") as f:
        f.write(text.replace("STAGE, s3, STEPS=100,", "STAGE, s3, STEPS=1,"))
    h5 = os.path.join(tmp, "diag_wet.h5")
    got = run([feps, out, "--quiet", "--output", h5])
    if got.returncode != 0:
        check("--misalignment diagonal --gamma --water-table: the deck runs", False, got.stderr[-300:])
    else:
        with h5py.File(h5) as f:
            x = f["mesh/coordinates"][...]
            c = {g: x[f[f"mesh/groups/{g}/connectivity"][...] - 1].mean(axis=1) for g in ("soil", "soil_wet")}
        check(f"--misalignment diagonal --gamma --water-table 800 runs: {len(c['soil'])} soil elements centred above "
              f"x = 1300, {len(c['soil_wet'])} below, on both sides of y = 0",
              c["soil"][:, 0].min() > 1300.0 and c["soil_wet"][:, 0].max() < 1300.0 and c["soil"][:, 1].min() < 0.0
              and c["soil_wet"][:, 1].min() < 0.0 and len(c["soil"]) + len(c["soil_wet"]) == 22 * 4 * 19,
              f"{c['soil'][:, 0].min()}, {c['soil_wet'][:, 0].max()}, {len(c['soil'])} + {len(c['soil_wet'])}")
    e, d, q = res["diag_edge"], res["diag_45"], res["diag_quarter"]
    text = ", ".join(f"{k} {v:.10g}" for k, v in zip(keys, e))
    check(f"diagonal = edge (both the full ring, beta 0.27 deg: the joint opens; q 10 MPa; 1e-9 relative): {text}; "
          f"diagonal off by {rel(d[:5], e[:5]):.1e}", rel(d[:5], e[:5]) < 1e-9 and d[5] == e[5] == 1, f"{e} / {d}")
    # the quarter model: sigma_max, Z, opening and P are its mirror's (Z read from the whole ring's
    # mirror pairs of points, feps_joint_report's contact_width); the deflection is a least-squares
    # slope over the end face's nodes, and the half ring counts the nodes on y = 0 once against the
    # others' twice in the whole ring (5.8e-3 apart)
    check(f"... = the quarter model's (half the interface elements: {q[6]} of {e[6]}; 1e-9 relative, the deflection "
          f"1e-2: {q[4]:.7g} deg)", rel(q[:4], e[:4]) < 1e-9 and abs(q[4] / e[4] - 1) < 1e-2 and 2 * q[6] == e[6]
          and q[5] == 1, f"{q} / {e}")
    h = res["diag_half"]
    check(f"diagonal quarter model (no --gamma) = the diagonal full ring (sigma_max, Z, opening, P: 1e-9 relative; "
          f"off by {rel(h[:4], d[:4]):.1e}) and = the edge quarter model (the five: 1e-9; off by {rel(h[:5], q[:5]):.1e})",
          rel(h[:4], d[:4]) < 1e-9 and rel(h[:5], q[:5]) < 1e-9 and h[5] == 1 and h[6] == q[6], f"{h} / {d} / {q}")
    soil_top(tmp, feps, gen, q, res["top_soil"], keys)
    pipe_soil(tmp, feps, gen, res["top_soil"], keys)


def soil_top(tmp, feps, gen, bottom, top, keys):
    """--soil-around-top: the mesh (the coarse deck of diagonal()), its joint against the soil-round-
    the-bottom deck's, and the weight under gravity alone."""
    # 4 soil layers x 18 theta elements x (19 below the joint + 2 by the packing + 31 by the top pipe)
    count, r_min, z_max = top[7]
    check(f"--soil-around-top: {count} soil elements = 4 x 18 x (19 + 2 + 31), from r = {r_min:g} to z = {z_max:g} "
          "(the top pipe's end)", count == 4 * 18 * 52 and abs(r_min - 715.0) < 1e-9 and abs(z_max - 3765.0) < 1e-9
          and top[5] == 1, str(top))
    # the bonded soil round the top pipe holds it: against its rotation (the deflection and the opening fall)
    # and against the rise of its axis as it turns about the closed edge (the soil pulls it down onto the
    # joint: P and sigma_max grow). Z is not held to a direction: on this mesh it moves by -0.03%, on the
    # default mesh by -6.7% (docs/verification.md)
    ch = {k: top[i] / bottom[i] - 1.0 for i, k in enumerate(keys)}
    check("... with the joint loaded (beta 0.27 deg, q 10 MPa) against soil round the bottom pipe only: "
          + ", ".join(f"{k} {100 * v:+.2f}%" for k, v in ch.items()),
          ch["deflection_deg"] < -0.1 and ch["opening"] < -0.1 and ch["load"] > 0.05 and ch["sigma_max"] > 0.05
          and abs(ch["contact_width"]) < 0.1, str(ch))
    # gravity alone: the generator's pipes weigh nothing, so the check gives them and the packing a weight;
    # the stages of the joint's load are taken out (the geostatic stage only). hex8 on a faceted ring:
    # each element's cross-section is the trapezoid 0.5 (r1^2 - r0^2) sin(dtheta), a prism along z
    out = gen("top_gravity.dat", "--soil-around-top", "--theta-step", "12", "--wall-elements", "1", "--gamma", "2e-5",
              "--k0", "0.5", "--cover", "1500")
    text = open(out).read() if out else ""
    text = text.replace("NU=0.2\nMATERIAL, soil", "NU=0.2, GAMMA=2.4e-5\nMATERIAL, soil").replace(
        "MATERIAL, packing, ELASTIC, G=300, NU=0.1", "MATERIAL, packing, ELASTIC, G=300, NU=0.1, GAMMA=1e-5")
    a, b = text.find("! stage 1:"), text.find("\n", text.find("STAGE, s3"))
    text = text[:a] + text[b + 1:]
    check("... --gamma: the soil's end face on rollers at the top pipe's end (z = 3765), the top end's "
          "displacement on the pipe's nodes only", "NSET, soil_end1, CSYS=3, R=716.:2000.0, Z=3765., TOL=0.01" in text
          and "NSET, top_end_nodes, CSYS=3, R=600.:715., Z=3765., TOL=0.01" in text and "GAMMA=2.4e-5" in text
          and "GAMMA=1e-5" in text and a > 0)
    with open(out, "w") as f:
        f.write(text)
    h5 = os.path.join(tmp, "top_gravity.h5")
    got = run([feps, out, "--quiet", "--output", h5])
    if got.returncode != 0:
        check("--soil-around-top --gamma: the geostatic stage runs", False, got.stderr[-300:])
        return
    # the water table splits the soil round the top pipe as round the bottom one (by element centres)
    wet = gen("top_wet.dat", "--soil-around-top", "--inner-diameter", "1000", "--wall", "100", "--theta-step", "24",
              "--steps", "1", "--gamma", "2e-5", "--soil-phi", "30", "--cover", "1500", "--water-table", "800")
    got = run([feps, wet, "--check"]) if wet else None
    check("--soil-around-top --gamma --water-table 800 (DN 1000): feps --check passes (the GEOSTATIC stage's "
          "two ground layers meet at the table round both pipes)", got is not None and got.returncode == 0,
          got.stderr[-300:] if got else "not written")
    with h5py.File(h5) as f:
        last = f["steps"][sorted(f["steps"].keys())[-1]]
        applied, reaction = last["applied_force"][...].sum(axis=0), last["reaction"][...].sum(axis=0)
    sines = sum(math.sin(math.radians(d)) for d in [3.0] * 4 + [12.0] * 14)

    def area(r0, r1):
        return 0.5 * (r1 ** 2 - r0 ** 2) * sines

    weight = (2.4e-5 * area(600.0, 715.0) * (1250.0 + 2500.0) + 1e-5 * area(600.0, 715.0) * 15.0
              + 2e-5 * area(715.0, 2000.0) * 3765.0)
    check(f"... gravity alone (GEOSTATIC, K0 0.5, elastic): applied {-applied[0]:.10g} N and the reactions "
          f"{reaction[0]:.10g} N along x = the weight of soil, pipes and packing from the geometry {weight:.10g} N "
          "(1e-9)", abs(-applied[0] / weight - 1) < 1e-9 and abs(reaction[0] / weight - 1) < 1e-9
          and max(abs(applied[1:]).max(), abs(reaction[1:]).max()) < 1e-9 * weight, f"{applied}, {reaction}, {weight}")


def pipe_soil(tmp, feps, gen, bonded, keys):
    """--soil-around-top --interface frictional: Mohr-Coulomb interfaces between the soil and the
    pipes and packing (the coarse deck of diagonal()). Its mesh (no node of the soil on a pipe), and
    the top body's axial balance: the jacking force on the top end equals the joint's normal force
    plus the axial shear of its interfaces with the soil, summed here from the interface points'
    tau2 (e2 along +z) and weights (each element a rectangle on the faceted surface: a quarter of
    its area a point); the friction takes a share of the jacking force, where the bonded soil added
    to it (diagonal()). Then the same joint in the ground's weight with cohesionless interfaces
    (c = 0): the GEOSTATIC stage's normal stress on the top body against Ripley's estimate."""
    common = ["--soil-around-top", "--interface", "frictional", "--theta-step", "12", "--wall-elements", "1"]
    out = gen("cap_friction.dat", *common, "--capacity", "0.05", "--steps", "4")
    check("--interface frictional --capacity: full Newton with the line search (without it the capacity deck "
          "cuts back without end)", out is not None and "CONTROLS, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-6, "
          "LINESEARCH=energy\n" in open(out).read())
    out = gen("top_friction.dat", *common, "--steps", "2", "--angle", "0.27")
    text = open(out).read() if out else ""
    check("--interface frictional (model C): group pipe_soil of interface-quad4 with model B's interface law "
          "(Ks = 50 E_s / 144, Kn = 2 Ks, phi = 15, c = 0.05), the top end's nodes the pipe's only",
          "GROUP, pipe_soil, TYPE=interface-quad4, MATERIAL=pipe_soil" in text
          and "MATERIAL, pipe_soil, INTERFACE, KN=100, KS=50, PHI=15., PSI=15., C=0.05" in text
          and "NSET, top_end_nodes, CSYS=3, R=600.:715., Z=3765., TOL=0.01, GROUP=top_pipe" in text)
    res, sums, mesh = joint_with_friction(tmp, feps, out, "1e-8", keys)
    if res is None:
        return
    x, conn, groups = mesh
    solid = np.concatenate([groups["bottom_pipe"], groups["packing"], groups["top_pipe"]])
    radius = np.hypot(x[conn - 1, 0], x[conn - 1, 1])
    check(f"... mesh: {len(conn)} interface elements = 18 x (19 + 2 + 31) on r = 715, lower layer on the pipes and "
          "packing, upper on the soil; no node shared by the soil and a pipe",
          len(conn) == 18 * 52 and abs(radius - 715.0).max() < 1e-9 and np.isin(conn[:, :4], solid).all()
          and np.isin(conn[:, 4:], groups["soil"]).all() and not np.isin(groups["soil"], solid).any())
    sines = sum(math.sin(math.radians(d)) for d in [3.0] * 4 + [12.0] * 14)
    jacking = 10.0 * 0.5 * (715.0 ** 2 - 600.0 ** 2) * sines           # q on the faceted half annulus
    friction = sums[-1][0]
    share = friction / jacking
    check(f"... the top body's axial balance: P / 2 {res[3] / 2:.10g} + the interfaces' axial shear {friction:.10g} "
          f"= q A / 2 {jacking:.10g} N (1e-7); the friction takes {100 * share:.1f}% of the jacking force, P "
          f"{res[3]:.7g} N against the bonded soil's {bonded[3]:.7g}",
          abs((res[3] / 2 + friction) / jacking - 1) < 1e-7 and 0.0 < share < 0.5 and res[3] < 2 * jacking < bonded[3],
          f"{res}, {friction}, {jacking}")
    # the ground's weight, 4 m of cover, c = 0: the in-situ stress closes the interfaces round both pipes
    out = gen("top_friction_c0.dat", *common, "--steps", "4", "--angle", "0.09", "--gamma", "2e-5", "--k0", "0.5",
              "--cover", "4000", "--soil-c", "0")
    res, sums, _ = joint_with_friction(tmp, feps, out, "1e-6", keys) if out else (None, None, None)
    if res is None:
        return
    # Ripley (thesis eq. 1.5.2): the K0 field round an undisturbed hole, integrated over the packing
    # and the top pipe (2515 mm) of the half model: pi R (sigma_v + sigma_h) L / 2 at the axis's depth
    sigma_v = 2e-5 * (4000.0 + 715.0)
    ripley = math.pi * 715.0 * 1.5 * sigma_v * 2515.0 / 2.0
    in_situ, (friction, _) = sums[0][1], sums[-1]
    check(f"... in the ground's weight with c = 0 (GEOSTATIC, K0 0.5, 4 m of cover): the top body's interface normal "
          f"force after the geostatic stage {in_situ:.7g} N = Ripley's pi R (sigma_v + sigma_h) L / 2 {ripley:.7g} N "
          f"(3 %: the ground arches round the stiff pipe); jacked, P / 2 {res[3] / 2:.10g} + the skin friction "
          f"{friction:.10g} = q A / 2 (1e-7)", abs(in_situ / ripley - 1.0) < 0.03
          and abs((res[3] / 2 + friction) / jacking - 1) < 1e-7 and friction > 0.0, f"{in_situ}, {ripley}, {res}")


def joint_with_friction(tmp, feps, deck, tolerance, keys):
    """Run a --interface frictional deck of pipe_soil() to its end (full Newton-Raphson with the line
    search to `tolerance`, one equilibrium step: the interfaces' sliding and opening need the exact
    tangent with the line search; without it full Newton cuts stage 2's first step back without
    end). Returns REPORT JOINT's `keys`, per result step the top body's (z > 1250) axial shear and
    normal force on its pipe/soil interfaces (N), and the mesh; (None, None, None) when it fails."""
    text = open(deck).read()
    text = text.replace("CONTROLS, METHOD=initial-stiffness, MAXIT=10, DELTA1=1e-4, DIVERGENCE=0.1",
                        f"CONTROLS, METHOD=full-newton-raphson, MAXIT=100, DELTA1={tolerance}, LINESEARCH=energy")
    with open(deck, "w") as f:
        f.write(text.replace("STAGE, s3, STEPS=100,", "STAGE, s3, STEPS=1,"))
    h5 = deck[:-4] + ".h5"
    got = run([feps, deck, "--quiet", "--output", h5])
    if got.returncode != 0:
        check(f"{os.path.basename(deck)}: the deck runs", False, got.stderr[-300:])
        return None, None, None
    with h5py.File(h5) as f:
        x = f["mesh/coordinates"][...]
        groups = {g: np.unique(f[f"mesh/groups/{g}/connectivity"][...]) for g in
                  ("soil", "bottom_pipe", "packing", "top_pipe")}
        conn = f["mesh/groups/pipe_soil/connectivity"][...]
        lower = x[conn[:, :4] - 1]
        area = np.linalg.norm(lower[:, 1] - lower[:, 0], axis=1) * np.linalg.norm(lower[:, 3] - lower[:, 0], axis=1)
        top = lower[:, :, 2].mean(axis=1) > 1250.0
        sums = []
        for name in sorted(f["steps"].keys()):
            traction = f["steps"][name]["interface/pipe_soil"][...].reshape(len(conn), 4, 4)[top]
            sums.append((float((traction[:, :, 1].sum(axis=1) * area[top] / 4.0).sum()),
                         float((-traction[:, :, 2].sum(axis=1) * area[top] / 4.0).sum())))
        a = f["summary"].attrs
        if int(a["converged"]) != 1:
            check(f"{os.path.basename(deck)}: every stage converged", False)
            return None, None, None
        return [float(a[f"joint_design_{k}"]) for k in keys], sums, (x, conn, groups)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--feps", required=True)
    ap.add_argument("--tmp", help="a folder for the decks and results, kept (default: a temporary one)")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="check_pipe_joint.") as scratch:
        tmp = a.tmp or scratch
        os.makedirs(tmp, exist_ok=True)
        identity(tmp)
        generic(tmp, os.path.abspath(a.feps))
    print(f"check_pipe_joint: {len(FAILED)} failed")
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
