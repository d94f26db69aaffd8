#!/usr/bin/env python3
"""Axial displacement w along r = R at a pipe end section against x (thesis Figures 7.3-7.6), for one
or more feps results, with the analytical lines of the Australian model and Haslem's flexible pipe
model (scripts/joint_models.py); with --joint-total, model C's total deformation at the joint
(thesis Figures 7.7-7.8).

    python3 scripts/plot_joint_deformation.py --h5 FE1.h5 FE2.h5 FE3.h5 \\
        --labels "typical soil" "soft soil" "stiff soil" --out results/figures/fig7_3.png
    python3 scripts/plot_joint_deformation.py --joint-total --h5 results/modelC/C_G300_nu*_b0.09/*.h5 \\
        --out results/figures/fig7_7.png

Numerical curves: w (uz of the chosen step) of the group's nodes on r = R (default: the group's
largest nodal radius, 715 in model B) at z = Z (default: the group's largest z, the top pipe end),
sorted by x = r cos(theta).

Analytical lines (thesis 7.2-7.3), defaults = thesis Table 7.1 (model B edge load): P = 2000 kN on
the full pipe, contact width Z = 495 mm (load from x = -220 to -715), a = 0 (no packing),
L = 1250 mm (half the pipe: both ends are loaded, the mid-section does not rotate), E_c = 40000 MPa.
- Australian model: the loaded part of the pipe compresses as independent columns, so w is linear in
  the loaded region, zero at its inner boundary (x = -220) and -tan(beta_A) * Z = -sigma_max L / E_c at
  the loaded edge, and zero elsewhere (no stress, no compression).
- Haslem: the pipe bends as a beam, plane sections stay plane: w is linear over the whole end,
  w = tan(beta_H) x. The thesis says only "linearly distributed over the pipe end"; the beam's
  rotation M L / (E_c I_c) is about its neutral axis, the pipe axis x = 0 (no uniform shortening is in
  the model), so the line is drawn through w = 0 at x = 0 (--haslem-pivot moves that point).
The lines' sign is that of the compressed end: w < 0 at the top end (largest z), w > 0 at the bottom.
--edge +1 puts the loaded edge at x = +R (model C's bottom pipe).

--joint-total (model C results of scripts/make_model_c.py's decks, thesis 7.4.2, Figures 7.7-7.8):
the total deformation at the joint along r = 715, D(x) = -(w at the top pipe's mid-length section
A-A, z = 2515, less the interface's elastic closure sigma_n / Kn), compression positive, as
scripts/postprocess_model_c.py computes it for beta_bar. Per file: the curve, the least-squares line
over x >= 250 mm whose slope is beta_bar (dashed), and, unless --no-analytical, the Australian
model's joint closure at that beta_bar, D = tan(beta_bar) (x - (R - Z)) for x > R - Z with its Z
(a = 15 mm, E_p = 2 G_p (1 + nu_p) from the case name, q = 10 MPa; dotted). Haslem's model gives
no closure profile across the joint, so it has no line here. --group, --radius, --z, --edge and the
joint model parameters do not apply.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402
import joint_models as jm  # noqa: E402
from feps_cli import Error, finite, guard, positive, positive_int  # noqa: E402
from plot_stress_maps import SOLID, step_arg  # noqa: E402

TABLE7_1 = dict(P=2.0e6, Z=495.0, a=0.0, L=1250.0, Ec=40000.0, Ep=1.0, R=715.0, r=600.0)


def ring_displacement(f, group, step, radius=None, z=None, tol=None):
    """(x, w, radius, z, top) of the group's nodes on r = radius, z = z, sorted by x; top is True when
    z is the group's largest z (the compressed end moves towards -z)."""
    x = fr.coordinates(f)
    nodes = fr.group_nodes(f, group)
    r, _, zz = fr.cylindrical(x[nodes])
    radius = float(r.max()) if radius is None else radius
    z = float(zz.max()) if z is None else z
    tol = 1e-6 * max(1.0, radius) if tol is None else tol
    on = (np.abs(r - radius) <= tol) & (np.abs(zz - z) <= tol)
    if on.sum() < 2:
        raise ValueError(f"{f.filename}: group {group} has fewer than 2 nodes on r = {radius:g}, z = {z:g}")
    ring = nodes[on]
    u = f[f"steps/{step}/displacement"][...]
    order = np.argsort(x[ring, 0])
    top = abs(z - zz.max()) <= abs(z - zz.min())
    return x[ring[order], 0], u[ring[order], 2], radius, z, top


def slope_angle(x, w, x0, x1):
    """atan of the slope of w between x0 and x1 (w interpolated linearly in x), in degrees: the angle
    REPORT ROTATION gives."""
    return np.degrees(np.arctan((np.interp(x1, x, w) - np.interp(x0, x, w)) / (x1 - x0)))


def analytical_lines(params, edge, top, pivot, npts=400):
    """{label: (x, w)} for the Australian and Haslem models."""
    R, Z = params["R"], params["Z"]
    kw = {k: params[k] for k in ("Z", "P", "a", "L", "Ec", "Ep", "R", "r")}
    aus, has = jm.australian(**kw), jm.haslem(**kw)
    x = np.linspace(-R, R, npts)
    s = edge * x                           # distance towards the loaded edge
    inner = R - Z                          # loaded where s > inner
    sign = -1.0 if top else 1.0            # compression moves the top end down
    w_aus = sign * np.tan(np.radians(aus.beta)) * np.clip(s - inner, 0.0, None)
    w_has = sign * np.tan(np.radians(has.beta)) * (s - edge * pivot)
    return {f"Australian model (beta = {aus.beta:.4f} deg)": (x, w_aus),
            f"Haslem (1996) (beta = {has.beta:.4f} deg)": (x, w_has)}, aus, has


def joint_total(ax, args, markers):
    """Model C: the total deformation at the joint per file (thesis Figures 7.7-7.8) on ax."""
    import postprocess_model_c as pmc
    for k, path in enumerate(args.h5):
        try:
            f = pmc.open_model_c(path)
        except Error as exc:            # a missing or non-model-C file is a bad argument here
            raise Error(str(exc), 2) from None
        with f:
            try:
                step = fr.pick_step(f, args.step)
            except ValueError as exc:
                raise Error(str(exc), 2) from None
            coords = f["mesh/coordinates"][...]
            conn_top = f["mesh/groups/top_pipe/connectivity"][...]
            conn_joint = f["mesh/groups/joint/connectivity"][...]
            for field in ("displacement", "nodal_interface/joint"):
                if f"steps/{step}/{field}" not in f:
                    raise Error(f"{path}: no /steps/{step}/{field} (the total joint deformation is read from "
                                "the displacements and the interface's normal stress at the nodes: make_model_c.py's "
                                "decks ask for them with FIELDS, all, nodal_interface)", 2)
            u = f[f"steps/{step}/displacement"][...]
            nodal = f[f"steps/{step}/nodal_interface/joint"]
            sigma_n = nodal[:, fr.components(nodal).index("sigma_n")]
            case = fr.case_name(f)
        bbar, _, x, d = pmc.beta_bar(coords, conn_top, conn_joint, u, sigma_n)
        label = args.labels[k] if args.labels else case
        line, = ax.plot(x, d, marker=markers[k % len(markers)], ms=3.5, lw=1.4,
                        label=f"{label} (beta_bar = {bbar:.4f} deg)")
        sel = x >= pmc.X_REGION - pmc.TOL
        a, b = pmc._lsq_line(x[sel], d[sel])
        xs = np.array([pmc.X_REGION, pmc.R_OUT])
        ax.plot(xs, a + b * xs, "--", color=line.get_color(), lw=1.0)
        text = (f"{path}: {label}: {len(x)} nodes on r = {pmc.R_OUT:g} at z = {pmc.Z_SECTION_AA:g}; D from "
                f"{d.min():.4f} to {d.max():.4f} mm; beta_bar (x >= {pmc.X_REGION:g}) = {bbar:.5f} deg")
        aus = pmc.analytical_at_beta_bar(case, bbar) if not args.no_analytical else {}
        if aus:
            z_aus = aus["australian_Z"]
            xa = np.linspace(-pmc.R_OUT, pmc.R_OUT, 400)
            da = np.tan(np.radians(bbar)) * np.clip(xa - (pmc.R_OUT - z_aus), 0.0, None)
            ax.plot(xa, da, ":", color=line.get_color(), lw=1.5,
                    label=f"Australian model at beta_bar (Z = {z_aus:.0f} mm)")
            text += f"; Australian Z = {z_aus:.1f} mm"
        print(text)
    ax.axvline(pmc.X_REGION, color="0.6", lw=0.6, ls="-.")
    ax.set_ylabel("total joint deformation D (mm, compression +)")
    ax.set_xlim(-pmc.R_OUT, pmc.R_OUT)
    return (f"Total deformation at the joint along r = {pmc.R_OUT:g} mm "
            f"(section A-A less the interface's elastic closure)")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--h5", nargs="+", required=True, help="feps result files")
    ap.add_argument("--labels", nargs="+", help="legend labels, one per file (default: the case names)")
    ap.add_argument("--group", default="pipe")
    ap.add_argument("--radius", type=positive, help="ring radius R (default: the group's largest radius)")
    ap.add_argument("--z", type=finite, help="section z (default: the group's largest z, the top end)")
    ap.add_argument("--step", type=step_arg, help="step number (default the last stored)")
    ap.add_argument("--no-analytical", action="store_true", help="numerical curves only")
    ap.add_argument("--joint-total", action="store_true",
                    help="model C: total deformation at the joint (thesis Figures 7.7-7.8)")
    ap.add_argument("--edge", type=int, choices=[-1, 1], default=-1, help="loaded edge at x = edge * R (default -1)")
    ap.add_argument("--haslem-pivot", type=finite, default=0.0, help="x where Haslem's line is zero (default 0)")
    for key, value in TABLE7_1.items():
        ap.add_argument(f"--{key}", type=finite, default=value,
                        help=f"joint model parameter {key} (default {value:g}, thesis Table 7.1)")
    ap.add_argument("--title", help="title")
    ap.add_argument("--dpi", type=positive_int, default=110)
    ap.add_argument("--out", required=True, help="PNG file")
    args = ap.parse_args(argv)
    if args.labels and len(args.labels) != len(args.h5):
        ap.error("give one label per --h5 file")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    markers = "osd^v<>p"
    if args.joint_total:
        fig, ax = plt.subplots(figsize=(7.2, 4.8))
        title = joint_total(ax, args, markers)
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set_xlabel("x (mm)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title(args.title or title, fontsize=10)
        return save(fig, plt, args.out, args.dpi)

    params = {k: getattr(args, k) for k in TABLE7_1}
    x0, x1 = args.edge * (params["R"] - params["Z"]), args.edge * params["R"]   # the loaded region
    fig, ax = plt.subplots(figsize=(7.2, 4.8))
    top = True
    for k, path in enumerate(args.h5):
        try:
            with fr.open_result(path) as f:
                step = fr.pick_step(f, args.step)
                fr.require_group(f, args.group, SOLID, "solid group")
                x, w, radius, z, top = ring_displacement(f, args.group, step, args.radius, args.z)
                label = args.labels[k] if args.labels else fr.case_name(f)
                # positive when the loaded edge is compressed (as REPORT ROTATION for the model B top end)
                angle = slope_angle(x, w, x0, x1) * (1.0 if top else -1.0) * -args.edge
        except ValueError as exc:
            raise Error(str(exc), 2) from None
        ax.plot(x, w, marker=markers[k % len(markers)], ms=3.5, lw=1.4,
                label=f"{label} (beta = {angle:.4f} deg)")
        print(f"{path}: {label}: {len(x)} nodes on r = {radius:g}, z = {z:g}; w from {w.min():.4f} to {w.max():.4f} mm; "
              f"deflection angle over x = {x0:g} .. {x1:g}: {angle:.5f} deg")
    if not args.no_analytical:
        try:
            lines, aus, has = analytical_lines(params, args.edge, top, args.haslem_pivot)
        except ValueError as exc:       # the joint models' own checks ("need R > r >= 0, ...")
            raise Error(f"analytical lines: {exc}", 2) from None
        for (label, (xa, wa)), style in zip(lines.items(), ["--", ":"]):
            ax.plot(xa, wa, "k" + style, lw=1.5, label=label)
        print(f"Australian: beta = {aus.beta:.5f} deg, sigma_max = {aus.sigma_max:.3f} MPa; "
              f"Haslem: beta = {has.beta:.5f} deg")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.axvline(x0, color="0.6", lw=0.6, ls="-.")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("w (mm)")
    ax.set_xlim(-params["R"], params["R"])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right" if (top and args.edge < 0) else "best")
    ax.set_title(args.title or f"Axial displacement w along r = {radius:g} mm at the pipe end z = {z:g} mm",
                 fontsize=10)
    return save(fig, plt, args.out, args.dpi)


def save(fig, plt, out, dpi):
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    print(f"-> {out}")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
