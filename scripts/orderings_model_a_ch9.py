#!/usr/bin/env python3
"""Qualitative findings of thesis chapter 4 (model A) and chapter 9 (back analysis) checked on
feps results.

    python3 scripts/orderings_model_a_ch9.py RESULTS_DIR

RESULTS_DIR holds the HDF5 files of the decks of scripts/make_model_a.py and
scripts/make_chapter9.py under their deck OUTPUT names: modelA_<E1..D3>_<thick|thin>.h5 and
chapter9_<CR|RE1|RE2|PR1|PR2>.h5 (e.g. `feps input/modelA/E1_thick.dat --output
RESULTS_DIR/modelA_E1_thick.h5`). Missing files are skipped; a folder that is missing or holds
none of them is an error (exit status 1), as in scripts/orderings_model_b_c.py.

`ordering_rows(results_dir)` returns rows (case, quantity, larger_value, smaller_value): the
thesis says larger_value > smaller_value. Measures (all on the concrete group `pipe`, last
step of the run, Gauss-point values of the most tensile principal stress s1,
'/steps/NNNN/principal/pipe' column 0):

* model A "peak": max s1 over all Gauss points (MPa). Rows:
  - thin over thick "by more than the thickness ratio": larger = peak(thin),
    smaller = peak(thick) * 25 / 14.3 (= 1.748; the end-pressure ratio 1.20 / 0.73 = 1.645 is
    the weaker statement that the normalised thin-wall stress is higher);
  - E1 over E3, E1 over E2 and E2 over E3 (thesis 4.3.1: E1 highest, E3 smallest), D1 over D2
    and D1 over D3 (thesis 4.3.2: highest in D1), D2 over D3 (thesis: "E2 and D2 produce higher
    tensile stresses ... than E3 and D3"), thick and thin;
  - diagonal over edge, Dk over Ek for k = 1, 2, 3 (thick and thin).
  The same rows are repeated with "peak_inner": max s1 over the Gauss points of the innermost
  element layer (the thesis describes the high-tension regions on the internal surface; this
  measure keeps away from the diagonal cases' point supports on the external surface).
* chapter 9 "high-tension volume": the volume (mm3, quarter model) of the concrete whose s1 is
  at least 0.8 ft = 4 MPa, each Gauss point carrying its weight times det J. The Matsuoka
  concrete cannot carry more than about ft, so the region that has yielded or is close to it is
  what the thesis's contours show growing (the 4-5 MPa band of Figures 9.3/9.6); 0.8 ft keeps
  points that are about to yield without counting the elastic bulk. Rows RE2 < RE1 < CR.
* chapter 9 "max tension": max s1 over all Gauss points (MPa). Rows PR2 < CR < PR1; repeated
  for the outermost Gauss layer (thesis 9.3 discusses the maximum below the band on the external
  surface), and the high-tension volume rows PR1 < PR2 < CR (thesis: "the high stress domains
  in PR1 and PR2 are smaller than that in CR, especially in PR1").
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402
from feps_cli import Error, guard  # noqa: E402

FT = 5.0
HIGH_TENSION_FRACTION = 0.8
THICKNESS_RATIO = 25.0 / 14.3


def read_pipe(path):
    """Last step's s1 of group pipe, Gauss-point positions and volumes (feps's own), node radii."""
    with h5py.File(path, "r") as f:
        step = fr.last_step(f)
        s1 = f[f"steps/{step}/principal/pipe"][:, 0]
        coords = f["mesh/coordinates"][...]
        conn = f["mesh/groups/pipe/connectivity"][...]
        x = fr.gauss_points(f, "pipe")
        vol = fr.point_weights(f, "pipe")
    node_r = np.unique(np.round(np.hypot(coords[conn - 1, 0], coords[conn - 1, 1]), 6))
    return s1, x, vol, node_r


def model_a_measures(path):
    s1, x, _, node_r = read_pipe(path)
    r = np.hypot(x[:, 0], x[:, 1])
    # innermost Gauss layer: between the inner surface and the middle of the first element layer
    inner = r < 0.5 * (node_r[0] + node_r[1])
    i = int(np.argmax(s1))
    j = int(np.flatnonzero(inner)[np.argmax(s1[inner])])
    where = lambda k: (round(float(r[k]), 2), round(float(np.degrees(np.arctan2(x[k, 1], x[k, 0]))), 2),
                       round(float(x[k, 2]), 2))
    return {"peak": float(s1.max()), "peak_inner": float(s1[inner].max()),
            "where": where(i), "where_inner": where(j)}


def chapter9_measures(path, fraction=HIGH_TENSION_FRACTION):
    s1, x, vol, node_r = read_pipe(path)
    r = np.hypot(x[:, 0], x[:, 1])
    outer = r > 0.5 * (node_r[-1] + node_r[-2])      # outermost Gauss layer
    return {"max": float(s1.max()), "max_external": float(s1[outer].max()),
            "high_volume": float(vol[s1 >= fraction * FT].sum()), "total_volume": float(vol.sum())}


def ordering_rows(results_dir):
    """Rows (case, quantity, larger_value, smaller_value) of the thesis's qualitative findings
    (chapter 4 model A, chapter 9 back analysis), from the HDF5 results in results_dir; the
    thesis's claim is larger_value > smaller_value. Cases whose files are missing are left out."""
    rows = []
    ma = {}
    for load in ("E", "D"):
        for k in (1, 2, 3):
            for wall in ("thick", "thin"):
                p = os.path.join(results_dir, f"modelA_{load}{k}_{wall}.h5")
                if os.path.exists(p):
                    ma[(f"{load}{k}", wall)] = model_a_measures(p)
    for measure in ("peak", "peak_inner"):
        for case in ("E1", "E2", "E3", "D1", "D2", "D3"):
            if (case, "thin") in ma and (case, "thick") in ma:
                rows.append((f"modelA {case} thin vs thick",
                             f"{measure} s1 (MPa): thin > thick x 25/14.3",
                             ma[(case, "thin")][measure], ma[(case, "thick")][measure] * THICKNESS_RATIO))
        for wall in ("thick", "thin"):
            # thesis 4.3.1: "the highest stress is in the case E1 and ... E3 is the smallest of the
            # three"; 4.3.2: "the highest tensile stress is in the case D1"; 4.5: "E2 and D2 produce
            # higher tensile stresses ... than E3 and D3"
            for big, small in (("E1", "E3"), ("E1", "E2"), ("E2", "E3"), ("D1", "D2"), ("D1", "D3"),
                               ("D2", "D3")):
                if (big, wall) in ma and (small, wall) in ma:
                    rows.append((f"modelA {big} vs {small} {wall}", f"{measure} s1 (MPa): {big} > {small}",
                                 ma[(big, wall)][measure], ma[(small, wall)][measure]))
            for k in (1, 2, 3):
                if (f"D{k}", wall) in ma and (f"E{k}", wall) in ma:
                    rows.append((f"modelA D{k} vs E{k} {wall}", f"{measure} s1 (MPa): diagonal > edge",
                                 ma[(f"D{k}", wall)][measure], ma[(f"E{k}", wall)][measure]))

    ch = {}
    for case in ("CR", "RE1", "RE2", "PR1", "PR2"):
        p = os.path.join(results_dir, f"chapter9_{case}.h5")
        if os.path.exists(p):
            ch[case] = chapter9_measures(p)
    label = f"volume (mm3) with s1 >= {HIGH_TENSION_FRACTION:g} ft = {HIGH_TENSION_FRACTION * FT:g} MPa"
    for big, small in (("CR", "RE1"), ("RE1", "RE2")):
        if big in ch and small in ch:
            rows.append((f"chapter9 {big} vs {small}", f"high-tension {label}: {big} > {small}",
                         ch[big]["high_volume"], ch[small]["high_volume"]))
    for big, small in (("CR", "PR2"), ("PR1", "CR")):
        if big in ch and small in ch:
            rows.append((f"chapter9 {big} vs {small}", f"max s1 (MPa): {big} > {small}",
                         ch[big]["max"], ch[small]["max"]))
    # thesis 9.3 speaks of the external surface ("high stresses below the steel band")
    for big, small in (("CR", "PR2"), ("PR1", "CR")):
        if big in ch and small in ch:
            rows.append((f"chapter9 {big} vs {small}", f"max s1 on the external surface (MPa): {big} > {small}",
                         ch[big]["max_external"], ch[small]["max_external"]))
    # thesis 9.3: "the high stress domains in PR1 and PR2 are smaller than in CR, especially PR1"
    for big, small in (("CR", "PR2"), ("PR2", "PR1")):
        if big in ch and small in ch:
            rows.append((f"chapter9 {big} vs {small}", f"high-tension {label}: {big} > {small}",
                         ch[big]["high_volume"], ch[small]["high_volume"]))
    return rows


def main():
    import argparse
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results_dir", nargs="?", default=".", help="the folder of the model A and chapter 9 HDF5 files")
    results_dir = ap.parse_args().results_dir
    if not os.path.isdir(results_dir):
        raise Error(f"no model A or chapter 9 results in {results_dir}: no such folder")
    rows = ordering_rows(results_dir)
    if not rows:
        raise Error(f"no model A or chapter 9 results in {results_dir} (no pair of modelA_*.h5 or chapter9_*.h5 "
                    "files of the cases compared)")
    w = max((len(r[0]) for r in rows), default=10)
    for case, quantity, larger, smaller in rows:
        verdict = "holds" if larger > smaller else "FAILS"
        print(f"{case:<{w}}  {larger:12.4g} > {smaller:12.4g}  {verdict:5}  {quantity}")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
