"""Ray tracing (paper Appendix B) of a plan: one core call for all ranges."""

from __future__ import annotations

from ... import _core
from ..validity import warn_if_rt_invalid, warn_if_rt_unconverged
from ._result import result


def run(plan):
    """G by ray tracing; the error estimate is the quadrature's plus the model error auto estimated
    (if any). Warns where ray tracing is outside its validity (not about diffraction auto has
    bounded) or the quadrature stopped short of its tolerance."""
    raw = _core.overlap_rt(plan.system._native, plan.ranges, plan.options)
    warn_if_rt_invalid(plan.system, plan.ranges, diffraction=plan.rt_diffraction_warning)
    warn_if_rt_unconverged(
        raw, plan.ranges, plan.rt_quadrature_tolerance, "raise max_segments or loosen tolerance"
    )
    return result(plan, raw.overlap, raw.error_estimate + plan.rt_model_error)
