#!/usr/bin/env python3
"""Qualitative findings of thesis chapter 5 (model B: diagonal against edge load) and chapter 6
(model C: the packing's Poisson's ratio and shear modulus) checked on feps results.

    python3 scripts/orderings_model_b_c.py RESULTS_DIR

RESULTS_DIR holds model B results as modelB_<case>.h5 (e.g. `feps input/modelB/SD1.dat --output
RESULTS_DIR/modelB_SD1.h5`) and/or model C results as <case>/<case>.h5 (the layout of
scripts/campaign_modelC.sh). Missing files are skipped; a folder that is missing or holds none of
them is an error (one line on stderr, exit status 1).

`ordering_rows(results_dir)` returns rows (case, quantity, larger_value, smaller_value): the
thesis says larger_value > smaller_value. Measures: the most tensile principal stress s1 at the
Gauss points of the last step ('/steps/NNNN/principal/<group>' column 0), concrete only.

* model B, thesis 5.6 conclusion (5): "the 'diagonal' loading condition seems to be more severe
  than the 'edge' loading condition since the tensile stresses in the pipe are higher and over a
  wider region". Rows for each soil k = 1, 2, 3 and each soil model present (S: elastic, F: with
  interfaces, P: Matsuoka): Dk over Ek by
  - "peak": max s1 over the pipe (MPa);
  - "peak on the external surface": max s1 over the outermost Gauss layer (thesis 5.3.2 finds the
    diagonal load's high tension on the external surface at the two non-loaded corners);
  - "tension volume": the volume (mm3, half model) of the pipe where s1 >= q / 4 (q = 4.21 MPa,
    the end load's mean pressure, which normalises the thesis's contours; each Gauss point
    carries its weight times det J).
* model C, thesis 6.3-6.5: for each packing shear modulus and misalignment, the peak s1 over the
  two concrete pipes (groups top_pipe and bottom_pipe; the packing and the interface are left
  out as in the thesis's contours) is highest with nu_p = 0.4 ("the highest stress in the case
  of nu_p = 0.4", Figs. 6.6, 6.10, 6.13, 6.17) and lower with nu_p = -0.3 than with 0.1
  (conclusion (2): "a negative Poisson's ratio produces even better results"); for each nu_p
  and misalignment, G_p = 900 gives a higher peak than 300 (conclusion (3): "the high shear
  modulus also increases the stresses ... in the pipe").
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import orderings_model_a_ch9 as model_a  # noqa: E402  (the pipe's points and weights)
from feps_cli import Error, guard  # noqa: E402
from make_model_c import case_name  # noqa: E402
from postprocess_model_c import peak_tension_pipes  # noqa: E402

MEAN_PRESSURE_B = 4.21            # MPa: model B's end load 1000 kN over the half annulus (SPEC 8)
TENSION_FRACTION_B = 0.25         # of the mean pressure: the "wider region" threshold
POISSON_C = (0.1, 0.4, -0.3)
SHEAR_MODULI_C = (300, 900)
BETAS_C = (0.09, 0.27)


def model_b_measures(path):
    """peak s1 (MPa), over the outermost Gauss layer too, and the volume (mm3) with
    s1 >= TENSION_FRACTION_B * MEAN_PRESSURE_B."""
    s1, x, vol, node_r = model_a.read_pipe(path)
    outer = np.hypot(x[:, 0], x[:, 1]) > 0.5 * (node_r[-1] + node_r[-2])
    return {"peak": float(s1.max()), "peak_external": float(s1[outer].max()),
            "volume": float(vol[s1 >= TENSION_FRACTION_B * MEAN_PRESSURE_B].sum())}


def model_b_rows(results_dir):
    rows = []
    label = f"tension volume (mm3) with s1 >= q/4 = {TENSION_FRACTION_B * MEAN_PRESSURE_B:.2f} MPa"
    for soil_model in "SFP":
        for k in (1, 2, 3):
            edge, diag = (os.path.join(results_dir, f"modelB_{soil_model}{l}{k}.h5") for l in "ED")
            if not (os.path.exists(edge) and os.path.exists(diag)):
                continue
            e, d = model_b_measures(edge), model_b_measures(diag)
            case = f"model B {soil_model}D{k} vs {soil_model}E{k}"
            rows.append((case, "peak s1 (MPa): diagonal > edge", d["peak"], e["peak"]))
            rows.append((case, "peak s1 on the external surface (MPa): diagonal > edge", d["peak_external"],
                         e["peak_external"]))
            rows.append((case, f"{label}: diagonal > edge", d["volume"], e["volume"]))
    return rows


def model_c_rows(results_dir):
    peaks = {}
    for G in SHEAR_MODULI_C:
        for nu in POISSON_C:
            for b in BETAS_C:
                case = case_name(G, nu, b)
                path = os.path.join(results_dir, case, case + ".h5")
                if os.path.exists(path):
                    peaks[(G, nu, b)] = peak_tension_pipes(path)
    rows = []
    quantity = "peak s1 in the pipes (MPa): "
    for b in BETAS_C:
        for G in SHEAR_MODULI_C:
            for big, small in ((0.4, 0.1), (0.4, -0.3), (0.1, -0.3)):
                if (G, big, b) in peaks and (G, small, b) in peaks:
                    rows.append((f"model C G{G} b{b:g} nu{big:g} vs nu{small:g}",
                                 quantity + f"nu_p = {big:g} > {small:g}", peaks[(G, big, b)], peaks[(G, small, b)]))
        for nu in POISSON_C:
            if (900, nu, b) in peaks and (300, nu, b) in peaks:
                rows.append((f"model C nu{nu:g} b{b:g} G900 vs G300", quantity + "G_p = 900 > 300",
                             peaks[(900, nu, b)], peaks[(300, nu, b)]))
    return rows


def ordering_rows(results_dir):
    """Rows (case, quantity, larger_value, smaller_value) of the thesis's findings on model B
    (diagonal against edge) and model C (packing properties) found in results_dir."""
    return model_b_rows(results_dir) + model_c_rows(results_dir)


def main():
    import argparse
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results_dir", nargs="?", default=".", help="the folder of the model B and model C HDF5 files")
    results_dir = ap.parse_args().results_dir
    if not os.path.isdir(results_dir):
        raise Error(f"no model B or model C results in {results_dir}: no such folder")
    rows = ordering_rows(results_dir)
    if not rows:
        raise Error(f"no model B or model C results in {results_dir}")
    for case, quantity, larger, smaller in rows:
        print(f"{case:<34} {quantity:<62} {larger:12.6g} {smaller:12.6g}  {'holds' if larger > smaller else 'FAILS'}")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
