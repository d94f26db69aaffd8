#!/usr/bin/env python3
"""Mesh convergence of thesis model B (chapter 5): how far the decks' mesh is from the answer.

    python3 scripts/study_mesh_modelB.py                         # SE1 and FE1 on the default meshes
    python3 scripts/study_mesh_modelB.py --cases SE1 --meshes hex8:1,hex8:2,hex8:4,hex20:1,hex20:2
    python3 scripts/study_mesh_modelB.py --report-only           # tables from the runs already made

The decks' mesh (make_model_b.py: hex8, 2 elements through the wall, 27 around the half pipe, 24
along it) is refined by splitting every element into k x k x k (`hex8:k`), or given 20-node
elements on the same element layout with 8-pair interfaces (`hex20:k`), by make_model_b.py
--refine k --element E. Each run has its own folder OUT/<case>_<element>_r<k>/ with its deck,
results and log, and is not rerun when its results exist (the study can be resumed).

Cases with interfaces or plastic soil run with full Newton-Raphson, --steps steps (default 20),
converged to 1e-6 at every step, so that what changes between meshes is the discretisation and
not the iteration or step error (FE1: 20 such steps give the deflection angle of 100 to 2e-7,
and docs/tradeoff.md: 100 give that of 400 to 1e-7).
SE1 is linear: one solve.

Quantities, at the last step (MPa; s1 most tensile, s3 most compressive principal stress of the
pipe; q = 4.21 MPa, the model's mean end pressure):
  rotation     the deflection angle (deg), REPORT deflection: thesis 7.3's loaded-region slope
  node_s1_max  the largest nodal average (feps `nodal_principal`) of s1 over the pipe, and where
  gp_s1_max    the largest s1 at a Gauss point
  node_s3_min, gp_s3_min   the same for the most compressive stress
  s1@A, s3@B   nodal values at fixed points present in every mesh: A = (r 600, theta 110, z 0)
               on the bore, where the decks' mesh has its peak tension; B = (715, 180, 2500),
               the loaded outer edge of the end; C = (600, 180, 1250) on the bore at mid-length
  sn_min, tau_max   (interface cases) the most compressive normal and largest shear traction
               at the interface's nodes (`nodal_interface`), found at the loaded edge's end of
               the interface (theta 180, z 0 or 2500)
  sn@D, sn@E   the interface's normal traction at D = (715, 180, 200), under the load near the
               end, and E = (715, 90, 1250) at mid-length
For each quantity and each element type with meshes k, 2k, 4k, the observed order of
convergence p = log2(|q_k - q_2k| / |q_2k - q_4k|) and the Richardson estimate
q_4k + (q_4k - q_2k) / (2^p - 1) are tabulated (with k, 2k only: the change, no estimate).

Writes OUT/results.csv and OUT/tables.md (default OUT: results/mesh-modelB, which git ignores).
feps is fpm's release build unless --feps names an executable; runs are one at a time under
`nice -n 5`, timed by /usr/bin/time (wall, peak memory).
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402
import make_model_b  # noqa: E402
from feps_cli import Error, feps_option, guard, positive_int  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
POINTS = {"A": (600.0, 110.0, 0.0), "B": (715.0, 180.0, 2500.0), "C": (600.0, 180.0, 1250.0)}
# interface points, on the pipe's outer face (the interface's lower layer)
INTERFACE_POINTS = {"D": (715.0, 180.0, 200.0), "E": (715.0, 90.0, 1250.0)}
FIELDS = "all,nodal_stress,nodal_principal,nodal_interface"
COLUMNS = ["case", "element", "refine", "status", "dofs", "elements", "wall_s", "peak_mb",
           "steps", "factorizations", "iterations", "unconverged_steps", "rotation",
           "node_s1_max", "node_s1_max_at", "gp_s1_max", "gp_s1_max_at",
           "node_s3_min", "node_s3_min_at", "gp_s3_min", "gp_s3_min_at",
           "s1@A", "s3@A", "s1@B", "s3@B", "s1@C", "s3@C", "sn_min", "sn_min_at", "tau_max", "sn@D", "sn@E"]
# the quantities the tables show, with the number of decimals
QUANTITIES = [("rotation", 6), ("node_s1_max", 4), ("gp_s1_max", 4), ("node_s3_min", 3), ("gp_s3_min", 3),
              ("s1@A", 4), ("s3@B", 3), ("s1@C", 4), ("s3@C", 4), ("sn_min", 4), ("tau_max", 4),
              ("sn@D", 5), ("sn@E", 5)]


def mesh_list(text):
    """argparse type: 'hex8:1,hex8:2,hex20:1' -> [('hex8', 1), ('hex8', 2), ('hex20', 1)]."""
    out = []
    for item in (t.strip() for t in text.split(",") if t.strip()):
        element, _, k = item.partition(":")
        if element not in make_model_b.ELEMENTS or not k.isdigit() or int(k) < 1:
            raise argparse.ArgumentTypeError(f"{item!r}: a mesh is ELEMENT:K with ELEMENT hex8 or hex20, K >= 1")
        out.append((element, int(k)))
    if not out:
        raise argparse.ArgumentTypeError("no mesh given")
    return out


def study_deck(case, element, refine, steps):
    """make_model_b's deck on the refined mesh; nonlinear cases converged by full Newton."""
    text = make_model_b.deck(case, 2000.0, refine, element)
    if case[0] == "S":
        return text
    stage = f"STAGE, load, STEPS={steps}, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-6"
    text, n = re.subn(r"^STAGE, load,.*$", stage, text, flags=re.MULTILINE)
    if n != 1:
        raise Error(f"{case}: no STAGE record to rewrite in make_model_b's deck")
    return "! mesh study (scripts/study_mesh_modelB.py): converged full Newton-Raphson\n" + text


def run_dir(out, case, element, refine):
    return os.path.join(out, f"{case}_{element}_r{refine}")


def run_one(feps, folder, deck_text):
    """Run feps in `folder` unless its results exist; (wall s, peak MB) of this or the recorded run."""
    os.makedirs(folder, exist_ok=True)
    h5 = os.path.join(folder, "result.h5")
    timing = os.path.join(folder, "time.txt")
    if os.path.isfile(h5) and os.path.isfile(timing):
        wall, kb = open(timing).read().split()
        return float(wall), float(kb) / 1024.0
    with open(os.path.join(folder, "deck.dat"), "w") as fh:
        fh.write(deck_text)
    cmd = ["nice", "-n", "5", "/usr/bin/time", "-f", "%e %M", "-o", timing, feps, "--fields", FIELDS,
           "--output", "result.h5", "deck.dat"]
    print(f"running {os.path.basename(folder)} ...", flush=True)
    with open(os.path.join(folder, "log.txt"), "w") as log:
        status = subprocess.call(cmd, cwd=folder, stdout=log, stderr=subprocess.STDOUT)
    if status != 0 or not os.path.isfile(h5):
        raise Error(f"{folder}: feps failed (status {status}); see its log.txt")
    wall, kb = open(timing).read().split()[-2:]
    with open(timing, "w") as fh:
        fh.write(f"{wall} {kb}\n")
    return float(wall), float(kb) / 1024.0


def where(r, t, z):
    return f"{r:.1f}/{t:.2f}/{z:.1f}"


def node_at(f, nodes, point, r, t, z):
    """Index into `nodes` of the node at cylindrical `point` (within 0.01 mm and 1e-4 deg)."""
    pr, pt, pz = point
    hit = np.nonzero((abs(r[nodes] - pr) < 1e-2) & (abs(t[nodes] - pt) < 1e-4) & (abs(z[nodes] - pz) < 1e-2))[0]
    if hit.size != 1:
        raise Error(f"{f.filename}: {hit.size} nodes at r, theta, z = {point} (expected one)")
    return hit[0]


def quantities(h5):
    """The study's quantities of one result file (a dict of COLUMNS)."""
    with fr.open_result(h5) as f:
        step = f["steps/" + fr.last_step(f)]
        summ = fr.summary(f)
        r, t, z = fr.cylindrical(fr.coordinates(f))
        nodes = fr.group_nodes(f, "pipe")
        nodal = step["nodal_principal/pipe"][...][nodes]
        out = {"dofs": summ["dofs"], "steps": summ["steps"], "factorizations": summ["factorizations"], "iterations": summ["iterations"],
               "unconverged_steps": summ["unconverged_steps"], "rotation": summ.get("rotation_deflection_deg", ""),
               "elements": sum(f[f"mesh/groups/{g}/connectivity"].shape[0] for g in fr.groups(f))}
        i, j = int(np.argmax(nodal[:, 0])), int(np.argmin(nodal[:, 1]))
        out["node_s1_max"], out["node_s1_max_at"] = nodal[i, 0], where(r[nodes[i]], t[nodes[i]], z[nodes[i]])
        out["node_s3_min"], out["node_s3_min_at"] = nodal[j, 1], where(r[nodes[j]], t[nodes[j]], z[nodes[j]])
        principal = step["principal/pipe"]
        gr, gt, gz = fr.cylindrical(fr.gauss_points(f, "pipe", principal))
        principal = principal[...]
        i, j = int(np.argmax(principal[:, 0])), int(np.argmin(principal[:, 1]))
        out["gp_s1_max"], out["gp_s1_max_at"] = principal[i, 0], where(gr[i], gt[i], gz[i])
        out["gp_s3_min"], out["gp_s3_min_at"] = principal[j, 1], where(gr[j], gt[j], gz[j])
        for name, point in POINTS.items():
            k = node_at(f, nodes, point, r, t, z)
            out[f"s1@{name}"], out[f"s3@{name}"] = nodal[k, 0], nodal[k, 1]
        if "nodal_interface/contact" in step:
            lower = np.unique(fr.connectivity(f, "contact")[:, :fr.connectivity(f, "contact").shape[1] // 2])
            traction = step["nodal_interface/contact"][...][lower]
            i = int(np.argmin(traction[:, 2]))
            out["sn_min"], out["sn_min_at"] = traction[i, 2], where(r[lower[i]], t[lower[i]], z[lower[i]])
            out["tau_max"] = float(np.hypot(traction[:, 0], traction[:, 1]).max())
            for name, point in INTERFACE_POINTS.items():
                out[f"sn@{name}"] = traction[node_at(f, lower, point, r, t, z), 2]
        else:
            out["sn_min"] = out["sn_min_at"] = out["tau_max"] = out["sn@D"] = out["sn@E"] = ""
    return out


def read_rows(path):
    if not os.path.isfile(path):
        return []
    with open(path) as fh:
        return list(csv.DictReader(fh))


def number(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


def richardson(q1, q2, q4):
    """(observed order p, estimate) from values on meshes k, 2k, 4k; (None, None) when the
    differences do not shrink monotonically."""
    d1, d2 = q1 - q2, q2 - q4
    if d2 == 0.0 or d1 == 0.0 or d1 * d2 < 0.0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log2(abs(d1) / abs(d2))
    return p, q4 + (q4 - q2) / (2.0 ** p - 1.0)


def tables(rows):
    """Markdown: per case, one table of the runs and one of the convergence of each quantity."""
    lines = []
    for case in dict.fromkeys(r["case"] for r in rows):
        runs = sorted((r for r in rows if r["case"] == case and r["status"] == "ok"),
                      key=lambda r: (r["element"], int(r["refine"])))
        if not runs:
            continue
        shown = [(q, d) for q, d in QUANTITIES if any(number(r[q]) is not None for r in runs)]
        lines += [f"### {case}", "", "| mesh | DOFs | steps | wall s | peak MB | fact. | "
                  + " | ".join(q for q, _ in shown) + " |", "| --- " + "| ---: " * (5 + len(shown)) + "|"]
        for r in runs:
            cells = [f"{float(r[q]):.{d}f}" if number(r[q]) is not None else "" for q, d in shown]
            lines.append(f"| {r['element']}:{r['refine']} | {int(r['dofs']):,} | {r['steps']} | {float(r['wall_s']):.1f} | "
                         f"{float(r['peak_mb']):.0f} | {r['factorizations']} | " + " | ".join(cells) + " |")
        lines += ["", "Peak locations (r / theta / z): " + "; ".join(
            f"{r['element']}:{r['refine']} node s1 {r['node_s1_max_at']}, Gauss s1 {r['gp_s1_max_at']}, "
            f"node s3 {r['node_s3_min_at']}" + (f", interface sn {r['sn_min_at']}" if r.get("sn_min_at") else "")
            for r in runs), ""]
        conv = []
        for element in dict.fromkeys(r["element"] for r in runs):
            by_k = {int(r["refine"]): r for r in runs if r["element"] == element}
            for k in sorted(by_k):
                if 2 * k not in by_k:
                    continue
                for q, d in shown:
                    v = [number(by_k[m][q]) if m in by_k else None for m in (k, 2 * k, 4 * k)]
                    if v[0] is None or v[1] is None:
                        continue
                    change = (v[1] - v[0]) / abs(v[1]) if v[1] else float("nan")
                    if v[2] is None:
                        conv.append(f"| {q} | {element} {k}, {2 * k} | {change:+.2%} | | | |")
                        continue
                    p, est = richardson(*v)
                    last = (v[2] - v[1]) / abs(v[2]) if v[2] else float("nan")
                    conv.append(f"| {q} | {element} {k}, {2 * k}, {4 * k} | {change:+.2%} | {last:+.2%} | "
                                + (f"{p:.2f} | {est:.{d}f} |" if p is not None else "none | |"))
        if conv:
            lines += ["| quantity | meshes | change k -> 2k | change 2k -> 4k | order p | Richardson |",
                      "| --- | --- | ---: | ---: | ---: | ---: |"] + conv + [""]
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="SE1,FE1", help="model B case ids (default SE1,FE1)")
    ap.add_argument("--meshes", type=mesh_list, default=mesh_list("hex8:1,hex8:2,hex8:4,hex20:1"),
                    help="ELEMENT:K list (default hex8:1,hex8:2,hex8:4,hex20:1; hex8:4 of FE1 is slow)")
    ap.add_argument("--steps", type=positive_int, default=20, help="full Newton steps of nonlinear cases")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "mesh-modelB"))
    ap.add_argument("--feps", default="", help="feps executable (default: fpm's release build)")
    ap.add_argument("--report-only", action="store_true", help="tables from the runs already made")
    args = ap.parse_args(argv)
    cases = [c for c in args.cases.split(",") if c]
    try:
        for c in cases:
            make_model_b.parse_case(c)
    except ValueError as exc:
        raise Error(str(exc), 2)
    out = os.path.abspath(args.out)
    if args.report_only and not os.path.isdir(out):
        raise Error(f"--out {args.out}: no such folder", 2)
    os.makedirs(out, exist_ok=True)
    csv_path = os.path.join(out, "results.csv")
    rows = {(r["case"], r["element"], r["refine"]): r for r in read_rows(csv_path)}
    feps = None if args.report_only else feps_option(args.feps)
    for case in cases:
        for element, k in args.meshes:
            folder = run_dir(out, case, element, k)
            if args.report_only:
                h5, timing = os.path.join(folder, "result.h5"), os.path.join(folder, "time.txt")
                if not (os.path.isfile(h5) and os.path.isfile(timing)):
                    continue
            wall, mb = run_one(feps, folder, study_deck(case, element, k, args.steps)) if feps else \
                [float(x) for x in open(os.path.join(folder, "time.txt")).read().split()]
            if not feps:
                mb /= 1024.0
            row = {"case": case, "element": element, "refine": str(k), "status": "ok",
                   "wall_s": f"{wall:.2f}", "peak_mb": f"{mb:.0f}"}
            row.update(quantities(os.path.join(folder, "result.h5")))
            rows[(case, element, str(k))] = row
            with open(csv_path, "w", newline="") as fh:
                w = csv.DictWriter(fh, fieldnames=COLUMNS)
                w.writeheader()
                for r in rows.values():
                    w.writerow({c: r.get(c, "") for c in COLUMNS})
    if not rows:
        raise Error(f"no runs of {args.cases} on {','.join(f'{e}:{k}' for e, k in args.meshes)} in {out}")
    with open(os.path.join(out, "tables.md"), "w") as fh:
        fh.write(tables(list(rows.values())))
    print(f"wrote {csv_path} and {os.path.join(out, 'tables.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
