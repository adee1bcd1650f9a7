"""Beams of mutually incoherent Gaussian components (:class:`lidar_overlap.GaussianMixtureBeam`):
each component's plan run by its own backend, G the power-weighted sum of theirs.

G is linear in the transmitted irradiance and incoherent components add their irradiances, so the
sum is exact; its error is the same weighted sum of the components' stated errors (a bound of the
sum where each is a bound, the weighted mean of nominal accuracies otherwise).
"""

from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

from ..result import OverlapResult
from . import batch
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


def systems(plan, variants: Sequence, warn: bool = True) -> Optional[batch.Curves]:
    """G of each system in ``variants`` under the mixture ``plan``, every component of every variant
    in one batched core call, then each variant's components summed with its power shares (in the
    order :func:`combine` sums them, so that G is bit for bit a single run's); None where the
    components cannot share a call (not all batched ray tracing on the same options)."""
    if not plan.parts:
        return None
    first = plan.parts[0].options
    if not all(
        p.batched
        and (p.options.tolerance, p.options.max_segments, p.options.threads)
        == (first.tolerance, first.max_segments, first.threads)
        for p in plan.parts
    ):
        return None
    split = [plan.with_system(s).system.incoherent_parts for s in variants]
    n = len(plan.parts)
    component = plan.component_plans()[0]
    flat = batch.systems(component, [part for parts in split for _, part in parts], warn)
    shape = (len(variants), n, plan.ranges.size)
    g, e = flat.overlap.reshape(shape), flat.error_estimate.reshape(shape)
    overlap = np.empty((len(variants), plan.ranges.size))
    error = np.empty_like(overlap)
    for v, parts in enumerate(split):
        overlap[v] = sum(w * g[v, i] for i, (w, _) in enumerate(parts))
        error[v] = sum(w * e[v, i] for i, (w, _) in enumerate(parts))
    return batch.Curves(overlap, error, np.asarray(flat.converged.reshape(shape).all(axis=1)))
