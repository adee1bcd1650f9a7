"""Aperture masks (the telecover test): ray tracing or Fourier optics through the masked aperture,
one core call for all ranges; the RT plans of one system through several masks (a telecover test's
sectors) in one call."""

from __future__ import annotations

import dataclasses

import numpy as np

from ... import _core
from ..validity import warn_if_rt_invalid, warn_if_rt_unconverged
from ._result import result

#: Nominal accuracy of the masked FO path: the mask's edges are sampled (8 x 8 sub-samples per edge
#: pixel) and,
#: unlike the aperture's, not cancelled by the full-aperture OTF; G moved by 4e-5 from tail_error
#: 1e-4 to 1e-5
#: (Table 1, a quadrant, 200-1000 m).
FO_MASKED_ACCURACY = 1e-4


def run(plan):
    """G through ``plan.system.telescope.mask``, normalised to the full aperture; warns as plain ray
    tracing."""
    mask = plan.system.telescope.mask
    raw = _core.overlap_rt_masked(plan.system._native, plan.ranges, mask._native, plan.options)
    warn_if_rt_invalid(plan.system, plan.ranges, diffraction=plan.rt_diffraction_warning)
    warn_if_rt_unconverged(
        raw, plan.ranges, plan.rt_quadrature_tolerance, "raise max_segments or loosen tolerance"
    )
    return result(plan, raw.overlap, raw.error_estimate + plan.rt_model_error)


def run_fo(plan):
    """G by Fourier optics through the sampled pupil cut to the mask: G_0 (exact, full aperture)
    plus the Parseval sum of the OTF's change."""
    mask = plan.system.telescope.mask
    raw = _core.overlap_fo_masked(plan.system._native, plan.ranges, mask._native, plan.options)
    return result(plan, raw.overlap, FO_MASKED_ACCURACY)


def together(plans) -> bool:
    """Whether ``plans`` are ray tracing of one system, ranges and options through different masks:
    what :func:`run_together` takes."""
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


def _options(plan) -> tuple:
    return plan.options.tolerance, plan.options.max_segments, plan.options.threads


def _unmasked(system):
    return dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, mask=None))


def run_together(plans) -> list:
    """:func:`run` of each plan (see :func:`together`), in one core call: the masks share the beam
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
