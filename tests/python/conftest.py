# SPDX-License-Identifier: MIT
"""Shared fixtures of the frictopt pytest suite (run by ctest: python_pytest_quick / _slow)."""
from __future__ import annotations

import os
import pathlib
import shutil

import pytest

import frictopt

ROOT = pathlib.Path(__file__).resolve().parents[2]
DEMO = ROOT / "cases3d" / "punch-anisotropic" / "case.toml"


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "slow: optimization runs (ctest label slow)")


@pytest.fixture(scope="session")
def root() -> pathlib.Path:
    return ROOT


@pytest.fixture(scope="session")
def demo_case() -> frictopt.Case:
    """The demo case (cases3d/punch-anisotropic), 16 × 16 × 8 cells."""
    return frictopt.load_case(DEMO)


@pytest.fixture(scope="session")
def coarse_case(demo_case: frictopt.Case) -> frictopt.Case:
    """The demo case on an 8 × 8 × 4 mesh (81 contact nodes), for quick solves and optimizations."""
    return demo_case.with_overrides(mesh={"cells": [8, 8, 4]}, output={"every": 2})


@pytest.fixture(scope="session")
def frictopt_binary() -> pathlib.Path:
    """The CLI built alongside the module (FRICTOPT_BINARY, set by ctest)."""
    path = os.environ.get("FRICTOPT_BINARY") or shutil.which("frictopt")
    if not path:
        pytest.skip("the frictopt CLI is not available (FRICTOPT_BINARY unset)")
    return pathlib.Path(path)
