#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Example (c): a short shape optimization with a live-updating history plot saved to PNG.

Optimizes the demo case (cases3d/punch-anisotropic: uniform contact pressure under anisotropic
friction) on a coarser mesh for a few bundle-trust iterations. The per-iteration callback
appends Θ and the relative stationarity measure to the plot and saves it again, so an image
viewer open on DIR/history.png follows the run; the run directory DIR/run is the CLI's
(history.csv, checkpoint.json, VTK series) and can be continued with
``frictopt.optimize(None, DIR/"run", resume=True)`` or ``frictopt optimize --resume``.
Ctrl-C stops at the next iteration with the run directory intact.

    python3 examples/python/live_optimization.py [--out DIR] [--iterations N] [--cells 8 8 4]
"""
from __future__ import annotations

import argparse
import pathlib

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

import frictopt

ROOT = pathlib.Path(__file__).resolve().parents[2]


class LivePlot:
    """Θ and the stationarity measure per iteration, redrawn and saved after each one."""

    def __init__(self, path: pathlib.Path, title: str) -> None:
        self.path = path
        self.fig, (self.ax_theta, self.ax_stat) = plt.subplots(2, 1, figsize=(6.0, 5.0), sharex=True)
        self.ax_theta.set_ylabel("Θ [N²]")
        self.ax_stat.set_ylabel("‖z + ω‖ / |Θ(α⁰)| [1/m]")
        self.ax_stat.set_xlabel("iteration")
        for ax in (self.ax_theta, self.ax_stat):
            ax.set_yscale("log")
            ax.grid(alpha=0.3)
        self.fig.suptitle(title)
        (self.theta_line,) = self.ax_theta.plot([], [], "o-", ms=3)
        (self.stat_line,) = self.ax_stat.plot([], [], "o-", ms=3, color="C1")
        self.iterations: list[int] = []
        self.theta: list[float] = []
        self.stationarity: list[float] = []

    def __call__(self, progress: frictopt.Summary) -> None:
        self.iterations.append(progress.iteration)
        self.theta.append(progress.theta)
        self.stationarity.append(progress.stationarity_relative)
        self.theta_line.set_data(self.iterations, self.theta)
        self.stat_line.set_data(self.iterations, self.stationarity)
        for ax in (self.ax_theta, self.ax_stat):
            ax.relim()
            ax.autoscale_view()
        self.fig.savefig(self.path, dpi=110)
        print(f"{progress.iteration:>4} {progress.step:>20} Θ = {progress.theta:.6e} N²  "
              f"stationarity {progress.stationarity_relative:.2e}  {progress.elapsed_seconds:6.2f} s", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("example-output"))
    parser.add_argument("--iterations", type=int, default=15)
    parser.add_argument("--cells", type=int, nargs=3, default=[8, 8, 4])
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    case = frictopt.load_case(ROOT / "cases3d" / "punch-anisotropic" / "case.toml").with_overrides(
        mesh={"cells": args.cells}, output={"every": 5})
    plot = LivePlot(args.out / "history.png", f"punch-anisotropic, mesh {'×'.join(map(str, args.cells))}")
    result = frictopt.optimize(case, args.out / "run", callback=plot, force=True, max_iterations=args.iterations)
    print(f"{result.status} ({result.stopped_by}) after {result.iterations} iterations, "
          f"{result.evaluations} evaluations: Θ {result.initial_cost:.4e} -> {result.final_cost:.4e} N² "
          f"({100 * (1 - result.final_cost / result.initial_cost):.1f}% lower)")
    print(f"final index sets: {result.final_index_sets}")
    print(f"wrote {plot.path} and the run directory {result.run_directory}")


if __name__ == "__main__":
    main()
