#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Plot measured vs fitted quantities of a `frictopt identify` run.

Reads DIR/fit.csv (columns quantity, node, x1, x2, measured, sigma, fitted,
normalized_residual, experiment; written by `frictopt identify CASE -o DIR`) and DIR/summary.json, and
writes DIR/identification.png with, per measured quantity kind, one panel of measured values
(error bars ±σ) and fitted values against the measurement index, plus a panel of the normalized
residuals (fitted − measured)/σ with the ±1 and ±2 bands; the title lists the estimates ± their
standard deviations (or their identifiability).

Usage:  /usr/bin/python3 viz/plot_identification.py DIR [--output FILE.png]
Exits non-zero when DIR/fit.csv is missing or empty.
"""

import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_fit(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("measured", "sigma", "fitted", "normalized_residual"):
            r[k] = float(r[k])
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", help="output directory of frictopt identify")
    parser.add_argument("--output", help="PNG path (default DIR/identification.png)")
    args = parser.parse_args()
    fit_path = os.path.join(args.dir, "fit.csv")
    if not os.path.isfile(fit_path):
        sys.exit(f"{fit_path}: not found (run frictopt identify CASE -o {args.dir} first)")
    rows = read_fit(fit_path)
    if not rows:
        sys.exit(f"{fit_path}: no rows")
    summary = {}
    summary_path = os.path.join(args.dir, "summary.json")
    if os.path.isfile(summary_path):
        with open(summary_path) as f:
            summary = json.load(f)

    # Node quantities get a panel each; the sums over the contact surface share one ("totals").
    def kind_of(r):
        return "totals" if r["quantity"].startswith("total_") else r["quantity"]

    kinds = []
    for r in rows:
        if kind_of(r) not in kinds:
            kinds.append(kind_of(r))
    fig, axes = plt.subplots(len(kinds) + 1, 1, figsize=(10, 2.6 * (len(kinds) + 1)), squeeze=False)
    for ax, kind in zip(axes[:, 0], kinds):
        sel = [r for r in rows if kind_of(r) == kind]
        idx = list(range(len(sel)))
        ax.errorbar(idx, [r["measured"] for r in sel], yerr=[r["sigma"] for r in sel], fmt="o", ms=3,
                    color="tab:blue", ecolor="tab:blue", alpha=0.7, label="measured ± σ")
        ax.plot(idx, [r["fitted"] for r in sel], "x", color="tab:red", ms=6, label="fitted")
        ax.set_ylabel(kind, fontsize=8)
        if all(r["node"] not in ("", "-1") for r in sel) and len(sel) <= 30:
            ax.set_xticks(idx)
            ax.set_xticklabels([f"{float(r['x1']):.2g},{float(r['x2']):.2g}" if r["x2"] not in ("", "nan")
                                else f"{float(r['x1']):.2g}" for r in sel], rotation=90, fontsize=6)
        if kind == "totals":
            ax.set_xticks(idx)
            # With several experiments (fit.csv's `experiment` column) each total names its own.
            ax.set_xticklabels([r["quantity"] + (f"\n{r['experiment']}" if r.get("experiment", "case") != "case" else "")
                                for r in sel], fontsize=7)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    ax = axes[-1, 0]
    res = [r["normalized_residual"] for r in rows]
    ax.axhspan(-2, 2, color="0.9")
    ax.axhspan(-1, 1, color="0.8")
    ax.plot(range(len(res)), res, "o", ms=3, color="k")
    ax.set_ylabel("(fitted − measured)/σ", fontsize=8)
    ax.set_xlabel("measurement (file order)")
    ax.grid(alpha=0.3)

    title = "frictopt identify"
    if summary:
        parts = []
        for e in summary.get("estimates", []):
            sd = e.get("standard_deviation")
            if sd is None or (isinstance(sd, float) and math.isnan(sd)):
                parts.append(f"{e['name']} = {e['value']:.4g} ({e['identifiability']})")
            else:
                parts.append(f"{e['name']} = {e['value']:.4g} ± {sd:.2g}")
        title += f": χ² = {summary.get('chi_square', float('nan')):.1f} ({summary.get('degrees_of_freedom')} dof)\n"
        title += ", ".join(parts)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    out = args.output or os.path.join(args.dir, "identification.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
