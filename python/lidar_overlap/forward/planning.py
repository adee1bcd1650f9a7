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
from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

import numpy as np

from .. import _checks, _core
from ..model.field_beam import FieldBeam
from ..model.mixture_beam import GaussianMixtureBeam
from ..model.system import GaussianBeam, LidarSystem
from . import auto
from .backends import BACKENDS, backend
from .methods import FO, RT, Auto, Method, Turbulent, from_shortcuts

#: The 2-D path of the turbulent FO overlap needs this many samples per side at least.
MIN_TURBULENT_GRID = 32


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
        return dataclasses.replace(
            self,
            ranges=self.ranges[index],
            parts=tuple(p.subset(index) for p in self.parts),
        )

    def at(self, ranges) -> "Plan":
        """The same decisions at other ``ranges`` (m, checked as :func:`plan` checks them). Where
        auto chose ray tracing, its model error is estimated again for the new ranges (geometry
        only) and the quadrature keeps its tolerance."""
        z = _checks.ranges("ranges", ranges)
        self.system._native.validate_ranges(z)
        error = self.rt_model_error
        if error > 0.0 and self.backend in ("rt", "rt_masked"):
            error = auto.rt_model_error(self.system, z)
        if self.parts:
            parts = tuple(p.at(z) for p in self.parts)
            error = _weighted(self.system, [p.rt_model_error for p in parts])
            return dataclasses.replace(self, ranges=z, rt_model_error=error, parts=parts)
        return dataclasses.replace(self, ranges=z, rt_model_error=error)

    def with_system(self, system) -> "Plan":
        """The same decisions for another ``system`` of the same kind (the same beam type and width
        law, aperture mask, and presence of receiver aberrations and of field-dependent ones): a
        shifted, misaligned or fitted variant. A system of another kind is refused, naming what
        changed: its plan needs other decisions (``lo.plan`` makes them)."""
        if not isinstance(system, LidarSystem):
            raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
        change = _kind_change(self.system, system)
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
        return _mixture(system, z, request, threads)
    if isinstance(request, Turbulent):
        return _turbulent(system, z, request, threads)
    return _plain(system, z, request, request, threads)


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
    other plan is returned as it is."""
    if not p.deferred:
        return p
    if p.parts:
        parts = tuple(resolve(part) for part in p.parts)
        return _mixture_of(p.system, p.ranges, p.request, parts, p.options.threads)
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
        options = _fan_options(model.rt, d.rt_quadrature_tolerance, p.options.threads)
        return dataclasses.replace(
            p, backend="rt_aberrated", options=options, rt_diffraction_warning=False, **common
        )
    fo = _aberrated(_base(p.system, p.ranges, p.request), p.system, model.fo, p.options.threads)
    return dataclasses.replace(fo, **common)


def _mixture(system, z, request, threads) -> Plan:
    """A :class:`GaussianMixtureBeam`: each component planned as a :class:`GaussianBeam` in this
    receiver (its own backend, auto's choice and error estimate), G their power-weighted sum."""
    parts = tuple(_plain(s, z, request, request, threads) for _, s in system.incoherent_parts)
    return _mixture_of(system, z, request, parts, threads)


def _mixture_of(system, z, request, parts, threads) -> Plan:
    """The mixture plan of the components' ``parts``. Auto may choose ray tracing for one component
    and Fourier optics for another; then every component runs Fourier optics at auto's tolerance, so
    that the curve is of one model."""
    n = len(parts)
    head = f"{n} incoherent Gaussian component{'s' if n > 1 else ''}, G = Σ w_i G_i"
    if any(p.deferred for p in parts):
        return Plan(
            **_base(system, z, request),
            backend="auto_mixture",
            tolerance=parts[0].tolerance,
            options=parts[0].options,
            reasons=(head + "; auto decides for each component when the plan runs",),
            parts=parts,
        )
    if len({p.method for p in parts}) > 1 and isinstance(request, Auto):
        parts = tuple(
            dataclasses.replace(
                _plain(p.system, z, request.fo, request, threads),
                tolerance=request.tolerance,
                reasons=("auto: Fourier optics, as for another component of the beam",),
            )
            for p in parts
        )
    key = "rt_mixture" if parts[0].method == "rt" else "fo_mixture"
    shares = [w for w, _ in system.incoherent_parts]
    return Plan(
        **_base(system, z, request),
        backend=key,
        tolerance=parts[0].tolerance,
        options=parts[0].options,
        rt_model_error=_weighted(system, [p.rt_model_error for p in parts]),
        rt_diffraction_warning=all(p.rt_diffraction_warning for p in parts),
        reasons=(head,)
        + tuple(
            f"component {i} (power share {w:.3g}): {p.reasons[0] if p.reasons else p.backend}"
            for i, (w, p) in enumerate(zip(shares, parts))
        ),
        parts=parts,
    )


def _weighted(system, values) -> float:
    """Σ w_i v_i over the power shares of ``system``'s incoherent parts."""
    return float(sum(w * v for (w, _), v in zip(system.incoherent_parts, values)))


def _base(system, z, request) -> dict:
    return dict(system=system, ranges=z, request=request, planned_on=system)


def check(p: Plan) -> Plan:
    """``p`` if its system is of the kind its decisions were made for; a ValueError naming what
    changed otherwise (a plan edited by hand, say with ``dataclasses.replace``)."""
    if p.planned_on is not None:
        change = _kind_change(p.planned_on, p.system)
        if change:
            raise ValueError(
                f"plan.system: {change}, so the plan ({BACKENDS[p.backend].description}) does not "
                "describe it; re-target a plan with Plan.with_system, or make one with "
                "lidar_overlap.plan(system, ranges, method)"
            )
    return p


def _plain(system, z, model, request, threads) -> Plan:
    """The plan of ``model`` (RT, FO or Auto) without turbulence; ``request`` is what the caller
    asked for."""
    base = _base(system, z, request)
    if system.telescope.mask is not None:
        return _masked(base, system, z, model, threads)
    if system.aberrated and system.detector.stop_radius is not None:
        raise ValueError(
            "detector.stop_radius with receiver aberrations is not modelled: set "
            "telescope.aberrations or detector.stop_radius to None"
        )
    if system.aberrated:
        if isinstance(system.beam, FieldBeam):
            raise ValueError(
                "aberrations with a FieldBeam are not modelled: expected a GaussianBeam (the "
                "aberrated paths weight the point image by the Gaussian beam image)"
            )
        return _aberrated(base, system, model, threads)
    field_beam = isinstance(system.beam, FieldBeam)
    if isinstance(model, Auto):
        d = auto.decide(system, z, model.tolerance)
        common: Dict[str, Any] = dict(
            base, tolerance=model.tolerance, rt_model_error=d.rt_model_error
        )
        if d.method == "rt":
            options = _rt_options(model.rt, d.rt_quadrature_tolerance, threads)
            return _auto_rt(common, "rt", options, d)
        fo = _fo(base, system, _auto_fo(model.fo, d.fo_path, field_beam), threads, field_beam)
        return dataclasses.replace(fo, reasons=tuple(d.reasons), **common)
    if isinstance(model, RT):
        if field_beam:
            raise ValueError(
                f"method = 'rt' is invalid for a {type(system.beam).__name__}: ray tracing models "
                "Gaussian beams only; use method='fo'"
            )
        return Plan(
            **base,
            backend="rt",
            tolerance=model.tolerance,
            options=_rt_options(model, model.tolerance, threads),
            reasons=(f"ray tracing asked for, to {model.tolerance:g} on G",),
        )
    return _fo(base, system, model, threads, field_beam)


def _fo(base, system, model: FO, threads, field_beam) -> Plan:
    common: Dict[str, Any] = dict(base, tolerance=float("nan"))
    if field_beam:
        if model.beam_grid is not None or model.beam_window is not None:
            raise ValueError(
                "beam_grid and beam_window apply to Gaussian beams only: a FieldBeam is propagated "
                "on its own grid"
            )
        options = _core.FoOptions()
        options.max_spectrum_grid, options.threads = model.max_spectrum_grid, threads
        return Plan(
            **common,
            backend="fo_field",
            options=options,
            reasons=(f"Fourier optics on the {type(system.beam).__name__}'s own grid",),
        )
    if model.path == "radial" or (model.path == "auto" and auto.radial_fo_applies(system)):
        if model.beam_grid is not None or model.beam_window is not None:
            raise ValueError(
                "beam_grid and beam_window apply to the 2-D FO path only; use fo_path='2d'"
            )
        radial = _core.RadialFoOptions()
        radial.threads = threads
        return Plan(
            **common,
            backend="fo_radial",
            options=radial,
            reasons=("Gaussian beam: Fourier optics on the radial path (one integral per range)",),
        )
    options = _core.FoOptions()
    if model.beam_grid is not None:
        options.beam_grid = model.beam_grid
    if model.beam_window is not None:
        options.beam_window = model.beam_window
    options.max_spectrum_grid, options.threads = model.max_spectrum_grid, threads
    return Plan(
        **common,
        backend="fo_2d",
        options=options,
        reasons=(
            f"Fourier optics on the 2d path: the beam sampled on {options.beam_grid}^2 over "
            f"{options.beam_window:g} waist radii",
        ),
    )


def _masked(base, system, z, model, threads) -> Plan:
    """An aperture mask (telecover): ray tracing with each scatterer's coupling restricted to the
    mask, or Fourier optics through the sampled pupil cut to it; auto chooses by RT's diffraction
    estimate, as without a mask."""
    if system.aberrated:
        raise ValueError(
            "telescope.mask with aberrations is not modelled: set telescope.aberrations or "
            "telescope.mask to None"
        )
    if isinstance(system.beam, FieldBeam):
        raise ValueError(
            f"telescope.mask is invalid for a {type(system.beam).__name__}: the masked paths model "
            "Gaussian beams only"
        )
    names = ", ".join(system.telescope.mask.names)
    if isinstance(model, Auto):
        d = auto.decide(system, z, model.tolerance)
        common: Dict[str, Any] = dict(
            base, tolerance=model.tolerance, rt_model_error=d.rt_model_error
        )
        if d.method == "rt":
            options = _rt_options(model.rt, d.rt_quadrature_tolerance, threads)
            return _auto_rt(common, "rt_masked", options, d)
        fo = _masked(base, system, z, model.fo, threads)
        return dataclasses.replace(fo, reasons=tuple(d.reasons), **common)
    if isinstance(model, RT):
        return Plan(
            **base,
            backend="rt_masked",
            tolerance=model.tolerance,
            options=_rt_options(model, model.tolerance, threads),
            reasons=(
                f"ray tracing through the aperture mask ({names}), to {model.tolerance:g} on G; G "
                "is normalised to the full aperture",
            ),
        )
    if system.detector.stop_radius is not None:
        raise ValueError(
            "detector.stop_radius with telescope.mask is modelled by ray tracing only: use "
            "method='rt', or set detector.stop_radius to None"
        )
    if model.path != "auto" or model.beam_grid is not None or model.beam_window is not None:
        raise ValueError(
            "fo_path, beam_grid and beam_window do not apply with telescope.mask: the masked "
            "Fourier-optics path samples the pupil cut to the mask (leave them at their defaults)"
        )
    options = _core.FoAberratedOptions()
    options.max_grid, options.threads = model.max_spectrum_grid, threads
    return Plan(
        **base,
        backend="fo_masked",
        tolerance=float("nan"),
        options=options,
        reasons=(
            f"Fourier optics through the pupil cut to the aperture mask ({names}), sampled at each "
            "range; G is normalised to the full aperture",
        ),
    )


def _aberrated(base, system, model, threads) -> Plan:
    if isinstance(model, Auto):
        # the estimate needs two coarse RT curves: made when the plan runs (resolve)
        return Plan(
            **base,
            backend="auto_aberrated",
            tolerance=model.tolerance,
            options=_fan_options(model.rt, model.tolerance, threads),
            reasons=(
                "receiver aberrations: auto's estimate of ray tracing's diffraction error needs "
                "two coarse aberrated RT curves, so ray tracing or Fourier optics is chosen when "
                "the plan runs",
            ),
        )
    if isinstance(model, RT):
        field_dependent = system.telescope.aberrations.field_dependent
        form = "a ray fan per scatterer" if field_dependent else "the pupil form where it applies"
        return Plan(
            **base,
            backend="rt_aberrated",
            tolerance=model.tolerance,
            options=_fan_options(model, model.tolerance, threads),
            reasons=(
                f"ray tracing through the aberrated pupil ({form}), to {model.tolerance:g} on G",
            ),
        )
    options = _core.FoAberratedOptions()
    options.max_grid, options.threads = model.max_spectrum_grid, threads
    return Plan(
        **base,
        backend="fo_aberrated",
        tolerance=float("nan"),
        options=options,
        reasons=("Fourier optics: the aberrated pupil sampled and its OTF computed at each range",),
    )


def _turbulent(system, z, request: Turbulent, threads) -> Plan:
    if system.telescope.mask is not None:
        raise ValueError(
            "turbulence with telescope.mask is not modelled: set telescope.mask or turbulence to "
            "None"
        )
    if system.aberrated:
        raise ValueError(
            "turbulence with receiver aberrations is not modelled yet: set telescope.aberrations "
            "to None or turbulence to None"
        )
    if isinstance(system.beam, FieldBeam):
        raise ValueError("turbulence with a FieldBeam is not modelled yet: expected a GaussianBeam")
    if system.detector.stop_radius is not None and request.paths == "both":
        raise ValueError(
            "detector.stop_radius with paths = 'both' is not modelled: the return path's receiver "
            "fields fill the aperture; expected paths = 'transmit' or detector.stop_radius None"
        )
    model = request.method
    tolerance = model.tolerance if isinstance(model, (RT, Auto)) else float("nan")
    chosen: Tuple[str, ...] = ()  # auto's reasons, said before the plan's own
    if isinstance(model, Auto):
        d = (
            auto.decide_both_paths(system, z, model.tolerance, request.turbulence)
            if request.paths == "both"
            else auto.decide(system, z, model.tolerance)
        )
        # through turbulence Fourier optics is always the 2-D path through the screens
        chosen = tuple(r for r in d.reasons if not r.startswith("Gaussian beam: the radial FO"))
        model = (
            dataclasses.replace(model.rt, tolerance=model.tolerance)
            if d.method == "rt"
            else model.fo
        )
    wavelength = system.beam.wavelength
    if request.turbulence.rytov_variance(wavelength, float(z[-1])) == 0.0:  # no turbulence at all
        p = _plain(system, z, model, request, threads)
        return dataclasses.replace(
            p,
            tolerance=tolerance if p.method == "rt" else p.tolerance,
            reasons=p.reasons
            + ("the turbulence is zero along the path: every draw is the turbulence-free curve",),
        )
    base = _base(system, z, request)
    if isinstance(model, RT):
        both = (
            "; the return path's image tilted (correlated with the wander) and blurred, and the "
            "mean with independent tilts computed exactly for the amplification"
            if request.paths == "both"
            else ""
        )
        return Plan(
            **base,
            backend="rt_turbulent",
            tolerance=model.tolerance,
            options=_rt_options(model, model.tolerance, threads),
            reasons=chosen
            + (
                f"{request.realizations} draws of the beam wander{both}, ray traced to "
                f"{model.tolerance:g}",
            ),
        )
    options = _core.TurbulenceOptions()
    options.realizations, options.screens = request.realizations, request.screens
    options.seed = request.seed
    if model.beam_grid is not None:
        options.beam_grid = _checks.count("beam_grid", model.beam_grid, MIN_TURBULENT_GRID)
    if model.beam_window is not None:
        options.beam_window = model.beam_window
    options.max_spectrum_grid, options.threads = model.max_spectrum_grid, threads
    options.paths, options.receiver_fields = request.paths, request.receiver_fields
    both = (
        f"; the return path through the same screens ({request.receiver_fields} random-phase "
        "receiver fields)"
        if request.paths == "both"
        else ""
    )
    return Plan(
        **base,
        backend="fo_turbulent",
        tolerance=float("nan"),
        options=options,
        reasons=chosen
        + (
            f"{request.realizations} draws of {request.screens} phase screens, the beam on "
            f"{options.beam_grid}^2{both}",
        ),
    )


def _auto_rt(common: dict, key: str, options, d) -> Plan:
    """Auto's choice of ray tracing: the quadrature gets what the model error leaves, whose
    diffraction is bounded (no warning about it)."""
    return Plan(
        **common,
        backend=key,
        options=options,
        rt_diffraction_warning=False,
        reasons=tuple(d.reasons),
    )


def _auto_fo(fo: FO, path: str, field_beam: bool) -> FO:
    """The FO auto runs on ``path``: its grid and window where that is the 2-D path of a Gaussian
    beam."""
    if field_beam:
        return FO(max_spectrum_grid=fo.max_spectrum_grid)
    if path == "radial":
        return FO(path="radial", max_spectrum_grid=fo.max_spectrum_grid)
    return dataclasses.replace(fo, path=path)


def _rt_options(model: RT, tolerance: float, threads: int):
    options = _core.RtOptions()
    options.tolerance, options.threads = tolerance, threads
    options.max_segments = model.max_segments
    return options


def _fan_options(model: RT, tolerance: float, threads: int):
    options = _core.RtAberratedOptions()
    options.rings, options.ring_rays, options.tolerance = model.rings, model.ring_rays, tolerance
    options.threads, options.max_segments = threads, model.max_segments
    return options


def _kind_change(old: LidarSystem, new: LidarSystem) -> str:
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
