"""The :class:`Plan`: one overlap computation, decided (its system, ranges, backend, options and
the error it will state), and how it is re-targeted (:meth:`Plan.with_system`, :meth:`Plan.at`) or
checked before it runs (:func:`check`: a plan edited by hand for a system of another kind is
refused)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Optional, Tuple

import numpy as np

from .. import _checks, _core, _values
from .._pickling import same_value
from .._values import frozen
from ..model.mixture_beam import GaussianMixtureBeam
from ..model.system import GaussianBeam, LidarSystem
from . import auto
from .backends import BACKENDS, Backend, backend
from .methods import FO, RT, Auto, Method, Turbulent

#: The plan's scalar fields and their kinds (NaN: no tolerance stated, or no model error estimate).
_SCALARS = {
    "tolerance": _values.real(low=0.0, nan=True),
    "rt_model_error": _values.real(low=0.0, nan=True),
    "rt_diffraction_warning": _values.flag,
}


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
    # Set by lidar_overlap.plan and kept by the plan's own methods; dataclasses.replace and
    # Plan(...) cannot set it (init=False), so a plan edited or built by hand is refused when it
    # runs.
    _decided: bool = dataclasses.field(default=False, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        """Every field checked, so that a plan edited with ``dataclasses.replace`` is refused by
        name rather than failing inside a backend; the ranges kept read-only."""
        for name, value in (("system", self.system), ("planned_on", self.planned_on)):
            if not isinstance(value, LidarSystem) and not (name == "planned_on" and value is None):
                raise ValueError(
                    f"{name} = {_checks.shown(value)} is invalid: expected a LidarSystem"
                )
        object.__setattr__(self, "ranges", frozen(_checks.ranges("ranges", self.ranges)))
        self.system._native.validate_ranges(self.ranges)  # > 0, beyond the obstruction distance
        if not isinstance(self.request, (RT, FO, Auto, Turbulent)):
            raise ValueError(
                f"request = {_checks.shown(self.request)} is invalid: expected an RT, FO, Auto or "
                "Turbulent method"
            )
        _checks.choice("backend", self.backend, tuple(BACKENDS))
        if type(self.options).__module__ != _core.__name__:
            raise ValueError(
                f"options = {_checks.shown(self.options)} is invalid: expected the core's options "
                "of the plan's backend (plans are made by lidar_overlap.plan)"
            )
        _values.check(self, _SCALARS)
        for name in ("reasons", "warnings"):
            value = getattr(self, name)
            if not isinstance(value, tuple) or not all(isinstance(t, str) for t in value):
                raise ValueError(
                    f"{name} = {_checks.shown(value)} is invalid: expected a tuple of texts"
                )
        if not isinstance(self.parts, tuple) or not all(isinstance(q, Plan) for q in self.parts):
            raise ValueError(
                f"parts = {_checks.shown(self.parts)} is invalid: expected a tuple of plans"
            )

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return all(
            _same_options(a, b) if f.name == "options" else same_value(a, b)
            for f in dataclasses.fields(self)
            if f.compare
            for a, b in [(getattr(self, f.name), getattr(other, f.name))]
        )

    __hash__ = None  # type: ignore[assignment]  # holds arrays

    def __reduce__(self):
        # The core's option objects do not pickle: they travel as their type and attributes.
        state = {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.init}
        options = state.pop("options")
        return _rebuild_plan, (
            state,
            type(options).__name__,
            _option_values(options),
            self._decided,
        )

    def _derived(self, **changes) -> "Plan":
        """A copy with ``changes`` made by one of the plan's own methods: decided if this one is."""
        q = dataclasses.replace(self, **changes)
        object.__setattr__(q, "_decided", self._decided)
        return q

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
                part = part._derived(ranges=self.ranges)
            out.append(part._derived(system=system))
        return tuple(out)

    def subset(self, index) -> "Plan":
        """The same plan (same decisions, same estimates) on ``ranges[index]`` (a slice): to run a
        long curve in parts."""
        if not isinstance(index, slice) or self.ranges[index].size == 0:
            raise ValueError(
                f"index = {_checks.shown(index)} is invalid: expected a slice that selects at "
                f"least one of the plan's {self.ranges.size} ranges"
            )
        return self._derived(
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
            return self._derived(ranges=z, rt_model_error=error, parts=parts)
        return self._derived(ranges=z, rt_model_error=error)

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
            return self._derived(system=system, parts=parts)
        return self._derived(system=system)

    def __str__(self) -> str:
        model = self.request.method if isinstance(self.request, Turbulent) else self.request
        head = ("auto: " if isinstance(model, Auto) else "plan: ") + BACKENDS[
            self.backend
        ].description
        return "\n".join([head] + [f"  - {r}" for r in self.reasons])


def decided(p: Plan) -> Plan:
    """``p`` marked as made by :func:`lidar_overlap.plan`: its decisions hold for its system and
    request."""
    object.__setattr__(p, "_decided", True)
    return p


def check(p: Plan) -> Plan:
    """``p`` if it was made by :func:`lidar_overlap.plan` or re-targeted by its own methods
    (:meth:`Plan.with_system`, :meth:`Plan.at`, :meth:`Plan.subset`); a ValueError otherwise: a
    plan edited with ``dataclasses.replace`` or built with ``Plan(...)`` may hold a system, ranges
    or a request its decisions were not made for, whatever its ``planned_on`` says."""
    if not p._decided:
        raise ValueError(
            "plan is invalid: it was built or edited by hand (Plan(...) or "
            "dataclasses.replace), so its decisions may not hold for its system, ranges and "
            "request; make it with lidar_overlap.plan(system, ranges, method), and move it with "
            "Plan.with_system or Plan.at"
        )
    if p.planned_on is not None:
        change = kind_change(p.planned_on, p.system)
        if change:  # a decided plan always passes; kept as a guard of the methods above
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


def _option_values(options) -> dict:
    """The settable attributes of one of the core's option objects."""
    return {
        name: getattr(options, name)
        for name in dir(options)
        if not name.startswith("_") and not callable(getattr(options, name))
    }


def _same_options(a, b) -> bool:
    return type(a) is type(b) and _option_values(a) == _option_values(b)


def _rebuild_plan(state: dict, options_type: str, values: dict, was_decided: bool) -> Plan:
    """A pickled :class:`Plan`: its core options made again from their attributes, the plan
    checked again by its constructor, decided if the pickled one was."""
    options = getattr(_core, options_type)()
    for name, value in values.items():
        setattr(options, name, value)
    p = Plan(options=options, **state)
    return decided(p) if was_decided else p
