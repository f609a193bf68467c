#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Plot the friction polar and the stick-area ramps of a `frictopt experiment` run.

Reads DIR/tribometer_law.csv (the law's radial function mu(phi) and support function N_W(theta)),
DIR/tribometer_polar.csv (per pull angle: the measured sliding force |T|/P at its direction phi,
the slip direction and the resistance along it) and DIR/tribometer_ramp.csv (stick-area fraction
along each ramp), all written by `frictopt experiment CASE -o DIR`, and writes
DIR/tribometer_polar.png: left, a polar plot of the law's friction set boundary mu(phi) (line)
with the measured friction forces (dots) and the law's resistance N_W(theta) along the slip
direction (dashed) with the measured resistances (crosses); right, the stick-area fraction
against the platen displacement, one line per pull angle.

Usage:  /usr/bin/python3 viz/plot_tribometer.py DIR [--output FILE.png]
Exits non-zero when a CSV is missing or empty.
"""

import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    if not os.path.isfile(path):
        sys.exit(f"plot_tribometer.py: {path} not found (run `frictopt experiment CASE -o DIR` first)")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot_tribometer.py: {path} has no rows")
    return [{k: float(v) if v not in ("", "nan", "null") else math.nan for k, v in r.items()} for r in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", help="output directory of frictopt experiment")
    parser.add_argument("--output", help="PNG file (default DIR/tribometer_polar.png)")
    args = parser.parse_args()
    law = read_rows(os.path.join(args.dir, "tribometer_law.csv"))
    polar = read_rows(os.path.join(args.dir, "tribometer_polar.csv"))
    ramp = read_rows(os.path.join(args.dir, "tribometer_ramp.csv"))

    fig = plt.figure(figsize=(12, 5.5))
    ax = fig.add_subplot(1, 2, 1, projection="polar")
    phi = [math.radians(r["angle_degrees"]) for r in law]
    ax.plot(phi, [r["radial_mu"] for r in law], "k-", lw=1.5, label="law: boundary of W, μ(φ)")
    ax.plot(phi, [r["support_mu"] for r in law], "k--", lw=0.8, label="law: resistance N_W(θ) along the slip")
    sliding = [r for r in polar if r["steady_sliding"] == 1.0]
    ax.plot([math.radians(r["force_angle_degrees"]) for r in sliding], [r["measured_mu"] for r in sliding], "o",
            color="tab:red", label="measured |T|/P at the force direction φ")
    ax.plot([math.radians(r["slip_angle_degrees"]) for r in sliding], [r["sliding_resistance"] for r in sliding], "x",
            color="tab:blue", label="measured ⟨−T/P, ŝ⟩ at the slip direction ŝ")
    worst = max((r["relative_error"] for r in sliding), default=math.nan)
    worst_n = max((r["normality_residual"] for r in sliding), default=math.nan)
    ax.set_title(f"friction polar ({len(sliding)}/{len(polar)} angles in steady sliding)\n"
                 f"max rel. error {worst:.1e}, max normality residual {worst_n:.1e}", fontsize=9)
    ax.legend(loc="lower left", bbox_to_anchor=(-0.15, -0.32), fontsize=8)

    ax2 = fig.add_subplot(1, 2, 2)
    angles = sorted({r["angle_degrees"] for r in ramp})
    cmap = plt.get_cmap("hsv")
    for k, a in enumerate(angles):
        rows = [r for r in ramp if r["angle_degrees"] == a]
        ax2.plot([r["pull"] * 1e6 for r in rows], [r["stick_fraction"] for r in rows], "-",
                 color=cmap(k / max(1, len(angles))), lw=1, label=f"{a:g}°" if len(angles) <= 12 else None)
    ax2.set_xlabel("platen displacement [µm]")
    ax2.set_ylabel("stick area / contact area")
    ax2.set_title("stick zone along the ramp (one line per pull angle θ)", fontsize=9)
    ax2.grid(True, alpha=0.3)
    if len(angles) <= 12:
        ax2.legend(fontsize=7)
    fig.tight_layout()
    out = args.output or os.path.join(args.dir, "tribometer_polar.png")
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
