#!/usr/bin/env python3
"""Normalised stress map on an unfolded cylinder surface r = const (thesis Figures 5.3-5.19,
6.6-6.17): theta (deg) across, z (mm) up, filled contours of sigma / q.

    python3 scripts/plot_stress_maps.py --h5 SE1.h5 --group pipe --surface inner --field tensile \\
        --norm 4.21 --out results/figures/SE1_tensile_inner.png

--surface inner | outer | r=VALUE: the group's smallest or largest nodal radius (about the global z
axis), or a given radius. Values come from the Gauss points of the elements that reach the
surface, the layer of points nearest to it in each element (--source gauss, default), from the
element averages of those elements at their centroids (--source cell), or at the surface nodes
(--source nodes: feps's nodal_principal field, which a run writes when its FIELDS or --fields
name it, e.g. `feps DECK --fields all,nodal_principal`: the principal values of the Gauss-point
stress tensors extrapolated to the nodes and averaged over the elements sharing each node; it
reaches the pipe ends, and smooths the jumps between elements). Points that coincide in
(theta, z) (an r = VALUE between two element layers) are averaged. The map covers the points'
extent: Gauss points sit inside the elements, so it stops short of the pipe ends by the distance
of the first point from the end (about 0.21 of the end element's length for 2x2x2 Gauss).
The plot is drawn with true proportions (arc length r theta against z).
--field tensile | compressive: the principal stresses (feps's principal / nodal_principal);
hoop | radial | axial: the stresses in the pipe's own frame, feps's stress_cyl (Gauss points)
or nodal_stress_cyl (--source nodes) about the z axis, which a run writes when its FIELDS or
--fields name them (`feps DECK --fields all,stress_cyl,nodal_stress_cyl`): the hoop stress
that cracks a pipe, with no rotation here.
Prints the peak value and where it is.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402
from feps_cli import Error, guard, positive, positive_int  # noqa: E402

SOURCES = {"gauss": "Gauss points", "cell": "element averages", "nodes": "nodal"}
# --field: (Gauss-point dataset, its nodal counterpart, column, name, colour-bar label, peak is the largest)
FIELDS = {"tensile": ("principal", "nodal_principal", 0, "most tensile principal stress", r"$\sigma_1 / q$", True),
          "compressive": ("principal", "nodal_principal", 1, "most compressive principal stress",
                          r"$\sigma_3 / q$", False),
          "radial": ("stress_cyl", "nodal_stress_cyl", 0, "radial stress", r"$\sigma_{rr} / q$", True),
          "hoop": ("stress_cyl", "nodal_stress_cyl", 1, "hoop stress", r"$\sigma_{\theta\theta} / q$", True),
          "axial": ("stress_cyl", "nodal_stress_cyl", 2, "axial stress", r"$\sigma_{zz} / q$", False)}


def surface_arg(text):
    """argparse type of --surface: inner, outer or r=VALUE (VALUE > 0)."""
    if text in ("inner", "outer"):
        return text
    if text.lower().startswith("r="):
        try:
            positive(text[2:])
            return text
        except argparse.ArgumentTypeError:
            pass
    raise argparse.ArgumentTypeError(f"inner, outer or r=VALUE with a radius VALUE > 0, not {text!r}")


def step_arg(text):
    """argparse type of --step: a step number >= 0."""
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text!r} is not a step number")
    return value


SOLID = fr.is_family("solid")


def surface_radius(f, group, surface):
    """Radius of 'inner', 'outer' or 'r=VALUE' for a group."""
    r, _, _ = fr.cylindrical(fr.coordinates(f)[fr.group_nodes(f, group)])
    if surface == "inner":
        return float(r.min())
    if surface == "outer":
        return float(r.max())
    if surface.lower().startswith("r="):
        return float(surface[2:])
    raise ValueError(f"--surface: inner, outer or r=VALUE, not '{surface}'")


def elements_reaching(f, group, radius, tol):
    """Boolean mask of the elements whose nodal radii span `radius` (within tol)."""
    r, _, _ = fr.cylindrical(fr.coordinates(f))
    rn = r[fr.connectivity(f, group)]
    return (rn.min(axis=1) <= radius + tol) & (rn.max(axis=1) >= radius - tol)


def nearest_layer(r_points, radius, ppe):
    """Mask of each element's points in the layer nearest to `radius`: within a quarter of the
    element's spread of distances from the nearest one (2 layers of 2x2x2 Gauss points, 3 of 3x3x3)."""
    d = np.abs(r_points - radius).reshape(-1, ppe)
    dmin = d.min(axis=1, keepdims=True)
    spread = d.max(axis=1, keepdims=True) - dmin
    return (d <= dmin + 0.25 * spread + 1e-9).ravel()


def merge_coincident(theta, z, values, radius):
    """Average the values of points closer than 1e-6 of the radius in (arc length, z)."""
    scale = 1e-6 * radius
    keys = np.round(np.column_stack([np.radians(theta) * radius, z]) / scale).astype(np.int64)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    sums = np.zeros(len(first))
    np.add.at(sums, inverse, values)
    counts = np.bincount(inverse, minlength=len(first))
    return theta[first], z[first], sums / counts


def surface_values(f, group, step, column, radius, source="gauss", tol=None, kind="principal"):
    """(theta deg, z, values) on the surface r = radius from the Gauss-point dataset
    /steps/step/<kind>/<group> (column) or its element averages (source='cell')."""
    tol = 1e-3 * radius if tol is None else tol
    reach = elements_reaching(f, group, radius, tol)
    if not reach.any():
        raise ValueError(f"group {group}: no element reaches r = {radius:g}")
    if source == "nodes":
        theta, z, values = nodal_values(f, group, step, column, radius, tol, "nodal_" + kind)
    elif source == "cell":
        data = f[f"steps/{step}/cell/{kind}/{group}"][:, column]
        conn = fr.connectivity(f, group)[reach]
        xc = fr.coordinates(f)[conn].mean(axis=1)
        _, theta, z = fr.cylindrical(xc)
        values = data[reach]
    else:
        ds = f[f"steps/{step}/{kind}/{group}"]
        ppe = int(ds.attrs["points_per_element"])
        xg = fr.gauss_points(f, group, ds).reshape(-1, ppe, 3)[reach].reshape(-1, 3)
        vals = ds[...][:, column].reshape(-1, ppe)[reach].ravel()
        rg, theta, z = fr.cylindrical(xg)
        keep = nearest_layer(rg, radius, ppe)
        theta, z, values = theta[keep], z[keep], vals[keep]
    return merge_coincident(theta, z, values, radius)


def nodal_values(f, group, step, column, radius, tol, kind="nodal_principal"):
    """(theta, z, value) at the group's nodes on r = radius: feps's nodal field `kind`
    (nodal_principal: the principal values of the Gauss-point stresses extrapolated to the nodes
    and averaged over the group's elements sharing each node; nodal_stress_cyl: those averages in
    the cylindrical frame)."""
    x = fr.coordinates(f)
    r, theta, z = fr.cylindrical(x)
    nodes = fr.group_nodes(f, group)
    nodes = nodes[np.abs(r[nodes] - radius) <= tol]
    if not len(nodes):
        raise ValueError(f"group {group}: no node on r = {radius:g} (--source nodes needs a node layer there)")
    values = f[f"steps/{step}/{kind}/{group}"][...][nodes, column]
    return theta[nodes], z[nodes], values

def unfolded_contour(ax, theta, z, values, radius, levels=12, cmap="turbo", zero_line=False):
    """Filled contours on (theta, z) triangulated in true proportions (arc length, z)."""
    import matplotlib.tri as mtri
    import matplotlib.pyplot as plt
    flat = mtri.Triangulation(np.radians(theta) * radius, z)
    tri = mtri.Triangulation(theta, z, triangles=flat.triangles)
    vmin, vmax = float(values.min()), float(values.max())
    if vmax - vmin < 1e-12 * max(1.0, abs(vmax)):
        vmin, vmax = vmin - 0.5, vmax + 0.5
    lv = np.linspace(vmin, vmax, levels + 1)
    # widen the outer levels a little: a plateau exactly at an extreme (a stress at the tension
    # cap) would otherwise be left blank
    lv[0] -= 1e-6 * (vmax - vmin)
    lv[-1] += 1e-6 * (vmax - vmin)
    cs = ax.tricontourf(tri, values, levels=lv, cmap=plt.get_cmap(cmap))
    if zero_line and vmin < 0.0 < vmax:
        ax.tricontour(tri, values, levels=[0.0], colors="k", linewidths=0.7, linestyles="--")
    ax.set_aspect(180.0 / (np.pi * radius))    # 1 deg of theta drawn as long as r pi / 180 mm of z
    ax.set_xlim(theta.min(), theta.max())
    ax.set_ylim(z.min(), z.max())
    ax.set_xlabel(r"$\theta$ (deg)")
    ax.set_ylabel("z (mm)")
    return cs


def mark_peak(ax, theta, z, values, use_max):
    """Cross at the largest (use_max) or smallest value; returns its index."""
    i = int(np.argmax(values) if use_max else np.argmin(values))
    ax.plot(theta[i], z[i], marker="x", color="k", markersize=9, mew=2, clip_on=False)
    return i


def peak_text(theta, z, values, i):
    return f"peak {values[i]:.2f} at theta = {theta[i]:.0f} deg, z = {z[i]:.0f} mm (x)"


def norm_of(f, norm):
    """--norm if given, else the mean pressure of a thesis model B or C result (feps_results)."""
    if norm is not None:
        return norm
    q, _ = fr.mean_pressure(f)
    if q is None:
        raise ValueError(f"{f.filename}: give --norm q (MPa): the file is no model B or C result "
                         f"(their /summary parameters give q), so its mean pressure is not known")
    return q


def step_label(f, step):
    lf = f[f"steps/{step}"].attrs.get("load_factor")
    return f"step {step}" + (f", load factor {float(lf):.3g}" if lf is not None else "")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--h5", required=True, help="feps result file")
    ap.add_argument("--group", default="pipe", help="solid element group (default pipe)")
    ap.add_argument("--surface", type=surface_arg, default="inner", help="inner, outer or r=VALUE (default inner)")
    ap.add_argument("--field", choices=sorted(FIELDS), default="tensile")
    ap.add_argument("--norm", type=positive,
                    help="mean pressure q (MPa) the stresses are divided by (default: 4.21 for a model B "
                         "result, 10 for model C, known from its /summary parameters; required for others)")
    ap.add_argument("--step", type=step_arg, help="step number (default the last stored)")
    ap.add_argument("--source", choices=["gauss", "cell", "nodes"], default="gauss",
                    help="Gauss points nearest the surface (default), element averages, or nodal values "
                         "(Gauss-point stresses extrapolated to the nodes and averaged)")
    ap.add_argument("--levels", type=positive_int, default=12, help="number of contour bands (default 12)")
    ap.add_argument("--zero-line", action="store_true", help="draw the zero contour (dashed)")
    ap.add_argument("--title", help="title (default: case, field and surface)")
    ap.add_argument("--dpi", type=positive_int, default=110)
    ap.add_argument("--out", required=True, help="PNG file")
    args = ap.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kind, nodal_kind, column, field_name, label, use_max = FIELDS[args.field]
    try:
        with fr.open_result(args.h5) as f:
            args.norm = norm_of(f, args.norm)
            step = fr.pick_step(f, args.step)
            fr.require_group(f, args.group, SOLID, "solid group")
            dataset = {"nodes": nodal_kind, "cell": "cell/" + kind}.get(args.source, kind)
            fr.require(f, f"steps/{step}/{dataset}/{args.group}", " (left out of the run's FIELDS?" +
                       (f" run feps DECK --fields all,{dataset})" if dataset != "principal" else ")"))
            radius = surface_radius(f, args.group, args.surface)
            theta, z, values = surface_values(f, args.group, step, column, radius, args.source, kind=kind)
            values = values / args.norm
            case = fr.case_name(f)
            where = {"inner": "inner surface", "outer": "outer surface"}.get(args.surface, "surface")
            title = args.title or (f"{case}: {field_name} / q (q = {args.norm:g} MPa)\n"
                                   f"{args.group}, {where} r = {radius:g} mm, {step_label(f, step)}, "
                                   f"{SOURCES[args.source]}")
    except ValueError as exc:
        raise Error(str(exc), 2) from None

    fig, ax = plt.subplots(figsize=(6.4, 6.6))
    cs = unfolded_contour(ax, theta, z, values, radius, args.levels,
                          cmap="turbo" if use_max else "turbo_r", zero_line=args.zero_line)
    i = mark_peak(ax, theta, z, values, use_max=use_max)
    ax.set_title(title + "\n" + peak_text(theta, z, values, i), fontsize=9.5)
    cb = fig.colorbar(cs, ax=ax, shrink=0.9, format="%.2f",
                      ticks=np.linspace(float(values.min()), float(values.max()), 7))
    cb.set_label(label)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=args.dpi)
    plt.close(fig)
    print(f"{case} {args.field} {where} r={radius:g}: peak {values[i]:.4f} q = {values[i] * args.norm:.4g} MPa "
          f"at theta={theta[i]:.1f} deg, z={z[i]:.1f} mm ({len(values)} points) -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
