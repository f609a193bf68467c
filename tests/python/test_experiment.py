# SPDX-License-Identifier: MIT
"""frictopt.experiment: the virtual tribometer from Python, the same run as ``frictopt experiment``
(io::run_experiment): summary.json's fields to 1e-12, the same CSV files, each angle's ramp as
numpy columns, and a case without [experiment] refused with the CLI's message. frictopt.solve_program:
a loading program, the same run as ``frictopt solve`` of such a case (io::run_loading_program)."""
from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import frictopt
from compare import assert_same


@pytest.fixture(scope="module")
def small_tribometer(root, tmp_path_factory):
    """The shipped elliptic tribometer on a coarse specimen, pulled along two angles, with the pull
    length left to the run (ramped on to steady sliding)."""
    case = frictopt.load_case(root / "cases3d/tribometer-ellipse/case.toml")
    small = case.with_overrides(mesh={"cells": [4, 4, 2]},
                                experiment={"angles_degrees": [0, 90], "ramp_steps": 12,
                                            "pull_displacement": None})
    path = tmp_path_factory.mktemp("tribometer") / "case.toml"
    path.write_text(small.toml)
    return path


def test_experiment_agrees_with_the_cli(small_tribometer, tmp_path, frictopt_binary) -> None:
    subprocess.run([frictopt_binary, "experiment", small_tribometer, "-o", tmp_path / "cli"], check=True,
                   capture_output=True)
    cli = json.loads((tmp_path / "cli" / "summary.json").read_text())
    case = frictopt.load_case(small_tribometer)
    result = frictopt.experiment(case, tmp_path / "py")
    cli["case"] = case.origin
    assert_same(cli, result)
    assert result.status == "converged"
    assert result.automatic_pull
    assert [a.angle_degrees for a in result.angles] == [0.0, 90.0]
    # Along the ellipse's axes the sliding force is μ_x P and μ_y P.
    for angle, mu in zip(result.angles, (0.4, 0.2)):
        assert angle.steady_sliding
        assert angle.measured_mu == pytest.approx(mu, rel=1e-6)
        assert angle.law_mu == pytest.approx(mu, rel=1e-12)
        ramp = angle.ramp
        assert 12 <= len(ramp.pull) < 20 * 12
        np.testing.assert_allclose(ramp.normal_force, 1.0e4, rtol=1e-6)
        assert ramp.stick_fraction[0] > ramp.stick_fraction[-1]
    for name in ("tribometer_ramp.csv", "tribometer_polar.csv", "tribometer_law.csv"):
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text(), name


def test_experiment_without_a_run_directory_writes_nothing(small_tribometer, tmp_path) -> None:
    result = frictopt.experiment(frictopt.load_case(small_tribometer))
    assert result.run_directory is None
    assert len(result.angles) == 2


def test_a_case_without_an_experiment_is_refused(root, tmp_path) -> None:
    case = frictopt.load_case(root / "cases3d/punch/case.toml")
    with pytest.raises(ValueError, match=r"no \[experiment\] table; expected one with normal_force"):
        frictopt.experiment(case, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_solve_program_agrees_with_the_cli(root, tmp_path, frictopt_binary) -> None:
    """The shipped Cattaneo–Mindlin program (press, then two tangential steps) on a coarse grid:
    summary.json and the VTK series as the CLI writes them."""
    case = frictopt.load_case(root / "cases3d/mindlin-loading/case.toml").with_overrides(
        mesh={"cells": [8, 8, 3], "growth": None, "refine_box": None})
    path = tmp_path / "case.toml"
    path.write_text(case.toml)
    subprocess.run([frictopt_binary, "solve", path, "-o", tmp_path / "cli"], check=True, capture_output=True)
    cli = json.loads((tmp_path / "cli" / "summary.json").read_text())
    loaded = frictopt.load_case(path)
    result = frictopt.solve_program(loaded, tmp_path / "py")
    cli["case"] = loaded.origin
    for step in cli["steps"]:
        step["case"] = loaded.origin
    assert_same(cli, result)
    assert result.status == "converged"
    assert result.steps_solved == len(result.steps) == 6
    assert result.factorizations == 1
    assert [s.step for s in result.steps] == list(range(1, 7))
    assert sorted(p.name for p in (tmp_path / "py").glob("*.pvd")) == sorted(p.name for p in (tmp_path / "cli").glob("*.pvd"))
    assert frictopt.solve_program(frictopt.load_case(path)).run_directory is None


def test_solve_program_refuses_a_case_without_a_program(root) -> None:
    with pytest.raises(ValueError, match="no \\[\\[program.step\\]\\] tables"):
        frictopt.solve_program(frictopt.load_case(root / "cases3d/punch/case.toml"))

