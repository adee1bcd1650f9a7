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
