"""Conversion of user input into the shapes the core expects, with errors that name the parameter.

Value ranges (positive sizes, obstruction inside the aperture, ...) are checked once, in C++; this
module checks types and shapes, which the core cannot see, and applies the core's rules (its length
scales and memory budget) to the arrays Python builds itself.
"""

from __future__ import annotations

import math
import os
import sys
import warnings
from types import FrameType
from typing import Any, Optional

import numpy as np

from . import _core

#: The error of every check here and in the core: a ValueError whose ``parameter``, ``value`` and
#: ``expected`` say what was refused, so that callers never read its message to learn which.
ParameterError = _core.ParameterError


def refused(
    parameter: str, value: Any, expected: str, message: Optional[str] = None
) -> ParameterError:
    """The :data:`ParameterError` refusing ``value`` of ``parameter``; ``message`` defaults to
    "{parameter} = {value} is invalid: expected {expected}"."""
    error = ParameterError(
        message or f"{parameter} = {shown(value)} is invalid: expected {expected}"
    )
    error.parameter, error.value, error.expected = parameter, value, expected
    return error


def reindexed(error: ParameterError, offset: int) -> ParameterError:
    """``error`` about item ``name[i]`` of an array as the same error about ``name[i + offset]``
    (a part of the array was checked, and the caller names the whole); any other ``error`` as it
    is."""
    name, bracket, rest = error.parameter.partition("[")
    index, _, tail = rest.partition("]")
    if not bracket or not index.isdigit() or not str(error).startswith(error.parameter):
        return error
    parameter = f"{name}[{int(index) + offset}]{tail}"
    message = parameter + str(error)[len(error.parameter) :]
    return refused(parameter, error.value, error.expected, message)


#: Largest integer option passed to the core (sizes are checked there against grid and memory
#: limits).
MAX_COUNT = 2**62


def shown(value: Any) -> str:
    """repr(value), shortened for messages (an int of 400 digits, a long list)."""
    text = repr(value)
    return text if len(text) <= 60 else f"{text[:28]}...{text[-12:]} ({type(value).__name__})"


def real(name: str, value: Any) -> float:
    """A real scalar as float; bools, strings and arrays are rejected, and so are ints beyond float
    range."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(
        value, (int, float, np.integer, np.floating)
    ):
        raise refused(name, value, "a real number")
    try:
        return float(value)
    except OverflowError:
        raise refused(name, value, "a real number within double range (|x| < 1.8e308)") from None


def positive(name: str, value: Any) -> float:
    """A finite real number > 0."""
    v = real(name, value)
    if not (v > 0 and math.isfinite(v)):
        raise refused(
            name, v, "a finite value > 0", f"{name} = {v!r} is invalid: expected a finite value > 0"
        )
    return v


def optional_real(name: str, value: Any) -> float | None:
    return None if value is None else real(name, value)


def pair(name: str, value: Any) -> tuple[float, float]:
    """An (x, y) pair of finite floats: a tuple, list or 1-D array of two real numbers (not bools or
    strings)."""
    items = value.tolist() if isinstance(value, np.ndarray) and value.ndim == 1 else value
    if not isinstance(items, (tuple, list)) or len(items) != 2:
        raise refused(name, value, "an (x, y) pair of two numbers")
    x, y = (real(f"{name}[{i}]", v) for i, v in enumerate(items))
    if not (math.isfinite(x) and math.isfinite(y)):
        raise refused(name, value, "finite numbers")
    return (x, y)


def ranges(name: str, value: Any) -> np.ndarray:
    """A non-empty, strictly increasing 1-D array of finite ranges (m)."""
    try:  # ragged nesting such as [1.0, (2.0, 3.0)] fails here, in NumPy's words
        raw = np.asarray(value) if not isinstance(value, (str, bytes)) else np.asarray([value])
    except (TypeError, ValueError, OverflowError) as exc:
        expected = "a 1-D array of ranges in m"
        raise refused(
            name, value, expected, f"{name} is invalid: expected {expected} ({exc})"
        ) from None
    if (
        raw.dtype.kind not in "iuf"
    ):  # strings, bools, objects: refused before float() could accept "100"
        raise refused(name, value, "a 1-D array of ranges in m (real numbers)")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:
        expected = "a 1-D array of ranges in m"
        raise refused(
            name, value, expected, f"{name} is invalid: expected {expected} ({exc})"
        ) from None
    if arr.ndim != 1 or arr.size == 0:
        expected = "a non-empty 1-D array of ranges in m"
        raise refused(name, value, expected, f"{name} has shape {arr.shape}: expected {expected}")
    bad = ~np.isfinite(arr)
    if bad.any():
        item = f"{name}[{int(np.argmax(bad))}]"
        expected = "a finite range in m"
        raise refused(
            item, arr[bad][0], expected, f"{item} = {arr[bad][0]} is invalid: expected {expected}"
        )
    if arr.size > 1 and not np.all(np.diff(arr) > 0):
        i = int(np.argmax(~(np.diff(arr) > 0)))
        raise refused(
            f"{name}[{i + 1}]",
            arr[i + 1],
            f"a range above {name}[{i}] = {arr[i]} (strictly increasing)",
            f"{name} must be strictly increasing: {name}[{i + 1}] = {arr[i + 1]} follows {arr[i]}",
        )
    return arr


def choice(name: str, value: Any, valid: tuple[str, ...]) -> str:
    """One of ``valid``; non-strings (NumPy arrays would make the comparison ambiguous) refused by
    name."""
    if not isinstance(value, str) or value not in valid:
        raise refused(name, value, f"one of {', '.join(map(repr, valid))}")
    return value


def flag(name: str, value: Any) -> bool:
    """True or False, strictly: a truthy string such as 'no' is refused, not read as True."""
    if not isinstance(value, (bool, np.bool_)):
        raise refused(name, value, "True or False")
    return bool(value)


def count(name: str, value: Any, minimum: int, maximum: int = MAX_COUNT) -> int:
    """An integer in [minimum, maximum] (bools refused)."""
    if (
        isinstance(value, (bool, np.bool_))
        or not isinstance(value, (int, np.integer))
        or not minimum <= value <= maximum
    ):
        too_large = isinstance(value, (int, np.integer)) and value > maximum
        limit = (
            f"from {minimum} to {maximum}" if maximum != MAX_COUNT or too_large else f">= {minimum}"
        )
        raise refused(name, value, f"an integer {limit}")
    return int(value)


def threads(value: Any) -> int:
    """The `threads` option: 0 (all cores) up to the core's cap, max(256, 4 x cores)."""
    return count("threads", value, 0, _core.max_threads())


#: The smallest tolerance on G a method accepts (the core's limit, checked here before any plan).
MIN_TOLERANCE = _core.MIN_TOLERANCE


def tolerance(name: str, value: Any) -> float:
    """An absolute tolerance on G, in [MIN_TOLERANCE, 1)."""
    v = real(name, value)
    if not MIN_TOLERANCE <= v < 1.0:
        expected = (
            f"a value in [{MIN_TOLERANCE:g}, 1) (an absolute error on G; double precision resolves "
            "none smaller)"
        )
        raise refused(name, v, expected, f"{name} = {v!r} is invalid: expected {expected}")
    return v


def unit_interval(name: str, value: Any, include_one: bool = False) -> float:
    """A value in (0, 1), or (0, 1] with include_one."""
    v = real(name, value)
    if not (0.0 < v < 1.0 or (include_one and v == 1.0)):
        expected = f"a value in (0, {'1]' if include_one else '1)'}"
        raise refused(name, v, expected, f"{name} = {v!r} is invalid: expected {expected}")
    return v


def length(name: str, value) -> float:
    """A length (m) within the core's scales, MIN_LENGTH to MAX_LENGTH, refused by name
    otherwise."""
    v = real(name, value)
    if not _core.MIN_LENGTH <= v <= _core.MAX_LENGTH:
        expected = f"a length from {_core.MIN_LENGTH:g} m to {_core.MAX_LENGTH:g} m"
        raise refused(name, v, expected, f"{name} = {v!r} is invalid: expected {expected}")
    return v


def check_memory(name: str, value, needed: float, fix: str) -> None:
    """Refuse, naming ``name``, work whose arrays need more than ``lo.max_memory()`` bytes (the
    core's rule for its own grids); ``needed`` in bytes, ``fix`` says what to lower."""
    budget = _core.max_memory()
    if not needed <= budget:
        raise refused(
            name,
            value,
            f"at most {_bytes_shown(budget)} of memory (max_memory)",
            f"{name} = {shown(value)} needs {_bytes_shown(needed)} of memory, more than the budget "
            f"of {_bytes_shown(budget)} (max_memory): {fix}, or raise the budget with "
            "set_max_memory",
        )


def _bytes_shown(size: float) -> str:
    mib = size / 2**20
    return f"{mib:.6g} MiB" if mib < 1024 else f"{mib / 1024:.6g} GiB"


def system_range(system, z: float, name: str) -> None:
    """Refuse, as the overlap paths refuse ``ranges[i]`` but naming ``name``, a range ``z`` (m)
    outside the core's lengths or, behind an obstruction, not beyond its distance
    (``LidarSystem.validate_ranges`` in C++)."""
    try:
        system._native.validate_ranges([z])
    except ParameterError as exc:
        if exc.parameter != "ranges[0]":
            raise
        message = name + str(exc)[len(exc.parameter) :]  # the message begins with the parameter
        raise refused(name, exc.value, exc.expected, message) from None


def warn(message: str, category: type = RuntimeWarning) -> None:
    """``warnings.warn`` attributed to the first caller outside this package, however deep the call
    that warns (so the warning points at the user's line, and filters on the package's modules see
    only misplaced ones)."""
    package = os.path.dirname(os.path.abspath(__file__)) + os.sep
    frame: Optional[FrameType] = sys._getframe(1)
    level = 2
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(package):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)


def real_array(name: str, value: Any, ndim: int | None = None) -> np.ndarray:
    """A float array of real numbers (ints and floats): complex values (never cut to their real
    part), bools, strings and objects are refused naming ``name``; ``ndim`` when given is the
    required number of dimensions."""
    if isinstance(value, (str, bytes)):
        raw = None
    else:
        try:
            raw = np.asarray(value)
        except (TypeError, ValueError, OverflowError):
            raw = None
    if raw is None or raw.dtype.kind not in "iuf":
        kind = "complex numbers" if raw is not None and raw.dtype.kind == "c" else "not numbers"
        raise refused(name, value, f"an array of real numbers ({kind})")
    try:
        values = raw.astype(float)
    except OverflowError:
        expected = "real numbers within double range"
        raise refused(name, value, expected, f"{name} is invalid: expected {expected}") from None
    if ndim is not None and values.ndim != ndim:
        expected = f"a {ndim}-D array of real numbers"
        raise refused(
            name, value, expected, f"{name} has shape {values.shape}: expected {expected}"
        )
    return values


def finite_array(name: str, value: Any, ndim: int | None = None) -> np.ndarray:
    """:func:`real_array` whose values are all finite: the first that is not is refused naming
    ``name[i]`` (i the flat index: a 1-D array's own)."""
    values = real_array(name, value, ndim)
    bad = ~np.isfinite(values)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(
            f"{name}[{i}] = {float(values.flat[i])!r} is invalid: expected finite values"
        )
    return values


def set_max_memory(bytes: int) -> None:
    """Set the memory budget of one call, in bytes (0 restores the default, a quarter of the
    physical memory); ValueError naming ``bytes`` for anything but an integer from 0 to
    2**63 - 1."""
    _core.set_max_memory(count("bytes", bytes, 0, 2**63 - 1))
