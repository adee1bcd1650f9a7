"""Aperture masks (the telecover test): ray tracing or Fourier optics through the masked aperture,
one core call for all ranges (the sectors of one system in one call: :mod:`.batch`)."""

from __future__ import annotations

from ... import _core
from ..validity import warn_if_rt_invalid, warn_if_rt_unconverged
from ._result import result

#: Nominal accuracy of the masked FO path: the mask's edges are sampled (8 x 8 sub-samples per edge
#: pixel) and, unlike the aperture's, not cancelled by the full-aperture OTF; G moved by 4e-5 from
#: tail_error 1e-4 to 1e-5 (Table 1, a quadrant, 200-1000 m).
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
