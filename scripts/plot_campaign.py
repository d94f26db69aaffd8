#!/usr/bin/env python3
"""Plot a campaign's trend: one quantity (or several) against one parameter, a line per value of
another, from the CSV a campaign writes (scripts/campaign.sh's summary.csv, whose parameter
columns come from the decks' PARAMETERS records, or scripts/postprocess_model_c.py's table.csv).

    python3 scripts/plot_campaign.py CSV --x PARAM --y QUANTITY [--y QUANTITY ...] [--by PARAM]
                                     [--where PARAM=VALUE ...] [--logx] [--logy] [-o FIGURE.png]
                                     [--title TEXT]

Rows whose status is not "ok" (campaign.sh) are left out and counted; a row without a number
in a column that is plotted is an error naming the row and column, not a silent gap, and so is
a value <= 0 on a logarithmic axis (--logx, --logy), which matplotlib would drop. The figure's
folder is made if missing.
Examples (README, "Parametric campaigns"):

    python3 scripts/plot_campaign.py results/friction/summary.csv --x phi \\
        --y peak_tensile_pipe_MPa --by load -o friction.png
    python3 scripts/plot_campaign.py results/packing/table.csv --x nu_p --y peak_s1_pipes \\
        --y sigma_max --where G_p=300 -o packing.png
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from feps_cli import Error, guard  # noqa: E402


def number(row, column, where, log=False):
    """The finite number in a row's column; with log, it must also be > 0 (a logarithmic axis)."""
    text = row.get(column, "")
    try:
        value = float(text)
    except ValueError:
        raise Error(f"{where}: column {column!r} holds {text!r}, not a number") from None
    if not math.isfinite(value):
        raise Error(f"{where}: column {column!r} is {text}")
    if log and not value > 0.0:
        raise Error(f"{where}: column {column!r} is {text}, which a logarithmic axis cannot show")
    return value


def read_rows(path, needed, where_filters):
    if not os.path.isfile(path):
        raise Error(f"no CSV file {path}", 2)
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in needed if c not in (reader.fieldnames or [])]
        if missing:
            raise Error(f"{path} has no column(s) {missing}; it has {reader.fieldnames}")
        rows, skipped = [], 0
        for row in reader:
            if row.get("status", "ok") != "ok":
                skipped += 1
                continue
            if all(_matches(row.get(k, ""), v) for k, v in where_filters):
                rows.append(row)
    return rows, skipped


def _matches(text, wanted):
    try:
        return math.isclose(float(text), float(wanted), rel_tol=1e-9, abs_tol=1e-12)
    except ValueError:
        return text == wanted


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("--x", required=True, help="the parameter on the horizontal axis")
    ap.add_argument("--y", action="append", required=True, help="a quantity to plot (repeat for more panels)")
    ap.add_argument("--by", help="one line per value of this parameter")
    ap.add_argument("--where", action="append", default=[], metavar="PARAM=VALUE", help="keep only these rows")
    ap.add_argument("-o", "--output", help="figure file (default: CSV name with _<y>.png)")
    ap.add_argument("--title")
    ap.add_argument("--logx", action="store_true", help="logarithmic horizontal axis (e.g. soil moduli)")
    ap.add_argument("--logy", action="store_true", help="logarithmic vertical axis")
    args = ap.parse_args(argv)
    filters = []
    for w in args.where:
        if "=" not in w:
            ap.error(f"--where takes PARAM=VALUE, not {w!r}")
        filters.append(tuple(w.split("=", 1)))
    needed = [args.x] + args.y + ([args.by] if args.by else []) + [k for k, _ in filters]
    rows, skipped = read_rows(args.csv, needed, filters)
    if not rows:
        raise Error(f"no finished row of {args.csv} matches {args.where or 'the CSV'}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    groups = {}
    for i, row in enumerate(rows):
        key = row[args.by] if args.by else ""
        groups.setdefault(key, []).append(row)
    fig, axes = plt.subplots(1, len(args.y), figsize=(max(7.0, 5.0 * len(args.y)), 4.0), squeeze=False)
    for ax, quantity in zip(axes[0], args.y):
        for key in sorted(groups, key=lambda k: (_as_float(k), k)):
            pts = sorted((number(r, args.x, f"row {r.get('case', '?')}", args.logx),
                          number(r, quantity, f"row {r.get('case', '?')}", args.logy)) for r in groups[key])
            label = f"{args.by} = {key}" if args.by else None
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=label)
        ax.set_xlabel(args.x)
        ax.set_ylabel(quantity)
        if args.logx:
            ax.set_xscale("log")
        if args.logy:
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
        if args.by:
            ax.legend()
    fig.suptitle(args.title or f"{os.path.basename(args.csv)}" + (f" ({', '.join(args.where)})" if args.where else ""))
    fig.tight_layout()
    out = args.output or os.path.splitext(args.csv)[0] + "_" + "_".join(args.y) + ".png"
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out, dpi=120)
    print(f"wrote {out} ({len(rows)} rows" + (f"; {skipped} not finished, left out" if skipped else "") + ")")
    return 0


def _as_float(text):
    try:
        return float(text)
    except ValueError:
        return math.inf


if __name__ == "__main__":
    sys.exit(guard(main))
