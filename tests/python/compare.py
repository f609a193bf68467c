# SPDX-License-Identifier: MIT
"""Comparing a Python summary with the JSON file the CLI wrote for the same run."""
from __future__ import annotations

import math
import re

import numpy as np

def is_timing(key: str) -> bool:
    """Wall and CPU times differ run to run; every summary names them *_seconds."""
    return key.endswith("_seconds")
# Ratios of singular values (in [0, 1]): an SVD gives every singular value to about ε·σ_max, so
# a ratio near zero is exact to ~1e-16 ABSOLUTELY but not relatively — measured in CI: the
# (MF1) ratio 2.749161075631567e-10 (CLI) against 2.7491610994504885e-10 (Python), 9e-9
# relative, from a different BLAS thread count (FRICTOPT_BLAS_THREADS=auto follows the idle
# cores). Compared to 1e-12 absolutely.
SINGULAR_VALUE_RATIOS = {"sigma_min_over_max"}


def without_times(text: str) -> str:
    """A one-line report without its wall times ("..., 0.0079 s")."""
    return re.sub(r"[0-9.e+-]+ s\b", "", text)


def assert_same(cli, py, path: str = "") -> None:
    """Every field of the CLI's JSON is in the Python summary and equal to it to 1e-12
    (relative; singular-value ratios absolute; timings and the wall times inside reports
    excepted; JSON null is NaN)."""
    if isinstance(cli, dict):
        for key, value in cli.items():
            assert key in py, f"{path}{key} missing from the Python summary"
            if not is_timing(key):
                assert_same(value, py[key], f"{path}{key}.")
    elif isinstance(cli, list) and cli and all(isinstance(v, (int, float)) or v is None for v in cli) \
            and any(isinstance(v, float) for v in cli):
        expected = np.array([np.nan if v is None else v for v in cli], dtype=float)
        np.testing.assert_allclose(np.asarray(py, dtype=float), expected, rtol=1e-12, atol=0, err_msg=path)
    elif isinstance(cli, list):
        assert len(py) == len(cli), path
        for k, (a, b) in enumerate(zip(cli, py)):
            assert_same(a, b, f"{path}[{k}].")
    elif cli is None:
        assert py is None or (isinstance(py, float) and math.isnan(py)), path
    elif isinstance(cli, float) and path.rstrip(".").rsplit(".", 1)[-1] in SINGULAR_VALUE_RATIOS:
        assert math.isclose(py, cli, rel_tol=0.0, abs_tol=1e-12), f"{path}: {py} != {cli}"
    elif isinstance(cli, float):
        assert math.isclose(py, cli, rel_tol=1e-12, abs_tol=0.0) or py == cli, f"{path}: {py} != {cli}"
    elif isinstance(cli, str):
        assert without_times(py) == without_times(cli), path
    else:
        assert py == cli, path
