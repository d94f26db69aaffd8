#!/usr/bin/env python3
"""Summarise the runs of the 2D joint model (thesis chapter 3; decks from scripts/make_joint_2d.py)
and check the trends the thesis reports in sections 3.3-3.5.

    python3 scripts/summarise_joint_2d.py [--dir DIR] [--plot PLOTDIR]

Reads DIR/joint2d_<case>.h5 (the decks' OUTPUT names; DIR defaults to the working directory) and
prints, per case, at the last step:
  - s1_conc: the most tensile principal stress in the concrete around the joint (Gauss points of
    groups pipe_low and pipe_up within 50 mm of the packing; column 0 of
    /steps/NNNN/principal/<group>) and where (x, y of the Gauss point); s1_all: the same over the
    whole concrete, with its place when it lies outside the joint zone (the pinned base corner);
  - s1_core: as s1_conc but leaving out 10 mm at each free end (x < 10, x > 140), where the
    corner peak depends on the mesh and on the interface stiffness;
  - ip_conc: s1_conc from the in-plane stresses (sxx, syy, sxy) only: column 0 of principal/ is
    of the full tensor, which in plane strain includes szz = nu (sxx + syy);
  - s1_pack, ip_pack: the same in the packing (in a packing of negative nu under compression szz
    is tensile, so the two differ there); s3_conc: the most compressive principal stress in the
    concrete around the joint;
  - sn_low, sn_up: the most compressive interface normal stress on the lower / upper interface and
    its x; sn_lst: the least compressive normal stress on either (the margin to separation);
  - tau L, tau R: the shear stress at the Gauss points nearest x = 0 and x = 150 of the lower
    interface (tau = traction the packing exerts on the lower pipe, +x; so tau < 0 at x = 0 and
    tau > 0 at x = 150 drag the pipe outwards);
  - slide / open: the interface Gauss points sliding (state 1) / open (state 2, separation), with
    the x range of the open ones (and a note when points were open at an earlier stored step);
  - V: the x reaction of the top nodes (N per mm of depth), the shear that holds delta.
Then it checks the qualitative statements of chapter 3 (the thesis gives figures, no numbers) and
prints which hold. With --plot it draws the lower interface's normal and shear stresses against x
(the thesis's Figs. 3.2/3.3 and 3.6/3.7) and the most tensile principal stress around the joint.
"""
import argparse
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_joint_2d import all_cases, case_name  # noqa: E402
import feps_results as fr  # noqa: E402

CONCRETE = ("pipe_low", "pipe_up")
INTERFACES = ("if_low", "if_up")
PACKING = 15.0      # mm, packing thickness of the decks
JOINT_ZONE = 50.0   # mm: concrete within this distance of the packing counts as "around the joint"
EDGE = 10.0         # mm: s1_core leaves out the concrete this close to the free ends x = 0, 150


def gauss_xy(f, group):
    """Coordinates (npoints x 2) of the Gauss points of a group, in the order feps writes them
    (element-major): /mesh/groups/<group>/points (interfaces: on their lower layer)."""
    return fr.gauss_points(f, group)[:, :2]


def inplane_s1(stress):
    """Most tensile principal stress in the x-y plane from rows sxx syy szz syz sxz sxy."""
    sxx, syy, sxy = stress[:, 0], stress[:, 1], stress[:, 5]
    return 0.5 * (sxx + syy) + np.sqrt((0.5 * (sxx - syy)) ** 2 + sxy ** 2)


def last_step(f):
    return sorted(f["steps"].keys(), key=int)[-1]   # by number: names have 4 or more digits


def summarise(path):
    with h5py.File(path, "r") as f:
        step = f["steps/" + last_step(f)]
        out = {"step": last_step(f)}
        # concrete Gauss points of both pipe pieces: the joint zone (within JOINT_ZONE of the
        # packing, the region of the thesis's Figs. 3.4/3.8) and everywhere (the pinned base
        # corner is a second concentration, of the cantilever's bending, not of the joint)
        xy = np.vstack([gauss_xy(f, g) for g in CONCRETE])
        p = np.vstack([step[f"principal/{g}"][...] for g in CONCRETE])
        ip = np.concatenate([inplane_s1(step[f"stress/{g}"][...]) for g in CONCRETE])
        ymid = 0.5 * (xy[:, 1].min() + xy[:, 1].max())
        zone = np.abs(xy[:, 1] - ymid) <= 0.5 * PACKING + JOINT_ZONE
        iz = np.flatnonzero(zone)
        i = iz[int(np.argmax(p[zone, 0]))]
        out["s1_conc"], out["s1_conc_xy"] = float(p[i, 0]), xy[i]
        out["s1_conc_inplane"] = float(ip[zone].max())
        # away from the free ends' corner zones (x within EDGE of 0 or 150), where the peak
        # depends on the mesh and on the interface stiffness (its boundary layer)
        core = zone & (xy[:, 0] > xy[:, 0].min() + EDGE) & (xy[:, 0] < xy[:, 0].max() - EDGE)
        out["s1_core"] = float(p[core, 0].max())
        j = iz[int(np.argmin(p[zone, 1]))]
        out["s3_conc"], out["s3_conc_xy"] = float(p[j, 1]), xy[j]
        k = int(np.argmax(p[:, 0]))
        out["s1_all"], out["s1_all_xy"] = float(p[k, 0]), xy[k]
        # the peak over all stored steps too (loading is proportional: it should be the last)
        out["s1_conc_any_step"] = max(float(np.vstack([f[f"steps/{k}/principal/{g}"][...] for g in CONCRETE])[zone, 0].max())
                                      for k in f["steps"])
        # in-plane principal stress (the x-y plane; column 0 also weighs szz of plane strain)
        out["s1_pack_inplane"] = float(inplane_s1(step["stress/packing"][...]).max())
        pk = step["principal/packing"][...]
        out["s1_pack"] = float(pk[:, 0].max())
        out["s1_pack_xy"] = gauss_xy(f, "packing")[int(np.argmax(pk[:, 0]))]
        for g in INTERFACES:
            a = step[f"interface/{g}"][...]
            # 2D interface output: tau, sigma_n, state (3 columns)
            tau, sn, state = a[:, 0], a[:, -2], a[:, -1]
            x = gauss_xy(f, g)[:, 0]
            order = np.argsort(x)
            k = int(np.argmin(sn))
            out[g] = {"sn_min": float(sn[k]), "sn_min_x": float(x[k]), "sn_max": float(sn.max()),
                      "tau_left": float(tau[order[0]]), "tau_right": float(tau[order[-1]]),
                      "x_left": float(x[order[0]]), "x_right": float(x[order[-1]]),
                      "tau_absmax": float(np.abs(tau).max()),
                      "n_slide": int(np.sum(state == 1)), "n_open": int(np.sum(state == 2)),
                      "n": len(state),
                      "n_open_any_step": max(int(np.sum(f[f"steps/{k}/interface/{g}"][:, -1] == 2)) for k in f["steps"]),
                      "open_x": (float(x[state == 2].min()), float(x[state == 2].max())) if np.any(state == 2) else None,
                      "profile": (x[order], sn[order], tau[order], state[order])}
        ux = step["displacement"][:, 0]
        r = step["reaction"][...]
        xyz = f["mesh/coordinates"][...]
        top = xyz[:, 1] > xyz[:, 1].max() - 1e-6
        out["shear_force"] = float(r[top, 0].sum())       # N per mm: the force holding delta
        out["top_ux"] = float(ux[top].mean())
        out["wall"] = float(f["summary"].attrs["wall_time"])
        out["coords"] = {g: gauss_xy(f, g) for g in CONCRETE + ("packing",)}
        out["s1_field"] = {g: step[f"principal/{g}"][:, 0] for g in CONCRETE + ("packing",)}
    return out


def fmt_all(r):
    if r["s1_all"] <= r["s1_conc"] + 1e-9:
        return "(joint)"
    return f"{r['s1_all']:.2f} at ({r['s1_all_xy'][0]:.0f},{r['s1_all_xy'][1]:.0f})"


def fmt_open(d):
    if d["n_open"] == 0:
        return "none"
    return f"{d['n_open']}/{d['n']} x={d['open_x'][0]:.0f}..{d['open_x'][1]:.0f}"


def check(label, ok):
    print(f"  [{'yes' if ok else 'NO '}] {label}")
    return ok


def trends(res):
    """The qualitative statements of thesis 3.3-3.5, each tested on the runs present."""
    def s1(name):
        return res[name]["s1_conc"] if name in res else None

    def have(*names):
        return all(n in res for n in names)

    print("\nThesis chapter 3 statements (figures only in the thesis, so trends, not numbers):")
    held = []
    for b in (0.1, 0.3):
        n1, n4, nm = (f"G300_nu0.1_b{b:g}", f"G300_nu0.4_b{b:g}", f"G300_nu-0.3_b{b:g}")
        if have(n1, n4, nm):
            held.append(check(f"beta {b:g}: nu_p = 0.4 gives much larger concrete tension than 0.1 "
                              f"({s1(n4):.2f} vs {s1(n1):.2f} MPa)", s1(n4) > 1.5 * s1(n1)))
            held.append(check(f"beta {b:g}: nu_p = -0.3 gives the least concrete tension, 'almost zero' "
                              f"({s1(nm):.2f} MPa; nu 0.1: {s1(n1):.2f})", s1(nm) < s1(n1)))
            held.append(check(f"beta {b:g}: nu_p = -0.3 puts high tension in the packing instead "
                              f"({res[nm]['s1_pack']:.2f} MPa vs concrete {s1(nm):.2f})",
                              res[nm]["s1_pack"] > s1(nm)))
            tl, tr = res[n4]["if_low"]["tau_left"], res[n4]["if_low"]["tau_right"]
            ml, mr = res[nm]["if_low"]["tau_left"], res[nm]["if_low"]["tau_right"]
            held.append(check(f"beta {b:g}: end shear on the lower pipe outwards for nu_p = 0.4 "
                              f"(tau {tl:.1f} at x~0, {tr:.1f} at x~150), inwards for -0.3 ({ml:.1f}, {mr:.1f})",
                              tl < 0 < tr and ml > 0 > mr))
        gs = [f"G{g}_nu0.1_b{b:g}" for g in (300, 600, 900)]
        if have(*gs):
            v = [s1(n) for n in gs]
            sn = [res[n]["if_low"]["sn_min"] for n in gs]
            vc = [res[n]["s1_core"] for n in gs]
            held.append(check(f"beta {b:g}: higher G_p, higher concrete tension (G 300/600/900: "
                              + "/".join(f"{x:.2f}" for x in v) + " MPa)", v[0] < v[1] < v[2]))
            held.append(check(f"beta {b:g}: ... and away from the free ends (s1_core "
                              + "/".join(f"{x:.2f}" for x in vc) + " MPa)", vc[0] < vc[1] < vc[2]))
            held.append(check(f"beta {b:g}: higher G_p, higher peak interface normal stress ("
                              + "/".join(f"{x:.1f}" for x in sn) + " MPa)", sn[0] > sn[1] > sn[2]))
            if have(n1, n4):
                held.append(check(f"beta {b:g}: the G_p effect (900 vs 300: {v[2] - v[0]:+.2f}) is smaller "
                                  f"than the nu_p effect (0.4 vs 0.1: {s1(n4) - s1(n1):+.2f})",
                                  abs(v[2] - v[0]) < abs(s1(n4) - s1(n1))))
        for n in gs[:1] + [n4] if have(gs[0], n4) else []:
            d = res[n]["if_low"]
            held.append(check(f"{n}: peak normal stress on the lower interface at the right end "
                              f"(x = {d['sn_min_x']:.1f}, {d['sn_min']:.1f} MPa)", d["sn_min_x"] > 140.0))
    for gp, nu in ((300, 0.1), (300, 0.4), (300, -0.3), (600, 0.1), (900, 0.1)):
        a, b = f"G{gp}_nu{nu:g}_b0.1", f"G{gp}_nu{nu:g}_b0.3"
        if have(a, b):
            held.append(check(f"G{gp} nu{nu:g}: beta 0.3 gives higher concrete tension than 0.1 "
                              f"({s1(b):.2f} vs {s1(a):.2f} MPa)", s1(b) > s1(a)))
            la = res[a]["if_low"]["sn_min"] / np.mean(res[a]["if_low"]["profile"][1])
            lb = res[b]["if_low"]["sn_min"] / np.mean(res[b]["if_low"]["profile"][1])
            held.append(check(f"G{gp} nu{nu:g}: normal stress more localised at beta 0.3 "
                              f"(peak / mean {lb:.2f} vs {la:.2f})", lb > la))
    for gp, nu in ((300, 0.1), (300, 0.4), (300, -0.3), (600, 0.1), (900, 0.1)):
        a, b = f"G{gp}_nu{nu:g}_b0.1", f"G{gp}_nu{nu:g}_b0.1_stiff"
        if have(a, b):
            # "similar": within 25% or 1.5 MPa (5% of q), and the peak in the same corner (10 mm)
            for key, what in (("s1_conc", "peak"), ("s1_core", "away from the ends")):
                va, vb = res[a][key], res[b][key]
                ok = abs(vb - va) <= max(0.25 * abs(va), 1.5)
                where = ""
                if key == "s1_conc":
                    same = np.hypot(*(res[a]["s1_conc_xy"] - res[b]["s1_conc_xy"])) <= 10.0
                    ok = ok and same
                    where = f", same place: {'yes' if same else 'no'}"
                held.append(check(f"G{gp} nu{nu:g}: Kn, Ks x10 give a similar {what} concrete tension "
                                  f"(within 25% or 1.5 MPa): {va:.2f} -> {vb:.2f} MPa "
                                  f"({100 * (vb - va) / abs(va):+.0f}%){where}", ok))
    print(f"{sum(held)} of {len(held)} statements hold")


def plot(res, outdir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(outdir, exist_ok=True)
    for b in (0.1, 0.3):
        names = [n for n in (f"G300_nu0.1_b{b:g}", f"G600_nu0.1_b{b:g}", f"G900_nu0.1_b{b:g}",
                             f"G300_nu0.4_b{b:g}", f"G300_nu-0.3_b{b:g}") if n in res]
        if not names:
            continue
        fig, ax = plt.subplots(1, 2, figsize=(11, 4))
        for n in names:
            x, sn, tau, _ = res[n]["if_low"]["profile"]
            ax[0].plot(x, sn, label=n)
            ax[1].plot(x, tau, label=n)
        ax[0].set(xlabel="x (mm)", ylabel="sigma_n (MPa)", title=f"lower interface, beta = {b:g} deg (cf. Fig. 3.{2 if b < 0.2 else 6})")
        ax[1].set(xlabel="x (mm)", ylabel="tau (MPa)", title=f"lower interface (cf. Fig. 3.{3 if b < 0.2 else 7})")
        ax[0].legend(fontsize=7)
        for a in ax:
            a.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, f"interface_b{b:g}.png"), dpi=110)
        plt.close(fig)
    for n, r in res.items():
        fig, ax = plt.subplots(figsize=(5, 5))
        xy = np.vstack([r["coords"][g] for g in r["coords"]])
        s1 = np.concatenate([r["s1_field"][g] for g in r["coords"]])
        keep = (xy[:, 1] > 110) & (xy[:, 1] < 205)
        sc = ax.scatter(xy[keep, 0], xy[keep, 1], c=s1[keep], s=4, cmap="jet")
        fig.colorbar(sc, ax=ax, label="most tensile principal stress (MPa)")
        ax.set(xlabel="x (mm)", ylabel="y (mm)", title=n, aspect="equal")
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, f"s1_{n}.png"), dpi=110)
        plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dir", default=".", help="folder holding joint2d_<case>.h5")
    ap.add_argument("--plot", default="", help="folder for PNG plots")
    args = ap.parse_args()
    res = {}
    for c in all_cases():
        name = case_name(*c)
        path = os.path.join(args.dir, f"joint2d_{name}.h5")
        if os.path.exists(path):
            res[name] = summarise(path)
        else:
            print(f"(missing {path})")
    if not res:
        raise SystemExit("no results found")
    print("Stresses in MPa (tension +), at the last step; x, y in mm. sn: most compressive interface normal"
          " stress; tau L/R: lower-interface shear at the Gauss points nearest x = 0 / 150.")
    head = (f"{'case':24s} {'s1_conc':>7s} {'at (x, y)':>13s} {'ip_conc':>7s} {'s1_core':>7s} {'s1_pack':>7s} {'ip_pack':>7s} {'s3_conc':>8s} "
            f"{'sn_low':>7s} {'at x':>6s} {'sn_up':>7s} {'sn_lst':>6s} {'tau L':>6s} {'tau R':>6s} "
            f"{'slide':>7s} {'open low':>14s} {'open up':>14s} {'V N/mm':>8s} {'wall s':>6s}  s1_all")
    print(head)
    print("-" * len(head))
    for name, r in res.items():
        lo, up = r["if_low"], r["if_up"]
        xy = r["s1_conc_xy"]
        print(f"{name:24s} {r['s1_conc']:7.2f} ({xy[0]:5.1f},{xy[1]:5.1f}) {r['s1_conc_inplane']:7.2f} {r['s1_core']:7.2f} "
              f"{r['s1_pack']:7.2f} {r['s1_pack_inplane']:7.2f} {r['s3_conc']:8.2f} "
              f"{lo['sn_min']:7.1f} {lo['sn_min_x']:6.1f} {up['sn_min']:7.1f} {max(lo['sn_max'], up['sn_max']):6.1f} "
              f"{lo['tau_left']:6.1f} {lo['tau_right']:6.1f} "
              f"{lo['n_slide'] + up['n_slide']:3d}/{lo['n'] + up['n']:3d} {fmt_open(lo):>14s} {fmt_open(up):>14s} "
              f"{r['shear_force']:8.1f} {r['wall']:6.1f}  {fmt_all(r)}")
        for g in INTERFACES:
            if r[g]["n_open_any_step"] > r[g]["n_open"]:
                print(f"{'':24s} ({g}: {r[g]['n_open_any_step']} points open at an earlier stored step)")
        if r["s1_conc_any_step"] > r["s1_conc"] + 1e-9:
            print(f"{'':24s} (peak over stored steps {r['s1_conc_any_step']:.2f} MPa, above the last step's)")
    trends(res)
    if args.plot:
        plot(res, args.plot)
        print(f"plots in {args.plot}")


if __name__ == "__main__":
    main()
