"""The method object an analysis runs: a shortcut string with its tolerance, or an object as given;
and the check that an analysis needing ray tracing's error estimates got ray tracing."""

from __future__ import annotations

from .. import _checks
from ..forward.methods import RT, from_shortcuts


def requested(method, tolerance) -> object:
    """The method object of ``method`` (a shortcut string takes ``tolerance``; an object is used as
    it is)."""
    return (
        from_shortcuts(method, tolerance=tolerance)
        if isinstance(method, str)
        else from_shortcuts(method)
    )


def ray_tracing(model, why: str) -> RT:
    """``model`` if it is ray tracing, else a ValueError saying ``why`` it must be."""
    if not isinstance(model, RT):
        raise ValueError(f"method = {_checks.shown(model)} is not available {why}")
    return model
