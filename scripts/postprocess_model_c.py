#!/usr/bin/env python3
"""Post-processing of thesis model C (section 7.4): beta*, beta_bar, Z and sigma_max of a case.

    python3 scripts/postprocess_model_c.py results/modelC/C_G300_nu0.1_b0.09/C_G300_nu0.1_b0.09.h5
    python3 scripts/postprocess_model_c.py --table results/modelC      # every case, thesis beside

From the last step of a model C run (decks by scripts/make_model_c.py; those of make_pipe_joint.py
for another pipe name its r_i, r_o, L, a and Kn in /summary, and the positions below, given for
the thesis's pipe, are that pipe's, x = 250 scaled by r_o / 715):

- beta* (eq. 7.4.2): tan(beta*) = (delta - delta_b) / L, L = 2500, delta the x displacement of the
  top end (read from the result), delta_b the x displacement of "the centre of the bottom end of
  the top pipe": the area-weighted mean ux over the top pipe's end face z = 1265 (the rigid
  translation of that section; the face is a ring and has no node at its centre). The mean ux of
  that face's nodes on x = 0 (theta = 90) is printed as a variant.
- beta_bar (7.4.2): the total joint deformation along r = 715 is the axial displacement w of the
  top pipe's mid-length section A-A (z = 2515; w = 0 on the symmetry plane z = 0 of the bottom
  pipe) less the deformation of the interface, taken as its elastic closure sigma_n / Kn (the
  interface's normal stress at the node: feps's nodal_interface field, extrapolated from each
  element's Gauss points to the node and averaged; Kn = 800):
  D(x) = -(w_AA - sigma_n / Kn), positive in compression. tan(beta_bar) is the least-squares slope
  dD/dx over the nodes with x >= 250 mm. Not the interface's whole normal relative displacement
  (the nodal jump uz(packing) - uz(bottom pipe) at z = 1250), which also holds the dilatant
  opening of the sliding points (psi = 20 deg): the thesis's Table 7.3 at beta = 0.27 deg is
  reproduced only with that opening left in, while its beta* and Z are reproduced only with
  the dilation present (docs/verification.md, model C, "What the thesis took out of w").
  Variants printed: the secant slope between x = 250 and 715 (linear interpolation), the slope of
  D averaged over the node radii of the wall (600, 657.5 and 715 in the decks), the slope with
  nothing taken out (raw), with the whole relative displacement taken out (whole_jump), and the
  mean rotation of section A-A (rotation_AA: the slope over every node of the section).
- Z (7.4.3): on each of the four lines of interface Gauss points across the wall (2x2 Gauss per
  quad, the first natural direction, along r, fastest; positions from the lower-layer nodes), the
  front of the contact zone is where sigma_n reaches zero going from x = +715 towards x = -715:
  linear interpolation between the last compressive point and the next one; when that next point
  is open (gap zone, sigma_n = 0 exactly) the line through the last two compressive points is
  extended to zero instead (kept between the two points). A line without any non-compressive
  point has no gap: the zero of the least-squares line sigma_n(x) through all its points
  ("interpolating linearly the stresses to a zero point"). Z = 715 - x_zero, averaged over the
  four lines ("the average value of Z is used").
- sigma_max (7.4.3), "calculated from the average stresses at the centre of elements in the region
  of the pipe edge (theta < 6 deg) with a linear interpolation": the axial stress szz of the
  packing elements whose nodes all lie at theta <= 6 deg, each element's average over its Gauss
  points (/steps/N/cell/stress/packing; the packing is the joint, and the analytical models'
  sigma_max is the packing's stress): 8 elements with the decks' mesh, 2 in theta x 2 through
  the wall x 2 packing layers (the count is printed). A least-squares line of szz against the
  element centre's x (the mean x of its 8 nodes; the two layers' elements share it, so each x
  carries two values) is evaluated at x = 715 and reported as a positive compression. The same
  reading of the interface's normal stress (the interface elements with theta <= 6 deg, 4 with
  the decks' mesh, each the mean of its 4 Gauss points) is printed as sigma_max_interface: it was
  the tabulated reading until 2026-11-22 and is 1-7% higher (docs/verification.md, model C).

Errors are one line on stderr: exit 2 for a result file that is missing or the thesis's tables
missing from the benchmarks folder (FEPS_BENCHMARKS, default ../shared/benchmarks; --table reads
Tables 7.3 and 7.4 there), 1 for a RESULTS_DIR that is missing or holds no <case>/<case>.h5 and
for a result that cannot be read or is not model C's.
"""
import argparse
import csv
import math
import os
import sys
from collections import namedtuple

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402
from feps_cli import Error, benchmark_rows, guard  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
R_IN, R_OUT = 600.0, 715.0
Z_JOINT = 1250.0
Z_TOP_BOTTOM = 1265.0
Z_SECTION_AA = 2515.0
Z_TOP_END = 3765.0
L_PIPE = 2500.0
X_REGION = 250.0      # beta_bar from the deformation in x > 250 mm (thesis 7.4.2)
EDGE_THETA = 6.0      # sigma_max from the elements with theta < 6 deg (thesis 7.4.3)
PACKING_A = 15.0      # mm: the packing thickness the analytical models take (SPEC section 8)
TOL = 1e-3
KN_INTERFACE = 800.0   # MPa/mm, the model C interface's normal stiffness (thesis 6.2, SPEC section 8)


class Geometry(namedtuple("Geometry", "r_in r_out length packing kn")):
    """The pipes of a model C result (mm) and the joint interface's Kn (MPa/mm)."""

    @property
    def z_top_bottom(self):
        return self.length / 2.0 + self.packing

    @property
    def z_section_aa(self):
        return self.z_top_bottom + self.length / 2.0

    @property
    def z_top_end(self):
        return self.z_top_bottom + self.length

    @property
    def x_region(self):
        """beta_bar's region x >= 250 mm at the thesis's size, scaled with r_o (make_pipe_joint.py)."""
        return round(X_REGION * self.r_out / R_OUT, 1)


THESIS = Geometry(R_IN, R_OUT, L_PIPE, PACKING_A, KN_INTERFACE)


def geometry(f):
    """The pipes of result file f: the /summary parameters r_i, r_o, L, a and Kn that
    make_pipe_joint.py's decks write for pipes off the thesis's, else the thesis's (THESIS)."""
    attrs = f["summary"].attrs if "summary" in f else {}
    return Geometry(*(float(attrs.get("parameter_" + k, v)) for k, v in zip(("r_i", "r_o", "L", "a", "Kn"), THESIS)))


def _lsq_line(x, y):
    """(intercept, slope) of the least-squares line y = a + b x."""
    b, a = np.polyfit(np.asarray(x, float), np.asarray(y, float), 1)
    return a, b


def beta_star(coords, conn_top, u, geo=THESIS):
    """beta* of eq. 7.4.2 (deg), delta, delta_b (area-weighted) and the x = 0 variant."""
    top_end = np.abs(coords[:, 2] - geo.z_top_end) < TOL
    delta = float(u[top_end, 0].mean())
    weights = np.zeros(len(coords))
    for elem in conn_top - 1:
        face = elem[:4]                          # hex8 bottom face (counter-clockwise)
        if not np.all(np.abs(coords[face, 2] - geo.z_top_bottom) < TOL):
            continue
        p = coords[face, :2]
        d1, d2 = p[2] - p[0], p[3] - p[1]
        area = 0.5 * abs(d1[0] * d2[1] - d1[1] * d2[0])
        weights[face] += area / 4.0
    delta_b = float(np.sum(weights * u[:, 0]) / np.sum(weights))
    on_face = weights > 0
    axis_nodes = on_face & (np.abs(coords[:, 0]) < TOL)
    # a mesh with no node on x = 0 (theta steps that miss 90 deg) has no such variant
    delta_b_x0 = float(u[axis_nodes, 0].mean()) if axis_nodes.any() else float("nan")
    beta = math.degrees(math.atan((delta - delta_b) / geo.length))
    beta_x0 = math.degrees(math.atan((delta - delta_b_x0) / geo.length))
    return beta, delta, delta_b, beta_x0, float(np.sum(weights))


def section_rotation(coords, conn_top, u, z):
    """The rotation (deg) of the top pipe's section at z: the least-squares slope -dw/dx over every
    node of the section (its mean rotation; beta_bar is the slope of w on r = 715, x >= 250 only,
    where the section is not plane)."""
    top = np.unique(conn_top - 1)
    m = top[np.abs(coords[top, 2] - z) < TOL]
    return math.degrees(-np.polyfit(coords[m, 0], u[m, 2], 1)[0])


def joint_pairs(conn_joint):
    """Map lower node -> upper node of the interface's coincident pairs (0-based)."""
    pairs = {}
    for elem in conn_joint - 1:
        for a in range(4):
            pairs[int(elem[a])] = int(elem[4 + a])
    return pairs


TAKE_OUT = ("elastic", "whole", "none")


def joint_deformation(coords, conn_top, conn_joint, u, radius, sigma_n=None, take_out="elastic", geo=THESIS):
    """x and the total joint deformation D = -(w_AA - jump) (mm, compression positive) along r = radius,
    where jump is what is taken out of w_AA as the interface's deformation:
    'elastic': its elastic closure sigma_n / Kn (the tabulated beta_bar; sigma_n: the nodal
    normal stress at the nodes, feps's nodal_interface),
    'whole': its whole normal relative displacement uz(packing) - uz(bottom pipe) at the node
    pairs, which also holds the dilatant opening of sliding points,
    'none': nothing (D = -w_AA)."""
    if take_out not in TAKE_OUT:
        raise ValueError(f"take_out {take_out!r} is not one of {TAKE_OUT}")
    radii = np.hypot(coords[:, 0], coords[:, 1])
    top_nodes = np.unique(conn_top - 1)
    aa = top_nodes[(np.abs(radii[top_nodes] - radius) < TOL) & (np.abs(coords[top_nodes, 2] - geo.z_section_aa) < TOL)]
    pairs = joint_pairs(conn_joint)
    lower = np.array([n for n in pairs if abs(radii[n] - radius) < TOL])
    if take_out == "elastic":
        jumps = sigma_n[lower] / geo.kn
    elif take_out == "whole":
        jumps = np.array([u[pairs[n], 2] - u[n, 2] for n in lower])
    else:
        jumps = np.zeros(len(lower))
    jump_at = {(round(float(coords[n, 0]), 3), round(float(coords[n, 1]), 3)): j for n, j in zip(lower, jumps)}
    xs, ds = [], []
    for n in aa:
        key = round(float(coords[n, 0]), 3), round(float(coords[n, 1]), 3)
        xs.append(coords[n, 0])
        ds.append(-(u[n, 2] - jump_at[key]))
    order = np.argsort(xs)
    return np.array(xs)[order], np.array(ds)[order]


def _slope_deg(x, d, geo=THESIS):
    """The angle (deg) of the least-squares slope of d over x >= 250 mm (geo.x_region)."""
    sel = x >= geo.x_region - TOL
    return math.degrees(math.atan(_lsq_line(x[sel], d[sel])[1]))


def beta_bar(coords, conn_top, conn_joint, u, sigma_n, geo=THESIS):
    """beta_bar (deg): least-squares slope over x >= 250 on r = 715 of D, w_AA less the interface's
    elastic closure (sigma_n: the interface's normal stress at the nodes, feps's nodal_interface);
    with the variants (a dict: secant, wall-averaged, nothing taken out, the whole relative
    displacement taken out) and the curve (x, D)."""
    x, d = joint_deformation(coords, conn_top, conn_joint, u, geo.r_out, sigma_n, geo=geo)
    secant = (np.interp(geo.r_out, x, d) - np.interp(geo.x_region, x, d)) / (geo.r_out - geo.x_region)
    # every node radius of the wall (600, 657.5, 715 with the decks' 2 elements through it):
    # D(theta) averaged over r, x taken on the mid radius
    radii = np.hypot(coords[:, 0], coords[:, 1])
    wall_radii = sorted(set(np.round(radii[(radii > geo.r_in - TOL) & (radii < geo.r_out + TOL)], 6)))
    ds = []
    for radius in wall_radii:
        xr, dr = joint_deformation(coords, conn_top, conn_joint, u, radius, sigma_n, geo=geo)
        ds.append((xr / radius, dr))
    d_mean = np.mean([dr for _, dr in ds], axis=0)
    x_mid = ds[0][0] * 0.5 * (geo.r_in + geo.r_out)
    variants = {"secant": math.degrees(math.atan(secant)), "wall_mean": _slope_deg(x_mid, d_mean, geo)}
    for take_out, key in (("none", "raw"), ("whole", "whole_jump")):
        variants[key] = _slope_deg(*joint_deformation(coords, conn_top, conn_joint, u, geo.r_out, take_out=take_out,
                                                      geo=geo), geo)
    return _slope_deg(x, d, geo), variants, x, d


def contact_width(coords, conn_joint, traction, xg, r_out=R_OUT):
    """Z (mm, thesis 7.4.3) and the per-line zero positions / kinds; `xg` (nelem*4, 3) are the
    interface's Gauss points on its lower layer, as feps wrote them (/mesh/groups/joint/points)."""
    sn = traction[:, 2]
    state = traction[:, 3]
    theta = np.degrees(np.arctan2(xg[:, 1], xg[:, 0]))
    # line id: the element's inner radius (rounded) and the Gauss point's first index
    r_node = np.round(np.hypot(coords[conn_joint[:, 0] - 1, 0], coords[conn_joint[:, 0] - 1, 1]), 6)
    line_of = [(float(r_node[p // 4]), (p % 4) % 2) for p in range(len(xg))]
    lines = sorted(set(line_of))
    zeros = []
    for key in lines:
        idx = np.array([p for p in range(len(xg)) if line_of[p] == key])
        idx = idx[np.argsort(theta[idx])]             # from x = +r (theta 0) towards x = -r
        x, s, st = xg[idx, 0], sn[idx], state[idx]
        nonneg = np.nonzero(s >= 0.0)[0]
        if len(nonneg) == 0:
            a, b = _lsq_line(x, s)
            zeros.append((-a / b, "extrapolated (no gap)"))
            continue
        k = nonneg[0]
        if k == 0:
            zeros.append((x[0], "open at the edge"))
            continue
        if st[k] >= 2 and k >= 2:
            # the next point is open (sigma_n = 0 exactly): extend the last two compressive points
            x1, x2, s1, s2 = x[k - 2], x[k - 1], s[k - 2], s[k - 1]
            xz = x2 - s2 * (x2 - x1) / (s2 - s1) if s2 != s1 else x2
            xz = min(max(xz, x[k]), x[k - 1])
            zeros.append((xz, "gap front (extrapolated, clipped)"))
        else:
            xz = x[k - 1] + s[k - 1] / (s[k - 1] - s[k]) * (x[k] - x[k - 1])
            zeros.append((xz, "gap front (interpolated)"))
    z_lines = [r_out - xz for xz, _ in zeros]
    return float(np.mean(z_lines)), lines, zeros


def contact_width_centres(coords, conn_joint, traction, r_out=R_OUT):
    """Variant of Z from element-centre stresses (the mean of each interface element's 4 Gauss
    points, the stresses the thesis reads sigma_max from): on each ring of elements across the
    wall, linear interpolation of sigma_n to zero between the last compressive element centre
    and the next one (the least-squares line through all centres when none is non-compressive),
    averaged over the rings. Where the next element is wholly open this puts the front at that
    element's centre, up to half an element beyond the Gauss-point front."""
    sn = traction[:, 2].reshape(-1, 4).mean(axis=1)
    centres = np.array([coords[elem[:4] - 1].mean(axis=0) for elem in conn_joint])
    rings = np.round(np.hypot(coords[conn_joint[:, 0] - 1, 0], coords[conn_joint[:, 0] - 1, 1]), 6)
    widths = []
    for ring in sorted(set(rings)):
        idx = np.nonzero(rings == ring)[0]
        idx = idx[np.argsort(np.arctan2(centres[idx, 1], centres[idx, 0]))]
        x, s = centres[idx, 0], sn[idx]
        nonneg = np.nonzero(s >= 0.0)[0]
        if len(nonneg) == 0:
            a, b = _lsq_line(x, s)
            widths.append(r_out + a / b)
            continue
        k = nonneg[0]
        xz = x[k - 1] + s[k - 1] / (s[k - 1] - s[k]) * (x[k] - x[k - 1]) if k > 0 else x[0]
        widths.append(r_out - xz)
    return float(np.mean(widths))


def _edge_line(coords, conn, nodes, values, r_out=R_OUT):
    """Least-squares line in x through (element centre x, value) of the elements whose corner
    nodes all lie at theta <= 6 deg, evaluated at x = 715 and returned as a positive compression
    (values are stresses, compression negative); with the number of elements used."""
    xs, ss = [], []
    for e, elem in enumerate(conn - 1):
        p = coords[elem[:nodes]]
        if np.degrees(np.arctan2(p[:, 1], p[:, 0])).max() <= EDGE_THETA + 1e-6:
            xs.append(p[:, 0].mean())
            ss.append(values[e])
    a, b = _lsq_line(xs, ss)
    return float(-(a + b * r_out)), len(xs)


def edge_stress(coords, conn_joint, traction, r_out=R_OUT):
    """sigma_max (MPa, compression positive) at x = 715 from the interface's normal stress: the
    element-centre values (mean of each quad's 4 Gauss points) of the elements with theta < 6 deg."""
    return _edge_line(coords, conn_joint, 4, traction[:, 2].reshape(-1, 4).mean(axis=1), r_out)


def edge_stress_packing(coords, conn_packing, cell_stress, r_out=R_OUT):
    """sigma_max (MPa, compression positive) at x = 715 from the centre stresses szz (element
    averages of the Gauss points, /steps/N/cell/stress/packing) of the packing elements with
    theta < 6 deg: least-squares line in the element centres' x, evaluated at x = 715."""
    return _edge_line(coords, conn_packing, 8, cell_stress[:, 2], r_out)


def _quantities(coords, conn_top, conn_joint, u, traction, conn_packing, packing_cells, xg, sigma_n, geo):
    bstar, delta, delta_b, bstar_x0, _ = beta_star(coords, conn_top, u, geo)
    bbar, variants, _, _ = beta_bar(coords, conn_top, conn_joint, u, sigma_n, geo)
    z, _, zeros = contact_width(coords, conn_joint, traction, xg, geo.r_out)
    z_centres = contact_width_centres(coords, conn_joint, traction, geo.r_out)
    smax_interface, _ = edge_stress(coords, conn_joint, traction, geo.r_out)
    smax, nedge = edge_stress_packing(coords, conn_packing, packing_cells, geo.r_out)
    return {"beta_star": bstar, "beta_bar": bbar, "Z": z, "sigma_max": smax, "delta": delta, "delta_b": delta_b,
            "sigma_max_interface": smax_interface, "beta_star_x0": bstar_x0,
            **{"beta_bar_" + k: v for k, v in variants.items()},
            "rotation_AA": section_rotation(coords, conn_top, u, geo.z_section_aa), "Z_centres": z_centres,
            "Z_lines": [geo.r_out - xz for xz, _ in zeros],
            "Z_kinds": [k for _, k in zeros], "n_edge_elements": nedge,
            "open_fraction": float(np.mean(traction[:, 3] >= 2)),
            "sliding_fraction": float(np.mean(traction[:, 3] == 1))}


MODEL_C_GROUPS = ("top_pipe", "bottom_pipe", "packing", "joint")


def open_model_c(h5path):
    """The HDF5 file of a model C run, open for reading; Error (one line) when it is missing (status
    2), not HDF5 or not model C's (no groups top_pipe, bottom_pipe, packing, joint or no steps)."""
    if not os.path.isfile(h5path):
        raise Error(f"no result file {h5path}", 2)
    try:
        f = h5py.File(h5path, "r")
    except OSError as exc:
        raise Error(f"{h5path}: not an HDF5 file ({exc})") from None
    groups = list(f["mesh/groups"]) if "mesh/groups" in f else []
    missing = [g for g in MODEL_C_GROUPS if g not in groups]
    if missing or not len(f.get("steps", ())):
        f.close()
        what = f"no group {', '.join(missing)}; it has {', '.join(groups) or 'none'}" if missing else "no /steps"
        raise Error(f"{h5path}: not a model C result of scripts/make_model_c.py's decks ({what})")
    return f


def postprocess(h5path, verbose=True):
    """Compute beta*, beta_bar, Z and sigma_max of a model C result at its last step (the end of
    the equilibrium stage s3) and, as 's2_*' entries, at the end of stage 2 (load factor 2) when
    that is a different step; print one line per quantity; return a dict."""
    with open_model_c(h5path) as f:
        coords = f["mesh/coordinates"][...]
        conn_top = f["mesh/groups/top_pipe/connectivity"][...]
        conn_joint = f["mesh/groups/joint/connectivity"][...]
        conn_packing = f["mesh/groups/packing/connectivity"][...]
        names = fr.steps(f)
        step = f["steps"][names[-1]]
        for path in ("displacement", "interface/joint", "nodal_interface/joint", "cell/stress/packing"):
            if path not in step:
                raise Error(f"{h5path}: no /steps/{names[-1]}/{path} (the quantities are read from the displacements, "
                            "the interface's stresses at its points and nodes and the packing's element stresses: "
                            "make_model_c.py's decks ask for them with FIELDS, all, nodal_interface)")
        xg = fr.gauss_points(f, "joint", step["interface/joint"])
        geo = geometry(f)
        normal = fr.components(step["nodal_interface/joint"]).index("sigma_n")

        def quantities(st):
            return _quantities(coords, conn_top, conn_joint, st["displacement"][...], st["interface/joint"][...],
                               conn_packing, st["cell/stress/packing"][...], xg,
                               st["nodal_interface/joint"][:, normal], geo)
        res = quantities(step)
        res["load_factor"] = float(step.attrs["load_factor"])
        res["residual"] = float(step.attrs["residual"])
        s2 = [n for n in names[:-1] if abs(float(f["steps"][n].attrs["load_factor"]) - 2.0) < 1e-9]
        if s2:
            st2 = f["steps"][s2[-1]]
            q2 = quantities(st2)
            for k in ("beta_star", "beta_bar", "Z", "sigma_max", "beta_bar_raw"):
                res["s2_" + k] = q2[k]
            res["s2_residual"] = float(st2.attrs["residual"])
        summ = f["summary"].attrs
        for k in ("wall_time", "iterations", "cutbacks", "steps"):
            if k in summ:
                res[k] = float(summ[k])
    if verbose:
        print(f"{os.path.basename(h5path)}: last step load factor {res['load_factor']:g}, residual "
              f"{res['residual']:.2e}; interface points open {100 * res['open_fraction']:.1f}%, sliding "
              f"{100 * res['sliding_fraction']:.1f}%")
        print(f"beta_star  {res['beta_star']:.4f} deg   (delta {res['delta']:.4f}, delta_b {res['delta_b']:.4f} mm "
              f"area-weighted over z = {geo.z_top_bottom:g}; with delta_b at x = 0: {res['beta_star_x0']:.4f} deg)")
        print(f"beta_bar   {res['beta_bar']:.4f} deg   (least squares over x >= {geo.x_region:g} on r = {geo.r_out:g} "
              f"of w at A-A less the interface's elastic closure sigma_n / Kn; secant {geo.x_region:g}..{geo.r_out:g}: "
              f"{res['beta_bar_secant']:.4f}; "
              f"wall-averaged: {res['beta_bar_wall_mean']:.4f}; nothing taken out: {res['beta_bar_raw']:.4f}; its "
              f"whole relative displacement taken out: {res['beta_bar_whole_jump']:.4f}; A-A's mean rotation: "
              f"{res['rotation_AA']:.4f})")
        print(f"Z          {res['Z']:.1f} mm   (per Gauss line across the wall: " +
              ", ".join(f"{z:.0f}" for z in res["Z_lines"]) + f"; {res['Z_kinds'][0]}; from element-centre "
              f"stresses: {res['Z_centres']:.1f})")
        print(f"sigma_max  {res['sigma_max']:.2f} MPa  (szz at the centres of the {res['n_edge_elements']} packing "
              f"elements with theta < {EDGE_THETA:g} deg, line in x to x = {geo.r_out:g}; the same from the "
              f"interface's normal stress: {res['sigma_max_interface']:.2f})")
        if "s2_beta_star" in res:
            print(f"end of stage 2 (residual {res['s2_residual']:.2e}): beta_star {res['s2_beta_star']:.4f}, "
                  f"beta_bar {res['s2_beta_bar']:.4f}, Z {res['s2_Z']:.1f}, sigma_max {res['s2_sigma_max']:.2f}")
    return res


# ------------------------------------------------------------------------------------------
# thesis tables
# ------------------------------------------------------------------------------------------

def case_name(G, nu, beta):
    """The deck writer's name of a thesis case (make_model_c.py)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import make_model_c
    return make_model_c.case_name(G, nu, beta)


def thesis_values():
    """case -> dict(beta_star, beta_bar, Z, sigma_max) from Tables 7.3 and 7.4 (same row order)."""
    t3, t4 = benchmark_rows("table7_3.csv"), benchmark_rows("table7_4.csv")
    out = {}
    for a, b in zip(t3, t4):
        assert abs(float(a["beta_bar_deg"]) - float(b["beta_bar_deg"])) < 1e-9
        case = case_name(float(a["G_p_MPa"]), float(a["mu_p"]), float(a["applied_beta_deg"]))
        out[case] = {"beta_star": float(a["beta_star_deg"]), "beta_bar": float(a["beta_bar_deg"]),
                     "Z": float(b["modelC_Z_mm"]), "sigma_max": float(b["modelC_smax_MPa"])}
    return out


def case_h5(results_dir, case):
    return os.path.join(results_dir, case, case + ".h5")


def compare_rows(results_dir, state="final"):
    """Rows (case, quantity, thesis, feps, tolerance, warping) for Tables 7.3 and 7.4 (model C
    columns).

    Tolerances are relative; tolerance None marks a row reported only (beta*). A case whose
    HDF5 file is missing gives feps = None. Case ids read 'table7.3 [C_G300_nu0.1_b0.09]'.
    warping (deg, beta_bar rows only, else None): how much steeper w of section A-A is on
    r = 715, x >= 250 than the section's mean rotation in feps's result (thesis_beta_bar_bound).
    state 'final': the equilibrated end of stage s3 (default); 's2': the end of stage 2, which
    still carries the unbalanced force of the initial-stiffness steps (as the thesis's runs did)."""
    rows = []
    prefix = "" if state == "final" else "s2_"
    for case, ref in thesis_values().items():
        path = case_h5(results_dir, case)
        res = postprocess(path, verbose=False) if os.path.exists(path) else None
        get = (lambda k: None if res.get(prefix + k) is None else float(res[prefix + k])) if res else (lambda k: None)
        warping = res["beta_bar_raw"] - res["rotation_AA"] if res else None
        rows.append((f"table7.3 [{case}]", "beta_bar, computed angle (deg)", ref["beta_bar"], get("beta_bar"), 0.03,
                     warping))
        rows.append((f"table7.3 [{case}]", "beta*, actual applied angle (deg)", ref["beta_star"], get("beta_star"),
                     None, None))
        rows.append((f"table7.4 [{case}]", "Z, diametrical contact width (mm)", ref["Z"], get("Z"), 0.05, None))
        rows.append((f"table7.4 [{case}]", "sigma_max, max joint stress (MPa)", ref["sigma_max"], get("sigma_max"),
                     0.05, None))
    return rows


def result_cases(results_dir):
    """Case folders under results_dir holding <case>/<case>.h5: the thesis's twelve first (in the
    order of its tables), then any other (a parametric campaign) in name order."""
    thesis = list(thesis_values())
    found = [d for d in os.listdir(results_dir) if os.path.exists(case_h5(results_dir, d))] \
        if os.path.isdir(results_dir) else []
    # parametric cases by (psi, E_s, beta, G_p, nu_p); a name make_model_c.py did not write comes last
    key = lambda c: (math.isnan(case_parameters(c)[0]), [case_parameters(c)[i] for i in (4, 3, 2, 0, 1)], c)
    return [c for c in thesis if c in found] + sorted((c for c in found if c not in thesis), key=key)


def peak_tension_pipes(h5path):
    """Max most tensile principal stress (MPa) over the Gauss points of the two concrete pipes at
    the last step (the packing and the interface left out, as in the thesis's contours)."""
    with open_model_c(h5path) as f:
        step = f["steps"][fr.last_step(f)]
        for g in ("top_pipe", "bottom_pipe"):
            if f"principal/{g}" not in step:
                raise Error(f"{h5path}: no principal stresses of {g} in the last step (left out with FIELDS?)")
        return max(float(step["principal"][g][:, 0].max()) for g in ("top_pipe", "bottom_pipe"))


def table(results_dir, csv_out=None):
    """Post-process every case found under results_dir (the thesis's and any other); print the
    thesis beside feps where it has the case; optionally write a CSV."""
    ref = thesis_values()
    out = []
    cases = result_cases(results_dir)
    if not cases:
        raise Error(no_results(results_dir))
    print(f"{'case':<28} {'beta*':>8} {'thesis':>8} {'beta_bar':>8} {'thesis':>8} {'Z':>7} {'thesis':>7} "
          f"{'s_max':>7} {'thesis':>7} {'s1_peak':>8}")
    if all(c in ref for c in cases):          # the thesis's campaign: say which cases are missing
        for case in ref:
            if case not in cases:
                print(f"{case:<28} (no result)")
    for case in cases:
        path = case_h5(results_dir, case)
        r = postprocess(path, verbose=False)
        r["peak_s1_pipes"] = peak_tension_pipes(path)
        r.update(analytical_at_beta_bar(case, r["beta_bar"]))
        out.append((case, r))
        t = ref.get(case, {})
        th = lambda k, width, prec: f"{t[k]:{width}.{prec}f}" if k in t else f"{'-':>{width}}"
        print(f"{case:<28} {r['beta_star']:8.4f} {th('beta_star', 8, 4)} {r['beta_bar']:8.4f} {th('beta_bar', 8, 4)} "
              f"{r['Z']:7.0f} {th('Z', 7, 0)} {r['sigma_max']:7.2f} {th('sigma_max', 7, 2)} {r['peak_s1_pipes']:8.2f}")
    if csv_out:
        keys = ["beta_star", "beta_bar", "Z", "sigma_max", "peak_s1_pipes", "australian_Z", "australian_sigma_max",
                "haslem_Z", "haslem_sigma_max", "sigma_max_interface", "Z_centres",
                "beta_star_x0", "beta_bar_secant", "beta_bar_wall_mean", "beta_bar_raw", "beta_bar_whole_jump",
                "rotation_AA",
                "delta_b", "open_fraction", "sliding_fraction", "residual", "s2_beta_star", "s2_beta_bar", "s2_Z",
                "s2_sigma_max", "s2_residual", "wall_time", "iterations", "cutbacks"]
        with open(csv_out, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["case", "G_p", "nu_p", "beta", "E_s", "psi_joint"] + keys +
                       ["thesis_beta_star", "thesis_beta_bar", "thesis_Z", "thesis_sigma_max"])
            for case, r in out:
                t = ref.get(case)
                w.writerow([case] + [f"{v:g}" for v in case_parameters(case)] +
                           [f"{r[k]:.6g}" if k in r else "" for k in keys] +
                           ([t["beta_star"], t["beta_bar"], t["Z"], t["sigma_max"]] if t else ["", "", "", ""]))
        print(f"wrote {csv_out}")
    return out


def analytical_at_beta_bar(case, beta_bar):
    """The Australian and Haslem joint models (scripts/joint_models.py) at feps's beta_bar, as the
    thesis's Table 7.4 sets them beside model C: a = 15 mm, E_p = 2 G_p (1 + nu_p), q = 10 MPa on
    the annulus, L = 2500, E_c = 40000. Empty for a case name make_model_c.py did not write."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import joint_models
    G, nu = case_parameters(case)[:2]
    if math.isnan(G) or not beta_bar > 0.0:
        return {}
    out = {}
    for model in (joint_models.australian, joint_models.haslem):
        res = model(beta=beta_bar, a=PACKING_A, Ep=joint_models.packing_modulus(G, nu))
        out[f"{res.model}_Z"], out[f"{res.model}_sigma_max"] = res.Z, res.sigma_max
    return out


def case_parameters(case):
    """(G_p, nu_p, beta, E_s, psi_joint) of a case name C_G300_nu0.1_b0.09[_Es1440][_psi0]
    (make_model_c.py)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import make_model_c
    try:
        return make_model_c.parse_case(case)
    except ValueError:
        return (float("nan"),) * 5


E_CONCRETE, NU_CONCRETE, Q_TOP = 40000.0, 0.2, 10.0


def _cowper_kappa():
    """Cowper's shear coefficient of the pipe's tube section (0.528 for r / R = 600 / 715)."""
    m2 = (R_IN / R_OUT) ** 2
    return 6 * (1 + NU_CONCRETE) * (1 + m2) ** 2 / ((7 + 6 * NU_CONCRETE) * (1 + m2) ** 2 +
                                                      (20 + 12 * NU_CONCRETE) * m2)


def thesis_beta_bar_bound(case, warping=0.0):
    """Is a Table 7.3 pair (beta*, beta_bar) consistent with statics, given the thesis's own Z and
    sigma_max?

    The joint's contact resultant sits e off the pipe axis: e = m(Z) / p(Z) for the linear joint
    stress with the thesis's contact width Z (analytical models, eqs. 7.2.4-7.2.13), and, where
    Z >= 2R (full contact, where the thesis's (Z, sigma_max) pairs disagree), the smaller of that
    and e = (sigma_max / q - 1) (R^2 + r^2) / (4 R) from its sigma_max. Moment equilibrium of the
    top pipe (load P = q A on its axis at the top) needs H = P e / L at the top end, so by beam
    theory section A-A's mean rotation is less than the chord angle beta* by the shear angle
    H / (kappa G A) less the bending term P e L / (24 E I). beta_bar is not that mean rotation:
    it is the slope of w on r = 715 over x >= 250 (steeper by `warping`, deg, where the section
    is not plane; beam theory has none, the thesis gives no section data, so a caller passes
    feps's own) less the slope of the interface's elastic closure sigma_n / Kn there (for the
    same linear joint stress, sigma_max / (Kn Z)). So beta* - beta_bar >= shear - bending -
    warping + closure. Returns (e in mm, that lower bound in deg, the thesis's beta* - beta_bar
    in deg)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import joint_models
    t = thesis_values()[case]
    area = math.pi * (R_OUT ** 2 - R_IN ** 2)
    inertia = math.pi / 4.0 * (R_OUT ** 4 - R_IN ** 4)
    p, m = joint_models.load_and_moment_factors(t["Z"], R_OUT, R_IN)
    e = m / p
    if t["Z"] >= 2.0 * R_OUT:
        e = min(e, (t["sigma_max"] / Q_TOP - 1.0) * (R_OUT ** 2 + R_IN ** 2) / (4.0 * R_OUT))
    P = Q_TOP * area
    H = P * e / L_PIPE
    G = E_CONCRETE / (2 * (1 + NU_CONCRETE))
    beam = H / (_cowper_kappa() * G * area) - P * e * L_PIPE / (24.0 * E_CONCRETE * inertia)
    closure = t["sigma_max"] / (KN_INTERFACE * t["Z"])
    return e, math.degrees(beam + closure) - warping, t["beta_star"] - t["beta_bar"]


def top_pipe_statics(h5path):
    """Why beta_bar < beta*: the top pipe is a beam loaded by the eccentric joint reaction.

    The top end carries the pressure q (resultant on the axis) and the imposed x displacement,
    whose reaction H is the only horizontal force on the pipe besides the joint's friction;
    moment equilibrium about the joint gives H L = P e (e: the eccentricity of the joint's
    contact resultant), so H cannot vanish while the joint stress is not uniform. The pipe
    bends under M(s) = H (L - s) and shears by gamma = H / (kappa G A). From the measured H
    (the sum of the top-end reactions, half pipe), Euler-Bernoulli and Timoshenko beam theory
    predict the section rotations along the pipe and beta* - theta(A-A); this returns the
    measured and predicted values (deg) for comparison."""
    with open_model_c(h5path) as f:
        X = f["mesh/coordinates"][...]
        step = f["steps"][fr.last_step(f)]
        u, reac = step["displacement"][...], step["reaction"][...]
        conn_top = f["mesh/groups/top_pipe/connectivity"][...]
    top = np.unique(conn_top - 1)
    theta = lambda z: section_rotation(X, conn_top, u, z)
    end = top[np.abs(X[top, 2] - Z_TOP_END) < TOL]
    H = float(reac[end, 0].sum())                       # half pipe (y >= 0)
    area = 0.5 * math.pi * (R_OUT ** 2 - R_IN ** 2)
    inertia = 0.5 * math.pi / 4.0 * (R_OUT ** 4 - R_IN ** 4)
    kappa = _cowper_kappa()
    G = E_CONCRETE / (2 * (1 + NU_CONCRETE))
    EI, L, s = E_CONCRETE * inertia, L_PIPE, Z_SECTION_AA - Z_TOP_BOTTOM
    rad = math.degrees
    th_b, th_aa, th_t = theta(Z_TOP_BOTTOM), theta(Z_SECTION_AA), theta(Z_TOP_END)
    res = {"H": H, "e": H * L / (Q_TOP * area), "theta_bottom": th_b, "theta_AA": th_aa, "theta_top": th_t,
           "dtheta_AA_fe": th_aa - th_b, "dtheta_AA_beam": rad(H / EI * (L * s - s * s / 2)),
           "dtheta_top_fe": th_t - th_b, "dtheta_top_beam": rad(H * L * L / (2 * EI)),
           "gamma": rad(H / (kappa * G * area)),
           "pred_gap": rad(H / (kappa * G * area)) + rad(H / EI * (L * L / 3 - (L * s - s * s / 2)))}
    bstar = beta_star(X, conn_top, u)[0]
    res["beta_star"] = bstar
    res["gap_fe"] = bstar - th_aa
    return res


def no_results(results_dir):
    """The message for a results folder that is missing or holds no <case>/<case>.h5."""
    if not os.path.isdir(results_dir):
        return f"no model C results in {results_dir}: no such folder"
    return f"no model C results in {results_dir} (it holds no <case>/<case>.h5)"


def statics_table(results_dir):
    """top_pipe_statics for every case found (the thesis's, then any other), one line each."""
    cases = result_cases(results_dir)
    if not cases:
        raise Error(no_results(results_dir))
    print(f"{'case':<22} {'H (kN)':>7} {'e (mm)':>6} {'th(1265)':>8} {'th(A-A)':>8} {'th(3765)':>8} "
          f"{'dth_AA fe/beam':>15} {'dth_top fe/beam':>16} {'gamma':>7} {'b*-th_AA fe/pred':>17}")
    for case in cases:
        path = case_h5(results_dir, case)
        r = top_pipe_statics(path)
        print(f"{case:<22} {r['H'] / 1e3:7.1f} {r['e']:6.0f} {r['theta_bottom']:8.4f} {r['theta_AA']:8.4f} "
              f"{r['theta_top']:8.4f} {r['dtheta_AA_fe']:7.4f}/{r['dtheta_AA_beam']:.4f} "
              f"{r['dtheta_top_fe']:8.4f}/{r['dtheta_top_beam']:.4f} {r['gamma']:7.4f} "
              f"{r['gap_fe']:8.4f}/{r['pred_gap']:.4f}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("h5", nargs="?", help="a model C result file")
    ap.add_argument("--table", metavar="RESULTS_DIR", help="post-process every case under RESULTS_DIR/<case>/")
    ap.add_argument("--csv", help="with --table: write this CSV")
    ap.add_argument("--statics", metavar="RESULTS_DIR",
                    help="the top pipe as a beam: measured section rotations against beam theory")
    args = ap.parse_args(argv)
    if args.statics:
        statics_table(args.statics)
    elif args.table:
        table(args.table, args.csv)
    elif args.h5:
        postprocess(args.h5)
    else:
        ap.error("give a result file or --table RESULTS_DIR")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
