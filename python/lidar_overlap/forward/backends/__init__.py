"""The code that computes a :class:`lidar_overlap.forward.planning.Plan`: one module per family of
paths, each function taking a plan and returning an :class:`OverlapResult`. None calls a public
entry point or plans anything."""

from __future__ import annotations

from ... import _checks
from ..result import OverlapResult
from . import aberrated, fo, masked, rt, turbulent

RUNNERS = {
    "rt": rt.run,
    "rt_aberrated": aberrated.run_rt,
    "rt_masked": masked.run,
    "fo_masked": masked.run_fo,
    "fo_radial": fo.run_radial,
    "fo_2d": fo.run_2d,
    "fo_field": fo.run_field,
    "fo_aberrated": aberrated.run_fo,
    "rt_turbulent": turbulent.run_rt,
    "fo_turbulent": turbulent.run_fo,
}


def run(plan) -> OverlapResult:
    """Compute ``plan``: its warnings, then its backend (a turbulent plan along a path without
    turbulence runs the plain backend and repeats its curve for every draw)."""
    if plan.backend not in RUNNERS:  # a Plan built by hand
        raise ValueError(
            f"plan.backend = {_checks.shown(plan.backend)} is invalid: expected one of "
            f"{', '.join(map(repr, RUNNERS))} (make plans with lidar_overlap.plan)"
        )
    for message in plan.warnings:
        _checks.warn(message)
    result = RUNNERS[plan.backend](plan)
    if plan.turbulence is not None and plan.backend not in ("rt_turbulent", "fo_turbulent"):
        return turbulent.without_turbulence(plan, result)
    return result
