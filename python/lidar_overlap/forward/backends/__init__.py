"""The code that computes a :class:`lidar_overlap.forward.planning.Plan`: one module per family of
paths, each runner taking a plan and returning an :class:`OverlapResult`, and :mod:`.many` for one
plan over many variants (systems, masks, alignment grids). These modules are the only callers of
the core's compute functions; none calls a public entry point or plans anything.

:data:`BACKENDS` is the one registry: each backend's key (what a plan names), what it computes, the
model (``"rt"`` or ``"fo"``) and Fourier-optics path it stands for, and its runner.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

from ... import _checks
from ..result import OverlapResult
from . import aberrated, fo, masked, mixture, rt, turbulent


@dataclass(frozen=True)
class Backend:
    """One way to compute G: ``description`` (for plans), ``model`` (``"rt"`` or ``"fo"``),
    ``fo_path`` (``""`` for RT), ``error_kind`` of the results, ``turbulent`` (draws of the
    atmosphere), and ``run`` (plan -> result; None where the plan is resolved first)."""

    description: str
    model: str
    fo_path: str
    error_kind: str
    turbulent: bool
    run: Optional[Callable]


BACKENDS = {
    "rt": Backend("ray tracing", "rt", "", "bound", False, rt.run),
    "rt_aberrated": Backend(
        "ray tracing through the aberrated pupil", "rt", "", "bound", False, aberrated.run_rt
    ),
    "rt_masked": Backend(
        "ray tracing through the aperture mask", "rt", "", "bound", False, masked.run
    ),
    "fo_masked": Backend(
        "Fourier optics through the aperture mask (sampled pupil)",
        "fo",
        "masked",
        "nominal",
        False,
        masked.run_fo,
    ),
    "fo_radial": Backend(
        "Fourier optics (radial path)", "fo", "radial", "nominal", False, fo.run_radial
    ),
    "fo_2d": Backend("Fourier optics (2d path)", "fo", "2d", "nominal", False, fo.run_2d),
    "fo_field": Backend(
        "Fourier optics (2d path, the field's own grid)", "fo", "2d", "nominal", False, fo.run_field
    ),
    "fo_aberrated": Backend(
        "Fourier optics (aberrated path)", "fo", "aberrated", "nominal", False, aberrated.run_fo
    ),
    "auto_aberrated": Backend(
        "auto through the aberrated pupil: ray tracing or Fourier optics, decided when run",
        "auto",
        "",
        "bound",
        False,
        None,
    ),
    "rt_mixture": Backend(
        "ray tracing of each incoherent beam component, G their power-weighted sum",
        "rt",
        "",
        "bound",
        False,
        lambda plan: _run_mixture(plan),
    ),
    "fo_mixture": Backend(
        "Fourier optics of each incoherent beam component, G their power-weighted sum",
        "fo",
        "mixture",
        "nominal",
        False,
        lambda plan: _run_mixture(plan),
    ),
    "auto_mixture": Backend(
        "auto for each incoherent beam component (with aberrations: decided when run), G their "
        "power-weighted sum",
        "auto",
        "",
        "bound",
        False,
        None,
    ),
    "rt_turbulent": Backend(
        "ray tracing of the wandering short-term beam (all draws in one core call)",
        "rt",
        "",
        "standard_error",
        True,
        turbulent.run_rt,
    ),
    "fo_turbulent": Backend(
        "Fourier optics through phase screens", "fo", "2d", "standard_error", True, turbulent.run_fo
    ),
}


def backend(key: str) -> Backend:
    """The registry entry of ``key``; a key no plan makes is refused by name."""
    if key not in BACKENDS:  # a Plan built by hand
        raise ValueError(
            f"plan.backend = {_checks.shown(key)} is invalid: expected one of "
            f"{', '.join(map(repr, BACKENDS))} (make plans with lidar_overlap.plan)"
        )
    return BACKENDS[key]


def run(plan) -> OverlapResult:
    """Compute ``plan`` (resolved: see :func:`lidar_overlap.forward.planning.resolve`): its
    warnings, then its backend (a turbulent plan along a path without turbulence runs the plain
    backend and repeats its curve for every draw)."""
    entry = backend(plan.backend)
    if entry.run is None:
        raise ValueError(
            f"plan.backend = {plan.backend!r} is decided when the plan runs: pass the plan to "
            "lidar_overlap.run"
        )
    for message in plan.warnings:
        _checks.warn(message)
    result = entry.run(plan)
    if plan.turbulence is not None and not entry.turbulent:
        return turbulent.without_turbulence(plan, result)
    return result


def _run_mixture(plan) -> OverlapResult:
    """A mixture plan: each component's plan run (its own warnings said), then combined."""
    return mixture.combine(plan, [run(part) for part in plan.component_plans()])
