# SPDX-License-Identifier: MIT
"""The examples under examples/python run headless (matplotlib Agg) and write their pictures."""
from __future__ import annotations

import csv
import os
import subprocess
import sys

import pytest


def run_example(root, tmp_path, name: str, *extra: str) -> str:
    env = dict(os.environ, MPLBACKEND="Agg")
    out = subprocess.run([sys.executable, root / "examples" / "python" / name, "--out", tmp_path, *extra],
                         capture_output=True, text=True, env=env, timeout=900)
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_friction_fit(root, tmp_path) -> None:
    text = run_example(root, tmp_path, "friction_fit.py")
    assert (tmp_path / "friction_fit.png").stat().st_size > 10_000
    # The 8-gon fit explains the data to the noise level; the ellipse cannot.
    rms = {line.split(":")[0].strip(): float(line.split("rms residual ")[1].split()[0])
           for line in text.splitlines() if "rms residual" in line}
    assert rms["polygon 8-gon"] < 0.012 < rms["ellipse 16-gon"]


def test_punch_sweep(root, tmp_path) -> None:
    run_example(root, tmp_path, "punch_sweep.py", "--cells", "6", "6", "3")
    assert (tmp_path / "punch_sweep.png").stat().st_size > 10_000
    with open(tmp_path / "punch_sweep.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 20
    # More friction at the same press: the stick area does not shrink.
    for press in {r["press_mm"] for r in rows}:
        fractions = [float(r["stick_area_fraction"]) for r in rows if r["press_mm"] == press]
        assert all(b >= a - 1e-12 for a, b in zip(fractions, fractions[1:])), press


def test_live_optimization(root, tmp_path) -> None:
    text = run_example(root, tmp_path, "live_optimization.py", "--iterations", "4")
    assert (tmp_path / "history.png").stat().st_size > 10_000
    assert (tmp_path / "run" / "checkpoint.json").exists()
    assert "after 4 iterations" in text
