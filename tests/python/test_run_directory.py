# SPDX-License-Identifier: MIT
"""Run directories written by the Python module are the CLI's: a body from a Gmsh file named
relative to its case can be resumed and certified by either (docs/case-format.md, "Run
directories"); a case.toml frictopt did not write is never replaced."""
from __future__ import annotations

import subprocess

import pytest

import frictopt


def test_a_run_of_a_gmsh_body_named_relatively_resumes_and_certifies(root, tmp_path, frictopt_binary,
                                                                    monkeypatch) -> None:
    # The case names its body "body.geo", relative to cases2d/gmsh-body/; the run's copy lives
    # in tmp_path and must name it absolutely (it kept the relative name, so neither the module
    # nor the CLI could read the run again).
    monkeypatch.chdir(root)
    case = frictopt.load_case("cases2d/gmsh-body/case.toml")
    run = tmp_path / "run"
    first = frictopt.optimize(case, run, max_iterations=2)
    assert first.iterations == 2
    copy = (run / "case.toml").read_text()
    assert str(root / "cases2d" / "gmsh-body" / "body.geo") in copy, copy
    monkeypatch.chdir(tmp_path)  # neither the module nor the CLI depends on the working directory
    resumed = frictopt.optimize(None, run, resume=True, max_iterations=3)
    assert resumed.iterations == 3
    done = subprocess.run([frictopt_binary, "optimize", run / "case.toml", "-o", run, "--resume"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    done = subprocess.run([frictopt_binary, "certify", run, "--cap", "16"], capture_output=True, text=True)
    assert done.returncode in (0, 3), done.stdout + done.stderr


def test_someones_case_toml_is_never_replaced(coarse_case: frictopt.Case, tmp_path) -> None:
    theirs = tmp_path / "theirs"
    theirs.mkdir()
    (theirs / "case.toml").write_text("# someone's case\n")
    with pytest.raises(ValueError, match="does not replace a case file it did not write"):
        frictopt.optimize(coarse_case, theirs, max_iterations=1)
    assert (theirs / "case.toml").read_text() == "# someone's case\n"
