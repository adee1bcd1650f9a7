"""Ray tracing through an aperture mask (the telecover test): one core call for all ranges."""

from __future__ import annotations

from .. import _core
from ..validity import warn_if_rt_invalid, warn_if_rt_unconverged
from ._result import result


def run(plan):
    """G through ``plan.system.telescope.mask``, normalised to the full aperture; warns as plain ray tracing."""
    mask = plan.system.telescope.mask
    raw = _core.overlap_rt_masked(plan.system._native, plan.ranges, mask._native, plan.options)
    warn_if_rt_invalid(plan.system, plan.ranges, diffraction=plan.rt_diffraction_warning)
    warn_if_rt_unconverged(raw, plan.ranges, plan.rt_quadrature_tolerance, "raise max_segments or loosen tolerance")
    return result(plan, raw.overlap, raw.error_estimate + plan.rt_model_error)
