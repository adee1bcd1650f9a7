"""The value contract of the public result types, declared once per type: each field's kind (a
finite real, a count, a 1-D or 2-D array, a mapping of names to numbers), checked on construction
so that neither a computation nor ``dataclasses.replace`` can leave NaN, a wrong kind or a wrong
shape in a result; arrays kept as read-only copies and mappings as :class:`FrozenMap`, so that a
result cannot be edited after its checks.

A type lists its fields' kinds in a ``FIELDS`` mapping and calls :func:`check` from
``__post_init__``; ``tests/test_value_contract.py`` checks every public type against the contract.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, Callable, Dict, Iterator, Optional

import numpy as np

from . import _checks

Kind = Callable[[str, Any], Any]


class FrozenMap(Mapping):
    """A read-only mapping (a copy of the one given), equal to any mapping with the same items,
    pickled as a dict; what the result types hold where a dict would let a caller change them."""

    __slots__ = ("_items",)
    _items: Dict[Any, Any]

    def __init__(self, items=()) -> None:
        object.__setattr__(self, "_items", dict(items))

    def __getitem__(self, key):
        return self._items[key]

    def __iter__(self) -> Iterator:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __setattr__(self, name, value):
        raise AttributeError("a FrozenMap cannot be changed")

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Mapping):
            return self._items == dict(other.items())
        return NotImplemented

    def __hash__(self) -> int:
        return hash(tuple(sorted(self._items.items(), key=repr)))

    def __reduce__(self):
        return (FrozenMap, (self._items,))

    def __repr__(self) -> str:
        return repr(self._items)

    def __or__(self, other) -> Dict:
        return {**self._items, **dict(other)}


def check(value: Any, fields: Mapping[str, Kind]) -> None:
    """Each of ``value``'s ``fields`` checked (and converted: read-only arrays, FrozenMap) by its
    kind; ValueError naming the field otherwise."""
    for name, kind in fields.items():
        object.__setattr__(value, name, kind(name, getattr(value, name)))


def real(*, low: float = -math.inf, nan: bool = False, inf: bool = False) -> Kind:
    """A real number >= ``low``; NaN and +inf (an unbounded value) only where allowed."""

    def kind(name: str, value: Any) -> float:
        v = _checks.real(name, value)
        if math.isnan(v):
            if nan:
                return v
        elif (math.isfinite(v) or (inf and v > 0)) and v >= low:
            return v
        allowed = " or NaN" if nan else ""
        bound = "" if low == -math.inf else f" >= {low:g}"
        raise ValueError(
            f"{name} = {v!r} is invalid: expected a {'' if inf else 'finite '}real number{bound}"
            f"{allowed}"
        )

    return kind


def count(low: int = 0) -> Kind:
    """An integer >= ``low``."""
    return lambda name, value: _checks.count(name, value, low)


def flag(name: str, value: Any) -> bool:
    """True or False (not a truthy object)."""
    return _checks.flag(name, value)


def pair(name: str, value: Any) -> tuple:
    """(x, y): two finite real numbers."""
    if not isinstance(value, (tuple, list, np.ndarray)) or len(value) != 2:
        raise ValueError(f"{name} = {_checks.shown(value)} is invalid: expected (x, y)")
    number = real()
    return tuple(number(f"{name}[{i}]", v) for i, v in enumerate(value))


def text(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise ValueError(f"{name} = {_checks.shown(value)} is invalid: expected a text")
    return value


def array(
    ndim: int = 1,
    *,
    low: float = -math.inf,
    nan: bool = False,
    inf: bool = False,
    optional: bool = False,
    square: bool = False,
) -> Kind:
    """A read-only float array of ``ndim`` dimensions (square when asked) whose values are >=
    ``low``; NaN and +inf only where allowed; None where ``optional``."""

    def kind(name: str, value: Any) -> Optional[np.ndarray]:
        if value is None and optional:
            return None
        a = _checks.real_array(name, value, ndim=ndim)
        if square and a.shape[0] != a.shape[-1]:
            raise ValueError(f"{name} has shape {a.shape}: expected a square matrix")
        bad = np.isinf(a) if not inf else np.isneginf(a)
        if not nan:
            bad |= np.isnan(a)
        bad |= a < low
        if bad.any():
            where = np.unravel_index(int(np.argmax(bad)), a.shape)
            index = ", ".join(str(int(i)) for i in where)
            raise ValueError(
                f"{name}[{index}] = {float(a[where])!r} is invalid: expected "
                f"{'' if inf else 'finite '}values"
                + ("" if low == -math.inf else f" >= {low:g}")
                + (" or NaN" if nan else "")
            )
        return frozen(a)

    return kind


def reals(*, nan: bool = False, inf: bool = False) -> Kind:
    """A mapping of names (str) to real numbers, kept as a :class:`FrozenMap`."""
    number = real(nan=nan, inf=inf)

    def kind(name: str, value: Any) -> FrozenMap:
        if not isinstance(value, Mapping):
            raise ValueError(
                f"{name} = {_checks.shown(value)} is invalid: expected a mapping of names to "
                "numbers"
            )
        items = {}
        for key, v in value.items():
            if not isinstance(key, str):
                raise ValueError(f"{name} key {_checks.shown(key)} is invalid: expected a name")
            items[key] = number(f"{name}[{key!r}]", v)
        return FrozenMap(items)

    return kind


def frozen(values: np.ndarray) -> np.ndarray:
    """``values`` as a read-only array of its own (a caller's array is copied, never frozen)."""
    values = np.array(values, dtype=float, copy=True)
    values.setflags(write=False)
    return values
