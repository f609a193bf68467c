# SPDX-License-Identifier: MIT
"""A small TOML writer for case tables built in Python (the standard library reads TOML,
tomllib, but does not write it). Cases built this way go through the case-file parser, so
they are validated exactly like files."""
from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np


def _key(key: str) -> str:
    if key and all(c.isalnum() or c in "_-" for c in key):
        return key
    return json.dumps(key)


def _is_table(value: Any) -> bool:
    return isinstance(value, Mapping)


def _is_table_array(value: Any) -> bool:
    return isinstance(value, (list, tuple)) and len(value) > 0 and all(isinstance(v, Mapping) for v in value)


def _value(value: Any) -> str:
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)  # shortest round-trip text; 1e-05 is valid TOML
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)  # JSON string escapes are TOML basic-string escapes
    if hasattr(value, "__fspath__"):
        return json.dumps(str(value))
    if isinstance(value, Sequence):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} value {value!r} as TOML")


def _emit(lines: list[str], path: list[str], table: Mapping, header: str | None) -> None:
    scalars = [(k, v) for k, v in table.items() if v is not None and not _is_table(v) and not _is_table_array(v)]
    if header is not None:
        lines.append("")
        lines.append(header)
    for key, value in scalars:
        lines.append(f"{_key(str(key))} = {_value(value)}")
    for key, value in table.items():
        sub = path + [_key(str(key))]
        if _is_table(value):
            _emit(lines, sub, value, "[" + ".".join(sub) + "]")
        elif _is_table_array(value):
            for item in value:
                _emit(lines, sub, item, "[[" + ".".join(sub) + "]]")


def to_toml(tables: Mapping[str, Any]) -> str:
    """TOML text of nested dicts (tables), lists of dicts (arrays of tables, e.g. [[dirichlet]])
    and scalars / lists / numpy arrays of numbers; keys whose value is None are left out."""
    lines: list[str] = []
    _emit(lines, [], tables, None)
    return "\n".join(lines).lstrip("\n") + "\n"


def merge(base: Mapping[str, Any], overrides: Mapping[str, Any]) -> dict[str, Any]:
    """`base` with `overrides` merged in: tables merge recursively, other values replace,
    and None removes a key."""
    out = dict(base)
    for key, value in overrides.items():
        if value is None:
            out.pop(key, None)
        elif _is_table(value) and _is_table(out.get(key)):
            out[key] = merge(out[key], value)
        else:
            out[key] = value
    return out
