# SPDX-License-Identifier: MIT
"""frictopt.Summary: the solver summaries returned to Python."""
from __future__ import annotations

import json
import math
from typing import Any

import numpy as np


class Summary(dict):
    """A solver summary: a dict whose keys are the fields of the JSON file the CLI writes for the
    same run (summary.json, certificate.json, ...), also readable as attributes
    (``summary.status`` is ``summary["status"]``). Numbers are SI / the cost's units as in that
    JSON; arrays of numbers are numpy arrays; a number the solver did not compute is NaN."""

    __slots__ = ()

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(f"Summary has no field '{name}'; fields: {', '.join(self)}") from None

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | set(self.keys()))

    def __repr__(self) -> str:
        def short(value: Any) -> str:
            if isinstance(value, np.ndarray):
                return f"array(shape={value.shape})" if value.size > 6 else np.array2string(value, precision=6)
            if isinstance(value, Summary):
                return "{" + ", ".join(value.keys()) + "}"
            if isinstance(value, float):
                return f"{value:.6g}"
            if isinstance(value, list) and len(value) > 4:
                return f"[{len(value)} items]"
            return repr(value)
        fields = ", ".join(f"{key}={short(value)}" for key, value in self.items())
        return f"Summary({fields})"

    def to_json(self, indent: int = 2) -> str:
        """The summary as JSON text (numpy arrays as lists, NaN as null, like the CLI's files)."""
        def plain(value: Any) -> Any:
            if isinstance(value, dict):
                return {k: plain(v) for k, v in value.items()}
            if isinstance(value, (list, tuple)):
                return [plain(v) for v in value]
            if isinstance(value, np.ndarray):
                return [plain(v) for v in value.tolist()]
            if isinstance(value, float) and not math.isfinite(value):
                return None
            if isinstance(value, np.generic):
                return value.item()
            return value if not hasattr(value, "__fspath__") else str(value)
        return json.dumps(plain(self), indent=indent)
