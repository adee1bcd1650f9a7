"""Pickling of the value types (for process pools and distributed clusters): a copy is built again
from the constructor arguments and validated again; the core's object inside a value is never
pickled (it cannot be)."""

from __future__ import annotations

import dataclasses


def rebuild(cls, kwargs: dict):
    """``cls(**kwargs)``: the unpickled copy, checked as any new value is."""
    return cls(**kwargs)


class ByArguments:
    """Mixin for the frozen dataclasses: pickle as (class, the fields the constructor takes)."""

    __slots__ = ()

    def __reduce__(self):
        return rebuild, (
            type(self),
            {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.init},
        )


def same_value(a, b) -> bool:
    """Equality of two field values of a value type: arrays element by element (shape and values,
    NaN equal to NaN), anything else by ``==``."""
    import numpy as np

    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return (
            isinstance(a, np.ndarray)
            and isinstance(b, np.ndarray)
            and a.shape == b.shape
            and bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc" and b.dtype.kind in "fc"))
        )
    return bool(a == b)


class ByValue:
    """Mixin for the frozen dataclasses that hold arrays: equal when of one type and every compared
    field is equal (arrays element by element); hashed by the scalar fields only, which equal
    values share."""

    __slots__ = ()

    def __eq__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return all(
            same_value(getattr(self, f.name), getattr(other, f.name))
            for f in dataclasses.fields(self)
            if f.compare
        )

    def __hash__(self):
        return hash(
            tuple(
                getattr(self, f.name)
                for f in dataclasses.fields(self)
                if f.compare and isinstance(getattr(self, f.name), (int, float, str, tuple))
            )
        )
