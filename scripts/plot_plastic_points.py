#!/usr/bin/env python3
"""Where the soil and the concrete yield: the Gauss points of a step by their state, on the
unfolded pipe (theta across, z up) and on cross-sections z = const, as PLAXIS shows its
"plastic points".

    python3 scripts/plot_plastic_points.py --h5 RESULT.h5 --out points.png
            [--step N] [--groups soil,pipe] [--band R0:R1] [--z Z1,Z2] [--dz MM]

The states are feps's own, written when the run's FIELDS (or --fields) name point_state
(`feps DECK --fields all,point_state`): a solid's point is elastic (0), yielding on the yield
surface (1) or at the tension cut-off (3: the Matsuoka-Nakai tension zone or apex). An
interface group's points are shown too, from its traction dataset's state column: sticking (0),
sliding (1) or open (2).

--groups: the groups to show (default: every group with states). --band R0:R1: the radial range
(about the z axis) of the points drawn on the unfolded surface (default, when there is a group
named pipe: from its bore to one wall thickness outside it, the wall and the ground next to it;
else every point). --z: the cross-sections (default: the layer
of Gauss points with the most yielding points), each showing the points within --dz of it
(default: half the smallest spacing of the point layers in z). Prints, for each group, how
many points are in each state (the numbers the picture shows), and writes the PNG.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import feps_results as fr  # noqa: E402
from feps_cli import Error, guard, positive, positive_int  # noqa: E402

# (family, state): label, colour, marker size
STATES = {("solid", 0): ("elastic", "#c8c8c8", 2), ("solid", 1): ("yielding", "#d62728", 9),
          ("solid", 3): ("tension cut-off", "#1f77b4", 9), ("interface", 0): ("interface sticking", "#e0e0e0", 2),
          ("interface", 1): ("interface sliding", "#ff7f0e", 9), ("interface", 2): ("interface open", "#9467bd", 9)}


def band_arg(text):
    try:
        r0, r1 = (float(v) for v in text.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"R0:R1, not {text!r}") from None
    if not 0.0 <= r0 < r1:
        raise argparse.ArgumentTypeError(f"need 0 <= R0 < R1, not {text!r}")
    return r0, r1


def z_list(text):
    try:
        return [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"z values separated by commas, not {text!r}") from None


def group_states(f, step, group):
    """(family, Gauss-point coordinates (n, 3), states (n,)) of a group at a step, or None when
    the step holds no states for it."""
    family = fr.family(f, group)
    if family == "solid":
        path = f"steps/{step}/point_state/{group}"
        if path not in f:
            return None
        ds = f[path]
        return family, fr.gauss_points(f, group, ds), ds[...][:, 0].astype(int)
    if family == "interface":
        path = f"steps/{step}/interface/{group}"
        if path not in f:
            return None
        ds = f[path]
        return family, fr.gauss_points(f, group, ds), ds[...][:, -1].astype(int)
    return None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--h5", required=True, help="feps result file (a run with FIELDS point_state)")
    ap.add_argument("--out", required=True, help="PNG file")
    ap.add_argument("--step", type=int, help="step number (default the last stored)")
    ap.add_argument("--groups", help="groups to show, comma-separated (default: every group with states)")
    ap.add_argument("--band", type=band_arg, help="R0:R1, the radii drawn on the unfolded surface")
    ap.add_argument("--z", type=z_list, help="cross-sections z, comma-separated")
    ap.add_argument("--dz", type=positive, help="half-thickness of a cross-section's slice (mm)")
    ap.add_argument("--dpi", type=positive_int, default=110)
    args = ap.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    try:
        with fr.open_result(args.h5) as f:
            step = fr.pick_step(f, args.step)
            names = args.groups.split(",") if args.groups else fr.groups(f)
            data = {}
            for g in names:
                fr.require_group(f, g)
                got = group_states(f, step, g)
                if got is not None:
                    data[g] = got
                elif args.groups:
                    raise Error(f"step {step} holds no point states of group {g} (run feps with "
                                "--fields all,point_state)", 2)
            if not data:
                raise Error(f"step {step} holds no point states (run feps with --fields all,point_state)", 2)
            band = args.band
            if band is None and "pipe" in fr.groups(f):
                r, _, _ = fr.cylindrical(fr.coordinates(f)[fr.group_nodes(f, "pipe")])
                band = (float(r.min()), float(2.0 * r.max() - r.min()))
            label = f"{fr.case_name(f)}, step {step}"
    except ValueError as exc:
        raise Error(str(exc), 2) from None

    every = np.concatenate([x for _, x, _ in data.values()])
    zs = np.unique(np.round(every[:, 2], 6))
    dz = args.dz or (0.5 * float(np.diff(zs).min()) if len(zs) > 1 else 1.0)
    sections = args.z
    if sections is None:
        plastic = np.concatenate([x[s != 0] for fam, x, s in data.values() if fam == "solid"] + [np.zeros((0, 3))])
        if len(plastic):
            layers, counts = np.unique(np.round(plastic[:, 2], 6), return_counts=True)
            sections = [float(layers[np.argmax(counts)])]
        else:
            sections = [float(np.median(zs))]

    fig, axes = plt.subplots(1, 1 + len(sections), figsize=(5.0 * (1 + len(sections)), 5.6), squeeze=False)
    unfolded, cuts = axes[0][0], axes[0][1:]
    shown = set()
    for g, (family, x, states) in data.items():
        r, theta, z = fr.cylindrical(x)
        on_band = np.ones(len(x), bool) if band is None else (r >= band[0] - 1e-6) & (r <= band[1] + 1e-6)
        counts = {STATES.get((family, s), (f"state {s}",))[0]: int((states == s).sum()) for s in np.unique(states)}
        print(f"{g} ({family}): {len(states)} points: " + ", ".join(f"{n} {k}" for k, n in counts.items()))
        for s in np.unique(states):
            name, colour, size = STATES.get((family, s), (f"state {s}", "k", 9))
            pick = states == s
            lab = name if name not in shown else None
            shown.add(name)
            unfolded.scatter(theta[pick & on_band], z[pick & on_band], s=size, c=colour, label=lab, linewidths=0)
            for ax, zc in zip(cuts, sections):
                sl = pick & (np.abs(x[:, 2] - zc) <= dz)
                ax.scatter(x[sl, 0], x[sl, 1], s=size, c=colour, linewidths=0)
    where = "every point" if band is None else f"r = {band[0]:g} .. {band[1]:g} mm"
    unfolded.set_title(f"{label}: unfolded, {where}", fontsize=9.5)
    unfolded.set_xlabel(r"$\theta$ (deg)")
    unfolded.set_ylabel("z (mm)")
    unfolded.legend(fontsize=8, markerscale=1.5, loc="best")
    for ax, zc in zip(cuts, sections):
        ax.set_title(f"cross-section z = {zc:g} mm (+-{dz:g})", fontsize=9.5)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_aspect("equal", adjustable="datalim")
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=args.dpi)
    plt.close(fig)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
