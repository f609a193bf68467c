# SPDX-License-Identifier: MIT
"""optimize: per-iteration callback, early stop, exceptions, run directories, resume, Ctrl-C."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import frictopt
from compare import assert_same


def test_callback_sees_every_iteration(coarse_case: frictopt.Case) -> None:
    seen = []
    result = frictopt.optimize(coarse_case, callback=seen.append, max_iterations=4)
    assert result.status == "max_iterations" and result.stopped_by == "max_iterations"
    assert [p.iteration for p in seen] == [1, 2, 3, 4] == list(result.history.iteration)
    assert seen[-1].theta == pytest.approx(result.final_cost, rel=1e-12)
    assert result.final_cost < result.initial_cost
    assert seen[0].alpha.shape == (16,) and "stationarity_relative" in seen[0]
    assert result.run_directory is None


@pytest.mark.parametrize("stop", ["false", "stop_iteration"])
def test_early_stop(coarse_case: frictopt.Case, stop: str) -> None:
    def callback(progress: frictopt.Summary):
        if progress.iteration == 2:
            if stop == "false":
                return False
            raise StopIteration
        return None
    result = frictopt.optimize(coarse_case, callback=callback)
    assert result.status == "stopped_by_callback" and result.iterations == 2


def test_callback_exception_is_raised_after_the_run_directory_is_complete(coarse_case, tmp_path) -> None:
    def callback(progress):
        if progress.iteration == 2:
            raise RuntimeError("enough")
    run = tmp_path / "run"
    with pytest.raises(RuntimeError, match="enough"):
        frictopt.optimize(coarse_case, run, callback=callback)
    summary = json.loads((run / "summary.json").read_text())
    assert summary["status"] == "stopped_by_callback" and summary["iterations"] == 2
    assert (run / "checkpoint.json").exists() and (run / "final_design.json").exists()


def test_run_directory_layout_refusal_and_resume(coarse_case: frictopt.Case, tmp_path) -> None:
    run = tmp_path / "run"
    first = frictopt.optimize(coarse_case, run, max_iterations=3)
    for name in ["case.toml", "history.csv", "checkpoint.json", "final_design.json", "summary.json",
                 "punch-anisotropic.pvd", "punch-anisotropic_iter0000.vtu"]:
        assert (run / name).exists(), name
    assert frictopt.load_case(run / "case.toml").to_dict() == coarse_case.to_dict()
    with pytest.raises(ValueError, match="already holds a run"):
        frictopt.optimize(coarse_case, run)
    resumed = frictopt.optimize(None, run, resume=True, max_iterations=6)
    assert resumed.iterations == 6
    rows = (run / "history.csv").read_text().strip().splitlines()
    assert [int(r.split(",")[0]) for r in rows[1:]] == [1, 2, 3, 4, 5, 6]
    # The checkpoint holds the warm start too: the resumed run repeats the uninterrupted one bit for bit.
    straight = frictopt.optimize(coarse_case, max_iterations=6)
    np.testing.assert_array_equal(resumed.alpha, straight.alpha)
    assert resumed.final_cost == straight.final_cost
    assert first.iterations == 3
    # force=True replaces a run, but never removes a file frictopt did not write.
    (run / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="notes.txt"):
        frictopt.optimize(coarse_case, run, force=True, max_iterations=1)
    assert (run / "notes.txt").read_text() == "mine"
    (run / "notes.txt").unlink()
    assert frictopt.optimize(coarse_case, run, force=True, max_iterations=1).iterations == 1
    with pytest.raises(ValueError, match="not the case of the run"):
        frictopt.optimize(coarse_case.with_overrides(material={"young": 2.1e11}), run, resume=True)
    with pytest.raises(ValueError, match="holds no run"):
        frictopt.optimize(coarse_case, tmp_path / "empty", resume=True)


def test_certify_a_run_directory(coarse_case: frictopt.Case, tmp_path) -> None:
    run = tmp_path / "run"
    frictopt.optimize(coarse_case, run, max_iterations=3)
    c = frictopt.certify(run_directory=run, cap=64)
    assert c.status == "converged"
    stored = json.loads((run / "certificate.json").read_text())
    assert stored["value"] == pytest.approx(c.value, rel=1e-15)
    final = json.loads((run / "final_design.json").read_text())["alpha"]
    np.testing.assert_array_equal(c.alpha, final)


CTRL_C_SCRIPT = textwrap.dedent("""
    import json, os, pathlib, signal, sys, threading, time
    import frictopt
    run = pathlib.Path(sys.argv[1])
    case = frictopt.load_case(sys.argv[2]).with_overrides(mesh={"cells": [8, 8, 4]})
    def interrupt():  # Ctrl-C while C++ works (the GIL is released): after 2 iterations are logged
        while not (run / "history.csv").exists() or len((run / "history.csv").read_text().splitlines()) < 3:
            time.sleep(0.01)
        os.kill(os.getpid(), signal.SIGINT)
    threading.Thread(target=interrupt, daemon=True).start()
    try:
        frictopt.optimize(case, run, max_iterations=200, epsilon=0.0)
        print(json.dumps({"interrupted": False}))
    except KeyboardInterrupt:
        summary = json.loads((run / "summary.json").read_text())
        print(json.dumps({"interrupted": True, "status": summary["status"], "iterations": summary["iterations"]}))
""")


def test_ctrl_c_stops_at_the_next_iteration_with_the_run_directory_intact(root, tmp_path) -> None:
    run = tmp_path / "run"
    out = subprocess.run([sys.executable, "-c", CTRL_C_SCRIPT, run, root / "cases3d/punch-anisotropic/case.toml"],
                         capture_output=True, text=True, timeout=600, env=dict(os.environ))
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout.strip().splitlines()[-1])
    assert report["interrupted"] and report["status"] == "stopped_by_callback"
    assert 2 <= report["iterations"] < 200
    resumed = frictopt.optimize(None, run, resume=True, max_iterations=report["iterations"] + 2)
    assert resumed.iterations == report["iterations"] + 2


@pytest.mark.slow
def test_optimize_agrees_with_the_cli(coarse_case: frictopt.Case, tmp_path, frictopt_binary) -> None:
    case_file = tmp_path / "coarse.toml"
    case_file.write_text(coarse_case.toml)
    text = case_file.read_text().replace("max_iterations = 60", "max_iterations = 8")
    case_file.write_text(text)
    subprocess.run([frictopt_binary, "optimize", case_file, "-o", tmp_path / "cli"], check=True, capture_output=True)
    cli = json.loads((tmp_path / "cli" / "summary.json").read_text())
    py = frictopt.optimize(frictopt.load_case(case_file), tmp_path / "py")
    cli["case"] = py["case"]  # each names its own run directory's case.toml
    assert_same(cli, py)
    cli_rows = (tmp_path / "cli" / "history.csv").read_text().splitlines()
    py_rows = (tmp_path / "py" / "history.csv").read_text().splitlines()
    strip = lambda rows: [",".join(r.split(",")[:14]) for r in rows]  # without the timing columns
    assert strip(py_rows) == strip(cli_rows)


@pytest.mark.slow
def test_certify_agrees_with_the_cli_on_a_python_run(coarse_case: frictopt.Case, tmp_path, frictopt_binary) -> None:
    run = tmp_path / "run"
    frictopt.optimize(coarse_case, run, max_iterations=5)
    subprocess.run([frictopt_binary, "certify", run, "--cap", "64"], check=True, capture_output=True)
    cli = json.loads((run / "certificate.json").read_text())
    py = frictopt.certify(run_directory=run, cap=64)
    assert_same(cli, py)
