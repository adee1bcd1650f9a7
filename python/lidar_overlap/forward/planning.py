"""Plan, then run: what one overlap computation will do, decided before anything is computed.

:func:`plan` turns (system, ranges, method) into a :class:`Plan`: the checked inputs, the backend
that will compute G (ray tracing, radial / 2-D / field / aberrated Fourier optics, their masked and
turbulent forms), the core's options for it, and the error the result will state. It computes no
overlap: auto's estimate for a plain receiver comes from the geometry (~50 µs); for a receiver with
aberrations it needs two coarse RT curves, so that plan says it decides when it runs
(:func:`resolve`, called by :func:`lidar_overlap.run`). :func:`explain` prints a plan.

A plan is re-targeted with :meth:`Plan.with_system` (its decisions kept, for a system of the same
kind) and :meth:`Plan.at` (other ranges): what fits, sensitivities and studies run many times.
"""

from __future__ import annotations

import dataclasses
from typing import Any, Dict

from .. import _checks
from ..model.mixture_beam import GaussianMixtureBeam
from ..model.system import LidarSystem
from . import auto
from .methods import Auto, Turbulent, from_shortcuts
from .planners import aberrated, fan_options, mixture, mixture_of, plain
from .plans import Plan, base_fields, check, decided
from .turbulent_planner import turbulent

__all__ = ["Plan", "check", "explain", "plan", "resolve"]


def plan(system: LidarSystem, ranges, method="rt", *, threads: int = 0, **shortcuts) -> Plan:
    """The :class:`Plan` of ``lo.overlap(system, ranges, method, threads=threads, **shortcuts)``:
    every input checked and every choice made, no overlap computed. ``method``: ``"rt"``, ``"fo"``,
    ``"auto"`` (with the shortcut options of :func:`lidar_overlap.overlap`) or an RT, FO, Auto or
    Turbulent object."""
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    request = from_shortcuts(method, **shortcuts)
    z = _checks.ranges("ranges", ranges)
    system._native.validate_ranges(z)  # before any path derives quantities from them
    threads = _checks.threads(threads)
    if isinstance(system.beam, GaussianMixtureBeam):
        if isinstance(request, Turbulent):
            raise ValueError(
                "turbulence with a GaussianMixtureBeam is not modelled: expected a GaussianBeam"
            )
        return decided(mixture(system, z, request, threads))
    if isinstance(request, Turbulent):
        return decided(turbulent(system, z, request, threads))
    return decided(plain(system, z, request, request, threads))


def explain(system, ranges, method="auto", *, threads: int = 0, **shortcuts) -> Plan:
    """Print and return the :class:`Plan` ``lo.overlap(system, ranges, method, **shortcuts)``
    follows, with the estimates behind it (``lo.explain(system, ranges, tolerance=1e-3)``: what auto
    does at that tolerance)."""
    p = plan(system, ranges, method, threads=threads, **shortcuts)
    print(p)
    return p


def resolve(p: Plan) -> Plan:
    """``p`` with every decision made: a plan that decides when it runs (auto with receiver
    aberrations) gets auto's choice, from two coarse RT curves (:func:`auto.decide_aberrated`); any
    other plan is returned as it is. The choice is decided as ``p`` is."""
    if not p.deferred:
        return p
    q = _resolved(p)
    return decided(q) if p._decided else q


def _resolved(p: Plan) -> Plan:
    if p.parts:
        parts = tuple(resolve(part) for part in p.parts)
        return mixture_of(p.system, p.ranges, p.request, parts, p.options.threads)
    model = p.request
    assert isinstance(
        model, Auto
    )  # the only deferred plans (turbulence with aberrations is refused)
    d = auto.decide_aberrated(p.system, p.ranges, model.tolerance, model.rt)
    common: Dict[str, Any] = dict(
        tolerance=model.tolerance,
        rt_model_error=d.rt_model_error,
        reasons=tuple(d.reasons),
        warnings=(f"overlap(auto): {d.warning}",) if d.warning else (),
    )
    if d.method == "rt":
        options = fan_options(model.rt, d.rt_quadrature_tolerance, p.options.threads)
        return dataclasses.replace(
            p, backend="rt_aberrated", options=options, rt_diffraction_warning=False, **common
        )
    fo = aberrated(
        base_fields(p.system, p.ranges, p.request), p.system, model.fo, p.options.threads
    )
    return dataclasses.replace(fo, **common)
