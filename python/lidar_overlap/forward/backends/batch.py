"""The core's calls for many variants of one ray-tracing plan: systems paired with ranges (one
batched call), masks (the sectors of a telecover test, one call sharing the beam integral's nodes)
and alignment grids (one call). The only callers of those core functions; each says the validity
and convergence warnings once, for all its variants (:mod:`.many` is the runner built on them)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ... import _core
from ..validity import warn_if_rt_invalid, warn_if_rt_unconverged
from ._result import result


@dataclass(frozen=True)
class Curves:
    """G of many variants: ``overlap`` and ``error_estimate`` shaped (variants..., ranges) (or flat
    for pairs), ``converged`` the quadrature's flags (all True where the backend has none)."""

    overlap: np.ndarray
    error_estimate: np.ndarray
    converged: np.ndarray


def pairs(plan, natives: Sequence, ranges, warn: bool = True) -> Curves:
    """Ray tracing of the core system ``natives[i]`` (a ``LidarSystem._native``) at ``ranges[i]``
    (m) on ``plan``'s options, in one core call (flat arrays). ``warn=False`` leaves the warnings
    to the caller (rows gathered from several calls): :func:`warn_rt` with the flags."""
    raw = _core.overlap_rt_batch(list(natives), np.asarray(ranges, dtype=float), plan.options)
    curves = Curves(
        np.asarray(raw.overlap),
        np.asarray(raw.error_estimate) + plan.rt_model_error,
        np.asarray(raw.converged, dtype=bool),
    )
    if warn:
        warn_rt(plan, curves.converged, np.asarray(raw.error_estimate), ranges)
    return curves


def systems(plan, variants: Sequence, warn: bool = True) -> Curves:
    """G of each system in ``variants`` (of the kind ``plan.system`` is) at ``plan.ranges`` by
    plain ray tracing, every variant in one batched core call: shape (len(variants), ranges).
    ``warn=False`` keeps the validity and convergence warnings back."""
    z = plan.ranges
    for s in variants:
        plan.with_system(s)  # the same kind of system, or refused naming what changed
    natives = [s._native for s in variants for _ in z]
    flat = pairs(plan, natives, np.tile(z, len(variants)), warn=False)
    shape = (len(variants), z.size)
    if warn:
        warn_rt(plan, flat.converged, flat.error_estimate, np.tile(z, len(variants)))
    return Curves(
        flat.overlap.reshape(shape),
        flat.error_estimate.reshape(shape),
        flat.converged.reshape(shape),
    )


def warn_rt(plan, converged, error_estimate, ranges) -> None:
    """RT's validity warnings for the plan's system, and its convergence warning over all the
    variants' flags (``ranges``: each flag's range)."""
    warn_if_rt_invalid(plan.system, plan.ranges, diffraction=plan.rt_diffraction_warning)
    flags = _Flags(np.asarray(converged, dtype=bool), np.asarray(error_estimate))
    warn_if_rt_unconverged(
        flags,
        np.asarray(ranges),
        plan.rt_quadrature_tolerance,
        "raise max_segments or loosen tolerance",
    )


def grid(plan, axes) -> Curves:
    """G over an alignment grid: ``axes`` is [(name, values)] of one or two misalignment axes of
    the core's alignment map (values added to the system's own), shape (axes..., ranges); one
    parallel core call."""
    raw = _core.alignment_map(plan.system._native, axes, plan.ranges, plan.options)
    warn_if_rt_invalid(plan.system, plan.ranges, diffraction=plan.rt_diffraction_warning)
    warn_if_rt_unconverged(
        raw, plan.ranges, plan.rt_quadrature_tolerance, "raise max_segments or loosen tolerance"
    )
    converged = np.broadcast_to(np.asarray(raw.converged, dtype=bool), np.shape(raw.overlap))
    return Curves(np.asarray(raw.overlap), np.asarray(raw.error_estimate), converged)


def one_call(plans) -> bool:
    """Whether ``plans`` are ray tracing of one system, ranges and options through different
    masks: what :func:`through_masks` takes."""
    first = plans[0]
    return all(
        p.backend == "rt_masked"
        and _options(p) == _options(first)
        and np.array_equal(p.ranges, first.ranges)
        and p.rt_model_error == first.rt_model_error
        and p.tolerance == first.tolerance
        and p.rt_diffraction_warning == first.rt_diffraction_warning
        and _unmasked(p.system) == _unmasked(first.system)
        for p in plans
    )


def through_masks(plans) -> list:
    """The result of each plan of :func:`one_call`, in one core call: the masks share the beam
    integral's nodes (each G to the plans' tolerance, not bit for bit the one-mask call). The
    validity warnings, the same for every mask, are given once."""
    first = plans[0]
    raws = _core.overlap_rt_masks(
        first.system._native,
        first.ranges,
        [p.system.telescope.mask._native for p in plans],
        first.options,
    )
    warn_if_rt_invalid(first.system, first.ranges, diffraction=first.rt_diffraction_warning)
    for raw in raws:
        warn_if_rt_unconverged(
            raw,
            first.ranges,
            first.rt_quadrature_tolerance,
            "raise max_segments or loosen tolerance",
        )
    return [
        result(p, raw.overlap, raw.error_estimate + p.rt_model_error) for p, raw in zip(plans, raws)
    ]


@dataclass(frozen=True)
class _Flags:
    converged: np.ndarray
    error_estimate: np.ndarray


def _options(plan) -> tuple:
    return plan.options.tolerance, plan.options.max_segments, plan.options.threads


def _unmasked(system):
    return dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, mask=None))
