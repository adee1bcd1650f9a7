"""Conversion of user input into the shapes the core expects, with errors that name the parameter.

Value ranges (positive sizes, obstruction inside the aperture, ...) are checked once, in C++; this
module only checks types and shapes, which the core cannot see.
"""

from __future__ import annotations

from typing import Any

import math

import numpy as np


def real(name: str, value: Any) -> float:
    """A real scalar as float; bools, strings and arrays are rejected."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"{name} = {value!r} is invalid: expected a real number")
    return float(value)


def positive(name: str, value: Any) -> float:
    """A finite real number > 0."""
    v = real(name, value)
    if not (v > 0 and math.isfinite(v)):
        raise ValueError(f"{name} = {v!r} is invalid: expected a finite value > 0")
    return v


def optional_real(name: str, value: Any) -> float | None:
    return None if value is None else real(name, value)


def pair(name: str, value: Any) -> tuple[float, float]:
    """An (x, y) pair of finite floats."""
    arr = np.asarray(value, dtype=float) if not isinstance(value, str) else np.asarray([])
    if arr.shape != (2,):
        raise ValueError(f"{name} = {value!r} is invalid: expected an (x, y) pair of two numbers")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} = {value!r} is invalid: expected finite numbers")
    return (float(arr[0]), float(arr[1]))


def ranges(name: str, value: Any) -> np.ndarray:
    """A non-empty, strictly increasing 1-D array of finite ranges (m)."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} is invalid: expected a 1-D array of ranges in m ({exc})") from None
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name} has shape {arr.shape}: expected a non-empty 1-D array of ranges in m")
    bad = ~np.isfinite(arr)
    if bad.any():
        raise ValueError(f"{name}[{int(np.argmax(bad))}] = {arr[bad][0]} is invalid: expected a finite range in m")
    if arr.size > 1 and not np.all(np.diff(arr) > 0):
        i = int(np.argmax(~(np.diff(arr) > 0)))
        raise ValueError(f"{name} must be strictly increasing: {name}[{i + 1}] = {arr[i + 1]} follows {arr[i]}")
    return arr


def choice(name: str, value: Any, valid: tuple[str, ...]) -> str:
    if value not in valid:
        raise ValueError(f"{name} = {value!r} is invalid: expected one of {', '.join(map(repr, valid))}")
    return value


def count(name: str, value: Any, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValueError(f"{name} = {value!r} is invalid: expected an integer >= {minimum}")
    return int(value)


def unit_interval(name: str, value: Any, include_one: bool = False) -> float:
    """A value in (0, 1), or (0, 1] with include_one."""
    v = real(name, value)
    if not (0.0 < v < 1.0 or (include_one and v == 1.0)):
        raise ValueError(f"{name} = {v!r} is invalid: expected a value in (0, {'1]' if include_one else '1)'}")
    return v
