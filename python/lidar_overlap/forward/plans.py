"""The :class:`Plan`: one overlap computation, decided (its system, ranges, backend, options and
the error it will state), and how it is re-targeted (:meth:`Plan.with_system`, :meth:`Plan.at`) or
checked before it runs (:func:`check`: a plan edited by hand for a system of another kind is
refused)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Optional, Tuple

import numpy as np

from .. import _checks, _core
from ..model.mixture_beam import GaussianMixtureBeam
from ..model.system import GaussianBeam, LidarSystem
from . import auto
from .backends import BACKENDS, Backend, backend
from .methods import Auto, Method, Turbulent


@dataclass(frozen=True, eq=False)
class Plan:
    """One overlap computation, decided.

    system, ranges : what it computes (ranges in m, checked). request : the method asked for (an RT,
        FO, Auto or Turbulent object). backend : the code that runs, a key of
        :data:`~lidar_overlap.forward.backends.BACKENDS`; ``method``, ``fo_path`` and ``error_kind``
        follow from it. options : the core's options for it (``_core.RtOptions`` and its kin).
        tolerance : what the result states (NaN for plain FO). rt_model_error : auto's estimate of
        RT's diffraction error, added to RT's stated error (0 when not estimated, NaN where RT
        cannot model the beam). rt_diffraction_warning : whether ray tracing warns about diffraction
        (not where auto bounded it). reasons : why, one line each. warnings : said when the plan
        runs. planned_on : the system the decisions were made for; a plan whose ``system`` is of
        another kind is refused when it runs (re-target plans with :meth:`with_system`). parts :
        for a :class:`GaussianMixtureBeam`, the plan of each component (the system of
        ``system.incoherent_parts``), whose G the mixture backends add; () otherwise.
    """

    system: LidarSystem
    ranges: np.ndarray
    request: Method
    backend: str
    options: Any
    tolerance: float
    rt_model_error: float = 0.0
    rt_diffraction_warning: bool = True
    reasons: Tuple[str, ...] = ()
    warnings: Tuple[str, ...] = ()
    planned_on: Optional[LidarSystem] = None
    parts: Tuple["Plan", ...] = ()

    @property
    def method(self) -> str:
        """The model that computes G: ``"rt"``, ``"fo"``, or ``"auto"`` while auto has not decided
        (a receiver with aberrations, decided when the plan runs)."""
        return backend(self.backend).model

    @property
    def fo_path(self) -> str:
        """``"radial"``, ``"2d"``, ``"aberrated"``, ``"masked"``, ``"mixture"`` (each component of a
        :class:`GaussianMixtureBeam` on its own path: see :meth:`component_plans`), or ``""`` for
        ray tracing."""
        return backend(self.backend).fo_path

    @property
    def error_kind(self) -> str:
        """What the result's error estimate is: ``"bound"`` (RT's quadrature bound plus auto's model
        error), ``"nominal"`` (FO: the path's measured accuracy) or ``"standard_error"``
        (turbulence: of the mean over the draws)."""
        return backend(self.backend).error_kind

    @property
    def engine(self) -> Backend:
        """The :class:`~lidar_overlap.forward.backends.Backend` that runs this plan: what it models
        and how it runs (``plan.engine.masks``, ``.aberrations``, ``.turbulence``, ``.mixture``)."""
        return backend(self.backend)

    @property
    def batched(self) -> bool:
        """True when the plan is plain-receiver ray tracing, whose variants (systems, alignment
        grids) run in one parallel core call (:mod:`lidar_overlap.forward.backends.many`)."""
        return backend(self.backend).batched

    @property
    def plain_rt(self) -> bool:
        """True when G comes from ray tracing of the plain receiver (one beam, or each incoherent
        component), whose accuracy its quadrature tolerance sets."""
        return backend(self.backend).plain_rt

    @property
    def turbulence(self) -> Optional[Turbulent]:
        """The :class:`Turbulent` request, or None."""
        return self.request if isinstance(self.request, Turbulent) else None

    @property
    def rt_quadrature_tolerance(self) -> float:
        """The tolerance ray tracing's quadrature runs at (0 for Fourier optics)."""
        if isinstance(self.options, (_core.RtOptions, _core.RtAberratedOptions)):
            return float(self.options.tolerance)
        return 0.0

    @property
    def deferred(self) -> bool:
        """True when the model is chosen when the plan runs (:func:`resolve`)."""
        return backend(self.backend).run is None

    def component_plans(self) -> Tuple["Plan", ...]:
        """The plans of the beam's components on this plan's ranges and for its system's
        components (a plan re-ranged or re-targeted with :func:`dataclasses.replace` leaves its
        ``parts`` as they were: their decisions hold, their ranges and systems follow)."""
        out = []
        for part, (_, system) in zip(self.parts, self.system.incoherent_parts):
            if not np.array_equal(part.ranges, self.ranges):
                part = dataclasses.replace(part, ranges=self.ranges)
            out.append(dataclasses.replace(part, system=system))
        return tuple(out)

    def subset(self, index) -> "Plan":
        """The same plan (same decisions, same estimates) on ``ranges[index]`` (a slice): to run a
        long curve in parts."""
        if not isinstance(index, slice) or self.ranges[index].size == 0:
            raise ValueError(
                f"index = {_checks.shown(index)} is invalid: expected a slice that selects at "
                f"least one of the plan's {self.ranges.size} ranges"
            )
        return dataclasses.replace(
            self,
            ranges=self.ranges[index],
            parts=tuple(p.subset(index) for p in self.parts),
        )

    def at(self, ranges) -> "Plan":
        """The same decisions at other ``ranges`` (m, checked as :func:`plan` checks them). Where
        auto chose ray tracing, its model error is estimated again for the new ranges (geometry
        only) and the quadrature keeps its tolerance. The one way a plan moves to other ranges: a
        plan rebuilt with ``dataclasses.replace(plan, ranges=...)`` keeps the model error of its
        old ranges."""
        z = _checks.ranges("ranges", ranges)
        self.system._native.validate_ranges(z)
        error = self.rt_model_error
        if error > 0.0 and self.engine.geometric_rt:
            error = auto.rt_model_error(self.system, z)
        if self.parts:
            parts = tuple(p.at(z) for p in self.parts)
            error = power_weighted(self.system, [p.rt_model_error for p in parts])
            return dataclasses.replace(self, ranges=z, rt_model_error=error, parts=parts)
        return dataclasses.replace(self, ranges=z, rt_model_error=error)

    def with_system(self, system) -> "Plan":
        """The same decisions for another ``system`` of the same kind (the same beam type and width
        law, aperture mask, and presence of receiver aberrations and of field-dependent ones): a
        shifted, misaligned or fitted variant. A system of another kind is refused, naming what
        changed: its plan needs other decisions (``lo.plan`` makes them)."""
        if not isinstance(system, LidarSystem):
            raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
        change = kind_change(self.system, system)
        if change:
            raise ValueError(
                f"Plan.with_system: {change}, so this plan ({BACKENDS[self.backend].description}) "
                "does not describe it; make its own plan with lidar_overlap.plan(system, ranges, "
                "method)"
            )
        system._native.validate_ranges(self.ranges)
        if self.parts:
            parts = tuple(
                p.with_system(s) for p, (_, s) in zip(self.parts, system.incoherent_parts)
            )
            return dataclasses.replace(self, system=system, parts=parts)
        return dataclasses.replace(self, system=system)

    def __str__(self) -> str:
        model = self.request.method if isinstance(self.request, Turbulent) else self.request
        head = ("auto: " if isinstance(model, Auto) else "plan: ") + BACKENDS[
            self.backend
        ].description
        return "\n".join([head] + [f"  - {r}" for r in self.reasons])


def check(p: Plan) -> Plan:
    """``p`` if its system is of the kind its decisions were made for; a ValueError naming what
    changed otherwise (a plan edited by hand, say with ``dataclasses.replace``)."""
    if p.planned_on is not None:
        change = kind_change(p.planned_on, p.system)
        if change:
            raise ValueError(
                f"plan.system: {change}, so the plan ({BACKENDS[p.backend].description}) does not "
                "describe it; re-target a plan with Plan.with_system, or make one with "
                "lidar_overlap.plan(system, ranges, method)"
            )
    return p


def power_weighted(system, values) -> float:
    """Σ w_i v_i over the power shares of ``system``'s incoherent parts."""
    return float(sum(w * v for (w, _), v in zip(system.incoherent_parts, values)))


def base_fields(system, z, request) -> dict:
    return dict(system=system, ranges=z, request=request, planned_on=system)


def kind_change(old: LidarSystem, new: LidarSystem) -> str:
    """What makes ``new`` a system of another kind than ``old`` for a plan, or '' if nothing."""
    if type(new.beam) is not type(old.beam):
        return f"the beam is a {type(new.beam).__name__}, the plan's a {type(old.beam).__name__}"
    if isinstance(old.beam, GaussianMixtureBeam) and isinstance(new.beam, GaussianMixtureBeam):
        if len(new.beam.components) != len(old.beam.components):
            return (
                f"the beam has {len(new.beam.components)} components, the plan's "
                f"{len(old.beam.components)}"
            )
    gaussian = (GaussianBeam, GaussianMixtureBeam)
    if isinstance(old.beam, gaussian) and isinstance(new.beam, gaussian):
        if new.beam.width_law != old.beam.width_law:
            return f"beam.width_law is {new.beam.width_law!r}, the plan's {old.beam.width_law!r}"
    if new.telescope.mask != old.telescope.mask:
        return "telescope.mask differs from the plan's system's"
    if new.aberrated != old.aberrated:
        has = "has" if new.aberrated else "has no"
        return f"the receiver {has} aberrations, unlike the plan's system"
    new_ab, old_ab = new.telescope.aberrations, old.telescope.aberrations
    if new.aberrated and new_ab is not None and old_ab is not None:
        if new_ab.field_dependent != old_ab.field_dependent:
            return "telescope.aberrations differ in field-dependent Seidel terms from the plan's"
    return ""
