#!/usr/bin/env python3
"""Compare feps with the thesis and with closed forms, case by case.

    python3 scripts/compare_thesis.py              # the fast cases
    python3 scripts/compare_thesis.py --all        # every case
    python3 scripts/compare_thesis.py sec2.3.4a    # named cases

Prints one row per compared quantity (case, quantity, thesis or closed form, feps, relative
error, verdict) and exits non-zero if any row fails. The cases (--list) and their decks:

    sec2.3.4a, sec2.3.4b  input/verification/sec2_3_4a.dat and sec2_3_4b.dat, with every --method
    table2.2, table2.3    input/verification/table2_2_bar<n>.dat and table2_3_bar<n>.dat, one per
                          row of the thesis's table (bars of n = 2, 3, 5 and 2, 3, 4 nodes)
    sec2.4.3, sec2.6.4    input/verification/sec2_4_3_compression.dat and sec2_4_3_tension.dat
                          (sec2.6.4: with every --method)
    table7.1              the joint models (scripts/joint_models.py) and input/modelB/FE1.dat
                          (FE2.dat, FE3.dat too with --all)
    table7.2              input/modelB/FD1.dat, FD2.dat, FD3.dat
    table7.3              the twelve decks of input/modelC, run by scripts/campaign_modelC.sh
    table7.4              the joint models; with --all also model C (input/modelC, as table7.3)
    orderings             input/modelB/SE1-3.dat and SD1-3.dat (FE1-3, FD1-3 too with --all),
                          the twelve decks of input/modelA, and with --all input/chapter9/CR.dat,
                          RE1.dat, RE2.dat, PR1.dat, PR2.dat

The thesis's tables (Tables 2.2, 2.3, 7.3 and 7.4) are read from the benchmarks folder,
$FEPS_BENCHMARKS (default ../shared/benchmarks beside the repository); without it the cases that
need them stop before anything runs, with one line naming the folder.
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402
from feps_cli import Error, benchmark_file, benchmarks_dir, feps_executable, guard  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRESETS = ["euler", "modified-euler", "newton-raphson", "modified-newton-raphson", "initial-stiffness",
           "full-newton-raphson"]


class Table:
    def __init__(self):
        self.rows = []

    def ordering(self, case, quantity, larger, smaller):
        """A qualitative finding: `larger` must exceed `smaller`; the row shows their ratio."""
        ratio = larger / smaller
        self.rows.append((case, quantity, 1.0, ratio, ratio - 1.0, "abs", 0.0, larger > smaller, "ordering"))

    def known(self, case, quantity, reference, value, tol, reason):
        """A row the thesis's own equations do not reproduce: shown with the reason, not failed."""
        err = abs(value - reference) / abs(reference) if reference else abs(value)
        ok_anyway = err <= tol
        self.rows.append((case, quantity, reference, value, err, "rel", tol, True,
                          "within tolerance" if ok_anyway else f"not reproduced: {reason}"))

    def add(self, case, quantity, reference, value, tol, kind="rel", scale=None, erratum=None):
        """kind 'rel': |value - reference| <= tol * max(|reference|, scale or 0);
        kind 'abs': |value - reference| <= tol. With erratum=(corrected, note) the thesis value is
        shown but the corrected one is checked (docs/verification.md gives the evidence)."""
        if erratum is not None:
            corrected, note = erratum
            ok = value is not None and abs(value - corrected) <= (tol if kind == "abs" else tol * abs(corrected))
            err = abs(value - reference) if kind == "abs" else abs(value - reference) / abs(reference)
            self.rows.append((case, quantity, reference, value, err, kind, tol, ok, f"erratum: {note}"))
            return ok
        if value is None or not np.isfinite(value):
            err, ok = float("nan"), False
        else:
            diff = abs(value - reference)
            if kind == "abs":
                err = diff
                ok = diff <= tol
            else:
                den = max(abs(reference), scale or 0.0)
                err = diff / den if den > 0 else diff
                ok = err <= tol
        self.rows.append((case, quantity, reference, value, err, kind, tol, ok, ""))
        return ok

    def print(self):
        head = f"{'case':<36} {'quantity':<46} {'reference':>12} {'feps':>12} {'error':>10}  verdict"
        print(head)
        print("-" * len(head))
        for case, q, ref, val, err, kind, tol, ok, note in self.rows:
            e = f"{err:.2e}" if np.isfinite(err) else "nan"
            unit = "" if kind == "rel" else " abs"
            if note.startswith("not reproduced"):
                verdict = f"KNOWN [{note}]"
            else:
                verdict = ("pass" if ok else "FAIL") + (f" [{note}]" if note else "")
            print(f"{case:<36} {q:<46} {ref:>12.6g} {val if val is not None else float('nan'):>12.6g} "
                  f"{e:>10}  {verdict} (tol {tol:g}{unit})")
        nfail = sum(1 for r in self.rows if not r[7])
        print(f"{len(self.rows) - nfail} passed, {nfail} failed")
        nknown = sum(1 for r in self.rows if r[7] and r[8].startswith("not reproduced"))
        if nknown:
            print(f"({nknown} of the passed rows are KNOWN: not reproduced, with the reason found; "
                  "docs/verification.md)")
        return nfail


def run_feps(feps, deck, workdir, name, *args):
    """Run a deck; return the path of its HDF5 file (or raise with feps's error)."""
    out = os.path.join(workdir, name + ".h5")
    proc = subprocess.run([feps, os.path.join(ROOT, deck), "--output", out, "--quiet", *args],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"feps {deck} {' '.join(args)} failed: {proc.stderr.strip()}")
    return out


def interface_history(path, group="joint"):
    """(load_factor, tractions, strains) of every written step, in step order."""
    with h5py.File(path) as f:
        steps = fr.steps(f)
        lf = np.array([f["steps"][s].attrs["load_factor"] for s in steps])
        tr = np.array([f["steps"][s]["interface"][group][...] for s in steps])
        st = np.array([f["steps"][s]["interface_strain"][group][...] for s in steps])
    return lf, tr, st


# --------------------------------------------------------------------------------------------
# Thesis section 2.3.4
# --------------------------------------------------------------------------------------------

def sec2_3_4a_reference(u):
    """Closed form of SPEC section 7: tau = 1000 u to 100 MPa at u = 0.1, then
    tau = 100 + (1000/3)(u - 0.1) with sigma_n = -2 tau (tan(phi) = 0.5, held normal)."""
    tau = np.where(u <= 0.1, 1000.0 * u, 100.0 + (1000.0 / 3.0) * (u - 0.1))
    sn = np.where(u <= 0.1, -200.0, -2.0 * tau)
    return tau, sn


def case_sec2_3_4a(table, feps, tmp):
    case = "sec2.3.4a"
    for preset in PRESETS:
        h5 = run_feps(feps, "input/verification/sec2_3_4a.dat", tmp, f"a_{preset}", "--method", preset)
        lf, tr, _ = interface_history(h5)
        tau = np.hypot(tr[:, :, 0], tr[:, :, 1])
        sn = tr[:, :, 2]
        label = f"{case} [{preset}]"
        table.add(label, "sigma_n after stage 1 (MPa)", -200.0, sn[0].mean(), 0.005)
        stage2 = lf > 1.0
        u = 0.2 * (lf[stage2] - 1.0)
        tau_ref, sn_ref = sec2_3_4a_reference(u)
        # Every step of stage 2, every point: error relative to the thesis scale (100 MPa at yield).
        err_tau = np.max(np.abs(tau[stage2] - tau_ref[:, None])) / 100.0
        err_sn = np.max(np.abs(sn[stage2] - sn_ref[:, None]) / np.abs(sn_ref[:, None]))
        table.add(label, "tau, all 100 steps: max error / 100 MPa", 0.0, err_tau, 0.005, kind="abs")
        table.add(label, "sigma_n, all 100 steps: max relative error", 0.0, err_sn, 0.005, kind="abs")
        i01 = np.argmin(np.abs(u - 0.1))
        table.add(label, "tau at yield, u = 0.1 mm (MPa)", 100.0, tau[stage2][i01].mean(), 0.005)
        table.add(label, "tau at u = 0.2 mm (MPa)", 133.3, tau[-1].mean(), 0.005)
        table.add(label, "sigma_n at u = 0.2 mm (MPa)", -266.7, sn[-1].mean(), 0.005)


def case_sec2_3_4b(table, feps, tmp):
    case = "sec2.3.4b"
    kn = 2000.0
    for preset in PRESETS:
        h5 = run_feps(feps, "input/verification/sec2_3_4b.dat", tmp, f"b_{preset}", "--method", preset)
        lf, tr, st = interface_history(h5)
        eps_n = st[:, :, 2]
        expected = np.where(eps_n < 0.0, kn * eps_n, 0.0)
        label = f"{case} [{preset}]"
        table.add(label, "max |sigma_n - Kn eps_n (closed)| (MPa)", 0.0,
                  float(np.max(np.abs(tr[:, :, 2] - expected))), 1e-6, kind="abs")
        table.add(label, "max |tau| (MPa)", 0.0, float(np.max(np.hypot(tr[:, :, 0], tr[:, :, 1]))), 1e-6,
                  kind="abs")
        opened = int(np.sum(tr[len(tr) // 2 - 1, :, 3] == 2))
        closed_end = int(np.sum(tr[-1, :, 3] != 2))
        table.add(label, "points open at the end of stage 1", 4.0, float(opened), 0.0, kind="abs")
        table.add(label, "points closed at the end of stage 2", 8.0, float(closed_end), 0.0, kind="abs")


# --------------------------------------------------------------------------------------------
# Thesis Tables 2.2 and 2.3: curved bars on a quarter circle
# --------------------------------------------------------------------------------------------

def read_bar_table(name):
    rows = []
    with open(benchmark_file(name)) as f:
        lines = [l.strip() for l in f if l.strip() and not l.startswith("#")]
    for line in lines[1:]:
        k, ne, ng, forces = line.split(",")
        rows.append((int(k), int(ne), int(ng), [float(x) for x in forces.split()]))
    return rows


# Table 2.3, 4-node bars: the thesis prints 100.98 N at the outer Gauss points; the
# discretisation gives 100.89 (two independent implementations; the middle point's 98.82
# matches). A transposition of two digits; see docs/verification.md.
BAR_ERRATA = {("table2_3.csv", 4, 0): 100.89, ("table2_3.csv", 4, 2): 100.89}


def bar_case(table, feps, tmp, case, csv, nnodes):
    for k, ne, ng, forces in read_bar_table(csv):
        deck = f"input/verification/{csv[:-4]}_bar{k}.dat"
        h5 = run_feps(feps, deck, tmp, f"{csv[:-4]}_bar{k}")
        with h5py.File(h5) as f:
            last = fr.last_step(f)
            n = f["steps"][last]["bar"]["ring"][:, 0]
        label = f"{case} [bar{k}]"
        table.add(label, "Gauss points written", float(ne * ng), float(n.size), 0.0, kind="abs")
        per_element = n.reshape(ne, ng)
        for g in range(ng):
            ref = forces[g]
            key = (csv, k, g)
            erratum = (BAR_ERRATA[key], "thesis 100.98 for 100.89") if key in BAR_ERRATA else None
            table.add(label, f"axial force, point {g + 1}, every element (N)", ref,
                      float(per_element[np.argmax(np.abs(per_element[:, g] - ref)), g]), 0.01, kind="abs",
                      erratum=erratum)
        if k == 2:
            delta = math.radians(90.0 / (nnodes - 1))
            table.add(label, "2-node bars: 100 / cos(delta/2) (N)", 100.0 / math.cos(delta / 2),
                      float(np.max(np.abs(n - 100.0 / math.cos(delta / 2))) + 100.0 / math.cos(delta / 2)),
                      1e-6, kind="abs")


def case_table2_2(table, feps, tmp):
    bar_case(table, feps, tmp, "table2.2", "table2_2.csv", 9)


def case_table2_3(table, feps, tmp):
    bar_case(table, feps, tmp, "table2.3", "table2_3.csv", 7)


# --------------------------------------------------------------------------------------------
# Thesis sections 2.4.3 and 2.6.4: the Matsuoka-Nakai block
# --------------------------------------------------------------------------------------------

def block_history(path):
    with h5py.File(path) as f:
        steps = fr.steps(f)
        lf = np.array([f["steps"][s].attrs["load_factor"] for s in steps])
        sz = np.array([f["steps"][s]["stress"]["block"][:, 2] for s in steps])
        summ = dict(f["summary"].attrs)
    return lf, sz, summ


EULER_DRIFT = ("Euler drops the unbalanced force of each step (thesis 2.6.1), so the lateral equilibrium "
               "error of the yield step is never corrected; the thesis's 2.6.4 runs used the other four methods")


def block_rows(table, label, lf, sz, which, drift_reason=None):
    plateau, top = (-15.71, -0.04) if which == "compression" else (6.00, 0.02)
    e = 10000.0
    eps = lf * top / 10.0
    elastic = np.abs(e * eps) < 0.9 * abs(plateau)
    slope = float(np.max(np.abs(sz[elastic] / (e * eps[elastic, None]) - 1.0))) if elastic.any() else float("nan")
    table.add(label, "slope / E before yield - 1 (max)", 0.0, slope, 1e-6, kind="abs")
    last = float(sz[-1][np.argmax(np.abs(sz[-1] - plateau))])
    after = np.abs(e * eps) > 1.2 * abs(plateau)
    worst = float(sz[after].flatten()[np.argmax(np.abs(sz[after].flatten() - plateau))])
    if drift_reason:
        table.known(label, "sigma_z plateau, every point, last step (MPa)", plateau, last, 0.002, drift_reason)
        table.known(label, "sigma_z after yield: max deviation (MPa)", plateau, worst, 0.002, drift_reason)
    else:
        table.add(label, "sigma_z plateau, every point, last step (MPa)", plateau, last, 0.002)
        table.add(label, "sigma_z after yield: max deviation (MPa)", plateau, worst, 0.002)


def case_sec2_4_3(table, feps, tmp):
    for which in ("compression", "tension"):
        h5 = run_feps(feps, f"input/verification/sec2_4_3_{which}.dat", tmp, f"mn_{which}")
        lf, sz, _ = block_history(h5)
        block_rows(table, f"sec2.4.3 [{which}]", lf, sz, which)


TIMINGS = []


def case_sec2_6_4(table, feps, tmp):
    """Section 2.6.4: the block with every preset gives the same plateaus; time and work shown."""
    for which in ("compression", "tension"):
        for preset in PRESETS:
            h5 = run_feps(feps, f"input/verification/sec2_4_3_{which}.dat", tmp, f"mn_{which}_{preset}",
                          "--method", preset)
            lf, sz, summ = block_history(h5)
            block_rows(table, f"sec2.6.4 [{which}, {preset}]", lf, sz, which,
                       drift_reason=EULER_DRIFT if preset == "euler" else None)
            TIMINGS.append((f"sec2.6.4 {which}", preset, int(summ["steps"]), int(summ["iterations"]),
                            int(summ["factorizations"]), int(summ["cutbacks"]), float(summ["wall_time"])))


# --------------------------------------------------------------------------------------------
# Thesis chapter 7: analytical joint models and model B
# --------------------------------------------------------------------------------------------

def joint_model_rows(table, prefix, feps):
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import joint_models
    joint_models.use_feps(feps)       # the library's models, through `feps joint`
    known = joint_models.not_reproduced()
    for case, quantity, thesis, value, tol in joint_models.table_rows():
        if not case.startswith(prefix):
            continue
        if (case, quantity) in known:
            table.known(case, quantity, thesis, value, tol, known[(case, quantity)])
        else:
            table.add(case, quantity, thesis, value, tol)


MODEL_B_EDGE = {"FE1": 0.0502, "FE2": 0.0544, "FE3": 0.0370}   # Table 7.1
MODEL_B_DIAGONAL = {"FD1": (0.2521, 0.2080), "FD2": (2.116, 2.071), "FD3": (0.0587, 0.0238)}  # Table 7.2


def summary_attr(path, key):
    with h5py.File(path) as f:
        return float(f["summary"].attrs[key])


def case_table7_1(table, feps, tmp, full=False):
    joint_model_rows(table, "table7.1", feps)
    for case, thesis in MODEL_B_EDGE.items():
        if case != "FE1" and not full:
            continue
        h5 = run_feps(feps, f"input/modelB/{case}.dat", tmp, f"modelB_{case}")
        table.add(f"table7.1 [{case}]", "deflection angle at the pipe end (deg)", thesis,
                  summary_attr(h5, "rotation_deflection_deg"), 0.15)


def case_table7_2(table, feps, tmp, full=True):
    for case, (total, rigid) in MODEL_B_DIAGONAL.items():
        h5 = run_feps(feps, f"input/modelB/{case}.dat", tmp, f"modelB_{case}")
        table.add(f"table7.2 [{case}]", "total deflection angle (deg)", total,
                  summary_attr(h5, "rotation_deflection_deg"), 0.15)
        table.add(f"table7.2 [{case}]", "rigid rotation angle (deg)", rigid,
                  summary_attr(h5, "rotation_rigid_deg"), 0.15)


MODEL_C_ROWS = {}


def model_c_rows(feps, tmp):
    """Run the 12 model C decks once (scripts/campaign_modelC.sh: as many at once as cores; about 13
    minutes on this shared 2-core machine with the release build, more under load) and keep
    their rows."""
    if not MODEL_C_ROWS:
        sys.path.insert(0, os.path.join(ROOT, "scripts"))
        import postprocess_model_c
        results = os.path.join(tmp, "modelC")
        # a case that fails has no result file: its rows then show feps = None (FAIL)
        subprocess.run(["bash", os.path.join(ROOT, "scripts", "campaign_modelC.sh"), "-o", results, "--feps", feps],
                       capture_output=True, text=True)
        MODEL_C_ROWS["rows"] = postprocess_model_c.compare_rows(results)
    return MODEL_C_ROWS["rows"]


def model_c_into(table, feps, tmp, prefix):
    """Model C rows. A Table 7.3 beta_bar row whose thesis pair (beta*, beta_bar) is closer than
    statics allows, given the thesis's own Z and sigma_max (postprocess_model_c.thesis_beta_bar_bound:
    the top pipe must carry H = P e / L and its section A-A turn less than its chord by the shear
    angle less a bending term; beta_bar, a slope on r = 715 over x >= 250, is steeper than that
    by the section's warping, taken from feps's result, and less steep by the interface's elastic
    closure), is shown as not reproducible with the numbers; docs/verification.md, model C, "Why
    beta_bar cannot equal beta*". Any other row is checked against its tolerance."""
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import postprocess_model_c as pmc
    for case, quantity, thesis, value, tol, warping in model_c_rows(feps, tmp):
        if not case.startswith(prefix):
            continue
        if quantity.startswith("beta_bar") and warping is not None:
            e, bound, gap = pmc.thesis_beta_bar_bound(case[case.index("[") + 1:case.index("]")], warping)
            if gap < bound:
                table.known(case, quantity, thesis, float(value), tol,
                            f"thesis beta* - beta_bar = {gap:.4f} deg, but with its own Z the joint resultant is "
                            f"e = {e:.0f} mm off the axis and statics needs >= {bound:.4f} deg (top pipe shear less "
                            f"bending, beam theory; less A-A's warping {warping:.4f} in feps; plus the elastic "
                            "closure)")
                continue
        table.add(case, quantity, thesis, None if value is None else float(value), tol if tol is not None else 0.03)


def case_table7_3(table, feps, tmp, full=True):
    model_c_into(table, feps, tmp, "table7.3")


def case_table7_4(table, feps, tmp, full=False):
    joint_model_rows(table, "table7.4", feps)
    if full:
        model_c_into(table, feps, tmp, "table7.4")


def peak_tension(path, group="pipe"):
    with h5py.File(path) as f:
        last = fr.last_step(f)
        return float(f["steps"][last]["principal"][group][:, 0].max())


def case_orderings(table, feps, tmp, full=False):
    """Qualitative findings: chapter 5 (elastic soil, edge load): soft soil raises the peak
    tensile stress and stiff soil lowers it, SE2 > SE1 > SE3 (thesis 5.3.1); the diagonal load is
    more severe than the edge load (5.6 (5); scripts/orderings_model_b_c.py); chapter 6 (--all):
    the packing with nu_p = 0.4 gives the highest tension in the pipes, -0.3 the lowest, and
    G_p = 900 more than 300 (6.3-6.5); chapter 4 and 9: scripts/orderings_model_a_ch9.py."""
    peaks = {}
    for case in ("SE1", "SE2", "SE3"):
        peaks[case] = peak_tension(run_feps(feps, f"input/modelB/{case}.dat", tmp, f"modelB_{case}"))
    for a, b in (("SE2", "SE1"), ("SE1", "SE3")):
        table.ordering("orderings [model B]", f"peak tension {a} > {b} (ratio {a}/{b})", peaks[a], peaks[b])
    # Model B diagonal against edge: elastic soil (linear, seconds) always; with interfaces (the
    # Table 7.1 / 7.2 runs, minutes) and model C's packing (the Table 7.3 / 7.4 campaign) with --all.
    model_b_cases = ["SD1", "SD2", "SD3"] + (["FE1", "FE2", "FE3", "FD1", "FD2", "FD3"] if full else [])
    for case in model_b_cases:
        if not os.path.exists(os.path.join(tmp, f"modelB_{case}.h5")):
            run_feps(feps, f"input/modelB/{case}.dat", tmp, f"modelB_{case}")
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import orderings_model_b_c
    rows = orderings_model_b_c.model_b_rows(tmp)
    if full:
        model_c_rows(feps, tmp)
        rows += orderings_model_b_c.model_c_rows(os.path.join(tmp, "modelC"))
    add_orderings(table, rows)
    # Model A (chapter 4, linear, seconds) always; the chapter 9 back analyses (minutes) with --all.
    import orderings_model_a_ch9 as orderings
    decks = [f"input/modelA/{l}{k}_{w}.dat" for l in "ED" for k in (1, 2, 3) for w in ("thick", "thin")]
    if full:
        decks += [f"input/chapter9/{c}.dat" for c in ("CR", "RE1", "RE2", "PR1", "PR2")]
    for deck in decks:
        stem = ("modelA_" if "modelA" in deck else "chapter9_") + os.path.basename(deck)[:-4]
        run_feps(feps, deck, tmp, stem)
    add_orderings(table, orderings.ordering_rows(tmp))


def add_orderings(table, rows):
    """Rows (case, quantity, larger, smaller) as ordering checks; one listed in
    ORDERING_NOT_REPRODUCED that does not hold is shown as KNOWN with its reason."""
    for case, quantity, larger, smaller in rows:
        reason = ORDERING_NOT_REPRODUCED.get((case, quantity))
        if reason and not larger > smaller:
            table.rows.append((f"orderings [{case}]", quantity, 1.0, larger / smaller, larger / smaller - 1.0, "abs",
                               0.0, True, f"not reproduced: {reason}"))
        else:
            table.ordering(f"orderings [{case}]", quantity, larger, smaller)


# Orderings feps does not reproduce, with what was found (docs/verification.md).
MODEL_B_DIAGONAL_PEAK = (
    "in both load cases the global peak is the hoop tension on the internal surface at a loaded end, "
    "where its loaded zone ends (theta = 106 deg; SD3's at the other end, theta = 81); the diagonal "
    "load's is 17-27% lower. The "
    "rest of thesis 5.6 (5) holds: under the diagonal load the tension is higher on the external surface "
    "(the non-loaded corners, thesis 5.3.2) and spreads over 5-25 times the volume (rows beside)")
MODEL_A_DIAGONAL_PEAK = (
    "the global diagonal peaks lie on the external surface next to the upper end's x-support nodes "
    "(the local constraint thesis 4.3.2 warns about) and order D3 > D2 > D1; on the internal surface, "
    "where the thesis's contours show the high tension, D1 is the highest in both walls (peak_inner rows)")

ORDERING_NOT_REPRODUCED = {
    **{(f"model B {m}D{k} vs {m}E{k}", "peak s1 (MPa): diagonal > edge"): MODEL_B_DIAGONAL_PEAK
       for m in "SFP" for k in (1, 2, 3)},
    **{(f"modelA {big} vs {small} {wall}", f"peak s1 (MPa): {big} > {small}"): MODEL_A_DIAGONAL_PEAK
       for big, small in (("D1", "D2"), ("D1", "D3"), ("D2", "D3")) for wall in ("thick", "thin")},
    ("modelA D2 vs D3 thin", "peak_inner s1 (MPa): D2 > D3"):
        "on the thin wall's internal surface the three diagonal cases lie within 7% (D1 29.03, D3 28.05, "
        "D2 27.04 MPa; the thesis: differences 'less than for the edge loading'): D1 is the highest, as "
        "the thesis says, but D3 comes second (the thick wall orders D1 > D2 > D3)",
    ("modelA E2 thin vs thick", "peak s1 (MPa): thin > thick x 25/14.3"):
        "the global peak ratio is 1.70 (above the end-pressure ratio 1.645, below 25/14.3); on the internal "
        "surface, which the thesis's contours show, thin/thick is 1.90-2.72 for every load",
    ("chapter9 PR1 vs CR", "max s1 (MPa): PR1 > CR"):
        "with the band born stress-free in stage 2 (ACTIVATE) as the thesis adds it, PR1 gives 4.93 MPa "
        "against CR's 4.98: every case reaches about ft = 5 MPa (perfectly plastic cap), so the maximum "
        "barely separates them",
    ("chapter9 PR1 vs CR", "max s1 on the external surface (MPa): PR1 > CR"):
        "the prestress alone gives 4.5 MPa axial tension on the external surface 22 mm below the band, but "
        "the end load's axial compression then removes it (PR1 2.94 against CR 4.85 MPa); band width and "
        "position (Figure 9.5) are not in the text",
}


# the cases that read the thesis's tables from the benchmarks folder
NEED_BENCHMARKS = {"table2.2", "table2.3", "table7.1", "table7.3", "table7.4"}

CASES = {
    # id: (function, fast)
    "sec2.3.4a": (case_sec2_3_4a, True),
    "sec2.3.4b": (case_sec2_3_4b, True),
    "table2.2": (case_table2_2, True),
    "table2.3": (case_table2_3, True),
    "sec2.4.3": (case_sec2_4_3, True),
    "sec2.6.4": (case_sec2_6_4, True),
    "table7.1": (case_table7_1, True),
    "table7.2": (case_table7_2, False),
    "table7.3": (case_table7_3, False),
    "table7.4": (case_table7_4, True),
    "orderings": (case_orderings, True),
}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("cases", nargs="*", help="case ids (default: the fast cases)")
    parser.add_argument("--all", action="store_true", help="run every case")
    parser.add_argument("--list", action="store_true", help="list the case ids")
    parser.add_argument("--profile", default=None,
                        help="fpm build profile of feps (default: debug; release with --all)")
    args = parser.parse_args()
    if args.list:
        for cid, (_, fast) in CASES.items():
            print(cid, "(fast)" if fast else "")
        return 0
    unknown = [c for c in args.cases if c not in CASES]
    if unknown:
        raise Error(f"unknown case ids {unknown}; known: {list(CASES)}", 2)
    ids = args.cases or [c for c, (_, fast) in CASES.items() if fast or args.all]
    if NEED_BENCHMARKS.intersection(ids):
        benchmarks_dir()
    feps = feps_executable(args.profile or ("release" if args.all else "debug"))
    table = Table()
    with tempfile.TemporaryDirectory() as tmp:
        for cid in ids:
            try:
                func = CASES[cid][0]
                if "full" in func.__code__.co_varnames:
                    func(table, feps, tmp, full=args.all)
                else:
                    func(table, feps, tmp)
            except (RuntimeError, Error) as exc:
                table.add(cid, f"run failed: {exc}"[:46], 0.0, None, 0.0)
    nfail = table.print()
    if TIMINGS:
        print()
        print(f"{'example':<26} {'method':<24} {'steps':>6} {'iterations':>10} {'factorizations':>14} "
              f"{'cut-backs':>9} {'wall s':>8}")
        for row in TIMINGS:
            print(f"{row[0]:<26} {row[1]:<24} {row[2]:>6} {row[3]:>10} {row[4]:>14} {row[5]:>9} {row[6]:>8.3f}")
    return 1 if nfail else 0


if __name__ == "__main__":
    sys.exit(guard(main))
