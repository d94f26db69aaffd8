#!/usr/bin/env python3
"""Normalised interface normal and shear stress maps (thesis Figures 5.9, 5.10, 5.12, 5.13 and
6.4, 6.5, 6.8, 6.9, 6.11, 6.12, 6.15, 6.16) from /steps/NNNN/interface/<group>.

    python3 scripts/plot_interface_maps.py --h5 FE1.h5 --group contact --norm 4.21 \\
        --out results/figures/FE1_interface.png

Points: the interface integration points, placed on the element's lower layer (its first half of
nodes) by the rule feps uses (interface-quad4: 2x2 Gauss, the first natural direction fastest;
see feps_results.py for the others). The surface is unfolded about the global z axis:
(theta, z) for a cylinder surface (normal mostly radial) or (theta, r) for a joint face z = const
(normal mostly axial); --unfold picks one, default auto. Drawn: sigma_n / q (tension positive,
compression negative) and the shear tau / q, tau = sqrt(tau1^2 + tau2^2) (--shear magnitude,
default) or one component tau1 / tau2 of the local frame (e1 = dx/ds1 of the element). A third
panel (--state) shows where points stick, slide or are open.

--source nodes draws the tractions averaged at the lower layer's nodes instead
(/steps/NNNN/nodal_interface/<group>, written when the deck's FIELDS names nodal_interface):
they reach the edges of the interface, where the Gauss points stop short; the state panel keeps
the points' states.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402
from feps_cli import Error, guard, positive, positive_int  # noqa: E402
from plot_stress_maps import mark_peak, norm_of, step_arg, step_label  # noqa: E402

STATE_NAMES = ["stuck", "sliding", "open"]
INTERFACE_3D = lambda f, group: fr.family(f, group) == "interface" and fr.group_attr(f, group, "dimension") == 3  # noqa: E731


def interface_points(f, group, step):
    """(x (n, 3), data (n, 4): tau1 tau2 sigma_n state) of an interface group at a step."""
    ds = f[f"steps/{step}/interface/{group}"]
    if not INTERFACE_3D(f, group):
        raise ValueError(f"group {group} is '{fr.element_type(f, group)}', not a 3D interface group")
    return fr.gauss_points(f, group, ds), ds[...]


def surface_kind(f, group):
    """'cylinder' when the interface normals are mostly radial, 'face' when mostly axial."""
    conn = fr.connectivity(f, group)
    x = fr.coordinates(f)
    half = conn.shape[1] // 2
    lower = x[conn[:, :half]]
    # corners 1, 2, 3 of the lower layer span the element (quad and tri alike)
    n = np.cross(lower[:, 1] - lower[:, 0], lower[:, 2] - lower[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    return "face" if np.mean(np.abs(n[:, 2])) > 0.5 else "cylinder"


def unfolded(x, kind):
    """(theta deg, vertical coordinate, its label, scale of 1 deg in mm) for a cylinder or a face."""
    r, theta, z = fr.cylindrical(x)
    if kind == "cylinder":
        radius = float(np.median(r))
        return theta, z, "z (mm)", np.pi / 180.0 * radius
    return theta, r, "r (mm)", None


def contour_panel(fig, ax, theta, v, values, scale, ylabel, title, cmap, levels, use_max):
    import matplotlib.tri as mtri
    import matplotlib.pyplot as plt
    # triangulate in true proportions: arc length for a cylinder, (theta * mean r, r) on a face
    s = scale if scale is not None else np.pi / 180.0 * float(np.mean(v))
    tri = mtri.Triangulation(theta, v, triangles=mtri.Triangulation(theta * s, v).triangles)
    vmin, vmax = float(values.min()), float(values.max())
    if vmax - vmin < 1e-9:
        vmin, vmax = vmin - 0.05, vmax + 0.05
    edges = np.linspace(vmin, vmax, levels + 1)
    # widen the outer levels a little: a plateau exactly at the extreme (sigma_n = 0 where the joint
    # is open) would otherwise be left blank
    edges[0] -= 1e-6 * (vmax - vmin)
    edges[-1] += 1e-6 * (vmax - vmin)
    cs = ax.tricontourf(tri, values, levels=edges, cmap=plt.get_cmap(cmap))
    cb = fig.colorbar(cs, ax=ax, shrink=0.85, format="%.2f", ticks=np.linspace(vmin, vmax, 7))
    cb.set_label(title)
    i = mark_peak(ax, theta, v, values, use_max)
    ax.set_title(f"{title}: peak {values[i]:.3f}\nat theta = {theta[i]:.0f} deg, {ylabel.split()[0]} = {v[i]:.0f} mm",
                 fontsize=9)
    ax.set_xlim(theta.min(), theta.max())
    ax.set_ylim(v.min(), v.max())
    if scale is not None:
        ax.set_aspect(1.0 / scale)
    ax.set_xlabel(r"$\theta$ (deg)")
    ax.set_ylabel(ylabel)
    return i


def state_panel(fig, ax, theta, v, state, ylabel, scale):
    """Regions of stuck, sliding and open points (boundaries half-way between points)."""
    import matplotlib.tri as mtri
    from matplotlib.colors import ListedColormap
    s = scale if scale is not None else np.pi / 180.0 * float(np.mean(v))
    tri = mtri.Triangulation(theta, v, triangles=mtri.Triangulation(theta * s, v).triangles)
    colours = ListedColormap(["#9ecae1", "#fd8d3c", "#d62728"])
    cs = ax.tricontourf(tri, state.astype(float), levels=[-0.5, 0.5, 1.5, 2.5], cmap=colours)
    cb = fig.colorbar(cs, ax=ax, shrink=0.85, ticks=[0, 1, 2])
    cb.ax.set_yticklabels(STATE_NAMES)
    counts = [int(np.sum(state == k)) for k in range(3)]
    ax.set_title("state (points): " + ", ".join(f"{c} {n}" for n, c in zip(STATE_NAMES, counts)), fontsize=9)
    ax.set_xlim(theta.min(), theta.max())
    ax.set_ylim(v.min(), v.max())
    if scale is not None:
        ax.set_aspect(1.0 / scale)
    ax.set_xlabel(r"$\theta$ (deg)")
    ax.set_ylabel(ylabel)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--h5", required=True, help="feps result file")
    ap.add_argument("--group", default="contact", help="interface group (default contact)")
    ap.add_argument("--norm", type=positive,
                    help="mean pressure q (MPa) (default: 4.21 for a model B result, 10 for model C; "
                         "required for others)")
    ap.add_argument("--step", type=step_arg, help="step number (default the last stored)")
    ap.add_argument("--unfold", choices=["auto", "cylinder", "face"], default="auto")
    ap.add_argument("--shear", choices=["magnitude", "tau1", "tau2"], default="magnitude")
    ap.add_argument("--state", action="store_true", help="add a panel with the contact state")
    ap.add_argument("--source", choices=["gauss", "nodes"], default="gauss",
                    help="tractions at the integration points (default) or averaged at the nodes "
                         "(the nodal_interface field)")
    ap.add_argument("--levels", type=positive_int, default=12)
    ap.add_argument("--title", help="figure title (default: case, group, step)")
    ap.add_argument("--dpi", type=positive_int, default=110)
    ap.add_argument("--out", required=True, help="PNG file")
    args = ap.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    try:
        with fr.open_result(args.h5) as f:
            args.norm = norm_of(f, args.norm)
            step = fr.pick_step(f, args.step)
            fr.require_group(f, args.group, INTERFACE_3D,
                             "3D interface group")
            fr.require(f, f"steps/{step}/interface/{args.group}", " (left out of the run's FIELDS?)")
            x, data = interface_points(f, args.group, step)
            x_state, state = x, np.rint(data[:, 3]).astype(int)
            if args.source == "nodes":
                fr.require(f, f"steps/{step}/nodal_interface/{args.group}",
                           " (written only when the deck's FIELDS names nodal_interface)")
                conn = fr.connectivity(f, args.group)
                lower = np.unique(conn[:, :conn.shape[1] // 2])
                x, data = fr.coordinates(f)[lower], f[f"steps/{step}/nodal_interface/{args.group}"][...][lower]
            kind = surface_kind(f, args.group) if args.unfold == "auto" else args.unfold
            case = fr.case_name(f)
            title = args.title or f"{case}: interface {args.group} / q (q = {args.norm:g} MPa), {step_label(f, step)}"
    except ValueError as exc:
        raise Error(str(exc), 2) from None
    theta, v, ylabel, scale = unfolded(x, kind)
    sigma_n = data[:, 2] / args.norm
    if args.shear == "magnitude":
        shear, shear_name = np.hypot(data[:, 0], data[:, 1]) / args.norm, r"$\tau / q$"
    else:
        k = 0 if args.shear == "tau1" else 1
        shear, shear_name = data[:, k] / args.norm, rf"$\tau_{k + 1} / q$"
    npanel = 3 if args.state else 2
    fig, axes = plt.subplots(1, npanel, figsize=(4.4 * npanel, 5.4), layout="constrained")
    i_n = contour_panel(fig, axes[0], theta, v, sigma_n, scale, ylabel, r"$\sigma_n / q$", "turbo_r",
                        args.levels, use_max=False)
    i_s = contour_panel(fig, axes[1], theta, v, shear, scale, ylabel, shear_name, "turbo", args.levels,
                        use_max=args.shear == "magnitude" or shear.max() >= -shear.min())
    if args.state:
        theta_s, v_s, _, _ = unfolded(x_state, kind)
        state_panel(fig, axes[2], theta_s, v_s, state, ylabel, scale)
    fig.suptitle(title, fontsize=10)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=args.dpi)
    plt.close(fig)
    where = "nodes" if args.source == "nodes" else "points"
    print(f"{case} interface {args.group} ({kind}, {len(sigma_n)} {where}): sigma_n/q min {sigma_n.min():.4f} "
          f"at theta={theta[i_n]:.1f}, {ylabel.split()[0]}={v[i_n]:.1f}; shear/q peak {shear[i_s]:.4f} "
          f"at theta={theta[i_s]:.1f}, {ylabel.split()[0]}={v[i_s]:.1f} -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
