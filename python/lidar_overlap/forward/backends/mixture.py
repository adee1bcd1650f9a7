"""Beams of mutually incoherent Gaussian components (:class:`lidar_overlap.GaussianMixtureBeam`):
each component's plan run by its own backend, G the power-weighted sum of theirs.

G is linear in the transmitted irradiance and incoherent components add their irradiances, so the
sum is exact; its error is the same weighted sum of the components' stated errors (a bound of the
sum where each is a bound, the weighted mean of nominal accuracies otherwise).
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from ..result import OverlapResult
from ._result import result


def combine(plan, parts: Sequence) -> OverlapResult:
    """The result of the mixture ``plan`` from its components' results ``parts`` (in the order of
    ``plan.parts``): G = Σ w_i G_i, error Σ w_i e_i, with w_i the power shares of
    ``plan.system.beam``."""
    weights = [w for w, _ in plan.system.incoherent_parts]
    if len(weights) != len(parts):
        raise ValueError(
            f"plan.parts has {len(parts)} plans: expected one per beam component ({len(weights)})"
        )
    overlap = sum(w * np.asarray(r.overlap, dtype=float) for w, r in zip(weights, parts))
    error = sum(w * np.asarray(r.error_estimate, dtype=float) for w, r in zip(weights, parts))
    return result(plan, overlap, error)
