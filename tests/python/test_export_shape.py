# SPDX-License-Identifier: MIT
"""frictopt.export_shape: a run's design out, the same files as ``frictopt export-shape``
(io::export_shape): the STEP surface's control points are the design's heights over the chart,
the .msh and STL files byte-identical to the CLI's, a directory that is not a run refused."""
from __future__ import annotations

import subprocess

import numpy as np
import pytest

import frictopt


@pytest.fixture(scope="module")
def short_run(coarse_case, tmp_path_factory):
    run = tmp_path_factory.mktemp("export") / "run"
    frictopt.optimize(coarse_case, run, max_iterations=2)
    return run


def test_export_shape_writes_the_clis_files(short_run, tmp_path, frictopt_binary) -> None:
    result = frictopt.export_shape(short_run)
    names = sorted(p.name for p in map(type(short_run), result.files))
    assert any(n.endswith("_design.step") for n in names)
    assert any(n.endswith("_optimized.msh") for n in names)
    assert any(n.endswith("_optimized.stl") for n in names)
    assert result.notes == []
    m1, m2 = result.net
    assert result.control_points.shape == (m1 * m2, 3)
    # The heights of the control points are the design's α (the box's bottom is the plane x3 = 0).
    alpha = np.array(__import__("json").loads((short_run / "final_design.json").read_text())["alpha"])
    np.testing.assert_allclose(result.control_points[:, 2], alpha[: m1 * m2], rtol=0, atol=1e-15)
    assert result.max_node_deviation <= 1e-9 * result.patch_size
    # The CLI writes the same mesh files, byte for byte (the STEP file carries a time stamp).
    copies = {p.name: p.read_bytes() for p in map(type(short_run), result.files) if p.suffix in (".msh", ".stl")}
    done = subprocess.run([str(frictopt_binary), "export-shape", str(short_run)], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    for name, data in copies.items():
        assert (short_run / name).read_bytes() == data, name


def test_export_shape_refuses_a_directory_that_is_no_run(tmp_path) -> None:
    with pytest.raises(ValueError):
        frictopt.export_shape(tmp_path)
