"""The one place an :class:`OverlapResult` is built from a core result and its plan."""

from __future__ import annotations

import numpy as np

from ..result import OverlapResult


def result(plan, overlap, error_estimate, cls=OverlapResult, **extra) -> OverlapResult:
    """``cls`` for ``plan`` (its ranges, system, model, stated tolerance and error kind) with G =
    ``overlap`` and ``error_estimate`` (an array, or one value for every range); ``extra`` fields
    for subclasses."""
    z = plan.ranges
    error = np.broadcast_to(np.asarray(error_estimate, dtype=float), z.shape).copy()
    return cls(
        ranges=z,
        overlap=np.asarray(overlap, dtype=float),
        method=plan.method,
        error_estimate=error,
        system=plan.system,
        tolerance=plan.tolerance,
        error_kind=plan.error_kind,
        **extra,
    )
