#!/usr/bin/env python3
"""How much prestress: chapter 9's band swept over its pressure q, for both ways to build it.

    python3 scripts/study_prestress.py [--q 0 1 2 3 4 5 6] [--bands pressure pretensioned [posttensioned]]
                                       [--name prestress] [--steps 400] [--plots-only]

Thesis 9.3 and 10 conclude that "the magnitude of the prestress should be well controlled": its
q = 5 MPa band (PR1) relieves the internal surface but "worsens the tensile stresses on the
external surface" below the band, while q = 1 MPa (PR2) does not. The thesis ran two values of
q; this sweeps q and shows where the external surface gets worse than the plain pipe CR.

For every q and band model it writes a chapter 9 PR deck (scripts/make_chapter9.py: `pressure`,
the thesis's post-tensioned band, q on the plain pipe and the band born afterwards;
`pretensioned`, the band's bars prestressed to the hoop force q R b and bonded, PRESTRESS;
`posttensioned` on request, the thesis's model with the band's own force, PRESTRESS ...,
BOND=after), plus CR, and runs them with scripts/campaign.sh NAME (parallel, resumable: results/NAME/<case>/).
Then, from each case's last step (scripts/orderings_model_a_ch9.py's measures): the largest
most-tensile principal stress s1 in the concrete, its largest value in the external Gauss layer,
and the volume with s1 >= 0.8 ft, the thesis's "high tension domain". It writes
results/NAME/prestress.csv, results/NAME/prestress.md (a table) and results/NAME/prestress.png.
Exit status 1 when a case did not finish (campaign.sh names it; nothing is written), 2 for bad
arguments or when feps --check rejects a deck (nothing is run).
"""
import argparse
import csv
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

import make_chapter9  # noqa: E402
from feps_cli import Error, finite, guard  # noqa: E402
from orderings_model_a_ch9 import chapter9_measures  # noqa: E402

COLUMNS = ["case", "band", "q", "band_force_N", "max_s1", "max_s1_external", "high_volume_mm3"]


def stem(band, q):
    return f"PR_{band}_q{q:g}"


def write_decks(folder, qs, bands, steps):
    os.makedirs(folder, exist_ok=True)
    paths = []
    path = os.path.join(folder, "CR.dat")
    with open(path, "w") as f:
        f.write(make_chapter9.deck("CR", steps))
    paths.append(path)
    for band in bands:
        for q in qs:
            path = os.path.join(folder, stem(band, q) + ".dat")
            with open(path, "w") as f:
                f.write(make_chapter9.deck("PR1", steps, band=band, q=q))
            paths.append(path)
    return paths


def band_force(q):
    """The band's hoop force T = q R b (N) that presses its width with q."""
    return q * make_chapter9.BAND_R * make_chapter9.BAND_WIDTH


def gather(campaign, qs, bands):
    rows = []
    cases = [("CR", "none", 0.0)] + [(stem(b, q), b, q) for b in bands for q in qs]
    for case, band, q in cases:
        h5 = os.path.join(campaign, case, case + ".h5")
        if not os.path.exists(h5):
            raise Error(f"{h5} is missing: the case did not finish (see {os.path.join(campaign, case, 'log.txt')})")
        m = chapter9_measures(h5)
        rows.append({"case": case, "band": band, "q": f"{q:g}",
                     "band_force_N": f"{band_force(q):g}" if band != "none" else "0",
                     "max_s1": f"{m['max']:.4f}", "max_s1_external": f"{m['max_external']:.4f}",
                     "high_volume_mm3": f"{m['high_volume']:.0f}"})
    return rows


def write_outputs(campaign, rows):
    with open(os.path.join(campaign, "prestress.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    lines = ["| band | q (MPa) | hoop force q R b (N) | max s1 (MPa) | max s1, external layer (MPa) | "
             "V(s1 >= 0.8 ft) (mm3) |", "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        lines.append(f"| {r['band']} | {r['q']} | {r['band_force_N']} | {r['max_s1']} | "
                     f"{r['max_s1_external']} | {r['high_volume_mm3']} |")
    with open(os.path.join(campaign, "prestress.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cr = next(r for r in rows if r["case"] == "CR")
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key, label in ((axes[0], "max_s1_external", "max s1 in the external layer (MPa)"),
                           (axes[1], "high_volume_mm3", "volume with s1 >= 0.8 ft (mm$^3$)")):
        for band, marker in (("pressure", "o"), ("pretensioned", "s"), ("posttensioned", "^")):
            pts = sorted((float(r["q"]), float(r[key])) for r in rows if r["band"] == band)
            if pts:
                ax.plot(*zip(*pts), marker=marker, label=f"band: {band}")
        ax.axhline(float(cr[key]), color="k", ls="--", lw=1, label="CR (no band)")
        ax.set_xlabel("band pressure q (MPa)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Chapter 9: prestressing band against its pressure q (thesis: PR2 q = 1, PR1 q = 5)")
    fig.tight_layout()
    out = os.path.join(campaign, "prestress.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--q", type=finite, nargs="+", default=[0, 1, 2, 3, 4, 5, 6],
                    help="band pressures q (MPa), each >= 0")
    ap.add_argument("--bands", nargs="+", choices=["pressure", "pretensioned", "posttensioned"],
                    default=["pressure", "pretensioned"])
    ap.add_argument("--name", default="prestress", help="campaign name: results/NAME")
    ap.add_argument("--steps", type=int, default=400, help="steps of the loading stage (thesis: 400)")
    ap.add_argument("--plots-only", action="store_true", help="only gather the finished cases")
    args = ap.parse_args()
    if any(q < 0 for q in args.q):
        ap.error("--q: a band pressure is >= 0")
    if args.steps < 1:
        ap.error(f"--steps {args.steps}: at least one step is needed")
    campaign = os.path.join(ROOT, "results", args.name)
    status = 0
    if not args.plots_only:
        decks = write_decks(os.path.join(campaign, "decks"), args.q, args.bands, args.steps)
        # campaign.sh: 0 all finished, 1 a case did not (named; gather() then says which is
        # missing), 2 bad arguments or a deck feps --check rejects (its errors printed, nothing run)
        status = subprocess.run(["bash", os.path.join(HERE, "campaign.sh"), args.name] + decks).returncode
        if status not in (0, 1):
            raise Error(f"campaign.sh {args.name} stopped with exit status {status}; nothing was run", status)
    write_outputs(campaign, gather(campaign, args.q, args.bands))
    if status:
        raise Error(f"campaign.sh {args.name} exited with status {status}", 1)
    return 0


if __name__ == "__main__":
    sys.exit(guard(main))
