"""How each model is planned: the backend, the core's options and the reasons for a plain
receiver (ray tracing, radial / 2-D / field Fourier optics, auto's choice between them), an aperture
mask, receiver aberrations, turbulence and a beam of incoherent Gaussian components. Each returns a
:class:`~lidar_overlap.forward.plans.Plan`; :func:`lidar_overlap.forward.planning.plan` picks the
planner.

A receiver's planners stand in one table, a :class:`Receiver` (:data:`PLAIN`, :data:`MASKED`,
:data:`ABERRATED`): the plan of each model (Auto, RT, FO) for that receiver, so that the ladder from
auto's choice to ray tracing or Fourier optics is written once (:meth:`Receiver.plan`)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Callable, Dict

from .. import _core
from ..model.field_beam import FieldBeam
from . import auto
from .methods import FO, RT, Auto
from .plans import Plan, base_fields, power_weighted


@dataclass(frozen=True)
class Scene:
    """What the planners of one request share: the system, the ranges ``z`` (m, checked), the
    plan's base fields (:func:`~.plans.base_fields`), the threads, and whether the beam is a
    sampled field."""

    system: Any
    z: Any
    base: Dict[str, Any]
    threads: int

    @property
    def field_beam(self) -> bool:
        return isinstance(self.system.beam, FieldBeam)


@dataclass(frozen=True)
class Receiver:
    """How one kind of receiver is planned: the plan of each model for a :class:`Scene`."""

    auto: Callable[[Scene, Auto], Plan]
    rt: Callable[[Scene, RT], Plan]
    fo: Callable[[Scene, FO], Plan]

    def plan(self, scene: Scene, model) -> Plan:
        """The plan of ``model`` (an Auto, RT or FO object)."""
        planners: Dict[type, Callable[[Scene, Any], Plan]] = {
            Auto: self.auto,
            RT: self.rt,
            FO: self.fo,
        }
        return planners[type(model)](scene, model)


def mixture(system, z, request, threads) -> Plan:
    """A :class:`GaussianMixtureBeam`: each component planned as a :class:`GaussianBeam` in this
    receiver (its own backend, auto's choice and error estimate), G their power-weighted sum."""
    parts = tuple(plain(s, z, request, request, threads) for _, s in system.incoherent_parts)
    return mixture_of(system, z, request, parts, threads)


def mixture_of(system, z, request, parts, threads) -> Plan:
    """The mixture plan of the components' ``parts``. Auto may choose ray tracing for one component
    and Fourier optics for another; then every component runs Fourier optics at auto's tolerance, so
    that the curve is of one model."""
    n = len(parts)
    head = f"{n} incoherent Gaussian component{'s' if n > 1 else ''}, G = Σ w_i G_i"
    if any(p.deferred for p in parts):
        return Plan(
            **base_fields(system, z, request),
            backend="auto_mixture",
            tolerance=parts[0].tolerance,
            options=parts[0].options,
            reasons=(head + "; auto decides for each component when the plan runs",),
            parts=parts,
        )
    if len({p.method for p in parts}) > 1 and isinstance(request, Auto):
        parts = tuple(
            dataclasses.replace(
                plain(p.system, z, request.fo, request, threads),
                tolerance=request.tolerance,
                reasons=("auto: Fourier optics, as for another component of the beam",),
            )
            for p in parts
        )
    key = "rt_mixture" if parts[0].method == "rt" else "fo_mixture"
    shares = [w for w, _ in system.incoherent_parts]
    return Plan(
        **base_fields(system, z, request),
        backend=key,
        tolerance=parts[0].tolerance,
        options=parts[0].options,
        rt_model_error=power_weighted(system, [p.rt_model_error for p in parts]),
        rt_diffraction_warning=all(p.rt_diffraction_warning for p in parts),
        reasons=(head,)
        + tuple(
            f"component {i} (power share {w:.3g}): {p.reasons[0] if p.reasons else p.backend}"
            for i, (w, p) in enumerate(zip(shares, parts))
        ),
        parts=parts,
    )


def plain(system, z, model, request, threads) -> Plan:
    """The plan of ``model`` (RT, FO or Auto) without turbulence; ``request`` is what the caller
    asked for."""
    scene = Scene(system, z, base_fields(system, z, request), threads)
    return receiver(system).plan(scene, model)


def receiver(system) -> Receiver:
    """The planners of ``system``'s receiver: with an aperture mask, with aberrations, or plain;
    a combination that no path models is refused naming both."""
    if system.telescope.mask is not None:
        if system.aberrated:
            raise ValueError(
                "telescope.mask with aberrations is not modelled: set telescope.aberrations or "
                "telescope.mask to None"
            )
        if isinstance(system.beam, FieldBeam):
            raise ValueError(
                f"telescope.mask is invalid for a {type(system.beam).__name__}: the masked paths "
                "model Gaussian beams only"
            )
        return MASKED
    if not system.aberrated:
        return PLAIN
    if system.detector.stop_radius is not None:
        raise ValueError(
            "detector.stop_radius with receiver aberrations is not modelled: set "
            "telescope.aberrations or detector.stop_radius to None"
        )
    if isinstance(system.beam, FieldBeam):
        raise ValueError(
            "aberrations with a FieldBeam are not modelled: expected a GaussianBeam (the "
            "aberrated paths weight the point image by the Gaussian beam image)"
        )
    return ABERRATED


def geometric_auto(rt_key: str, fo: Callable[[Scene, Auto, auto.Decision], Plan]):
    """Auto for a receiver whose RT error auto estimates from the geometry (:func:`auto.decide`):
    ray tracing on backend ``rt_key`` with the quadrature's share of the tolerance, or the plan
    ``fo(scene, model, decision)`` with auto's reasons."""

    def plan(scene: Scene, model: Auto) -> Plan:
        d = auto.decide(scene.system, scene.z, model.tolerance)
        common: Dict[str, Any] = dict(
            scene.base, tolerance=model.tolerance, rt_model_error=d.rt_model_error
        )
        if d.method == "rt":
            options = rt_options(model.rt, d.rt_quadrature_tolerance, scene.threads)
            return auto_rt(common, rt_key, options, d)
        return dataclasses.replace(fo(scene, model, d), reasons=tuple(d.reasons), **common)

    return plan


def plain_rt(scene: Scene, model: RT) -> Plan:
    if scene.field_beam:
        raise ValueError(
            f"method = 'rt' is invalid for a {type(scene.system.beam).__name__}: ray tracing "
            "models Gaussian beams only; use method='fo'"
        )
    return Plan(
        **scene.base,
        backend="rt",
        tolerance=model.tolerance,
        options=rt_options(model, model.tolerance, scene.threads),
        reasons=(f"ray tracing asked for, to {model.tolerance:g} on G",),
    )


def plain_fo(scene: Scene, model: FO) -> Plan:
    common: Dict[str, Any] = dict(scene.base, tolerance=float("nan"))
    if scene.field_beam:
        if model.beam_grid is not None or model.beam_window is not None:
            raise ValueError(
                "beam_grid and beam_window apply to Gaussian beams only: a FieldBeam is propagated "
                "on its own grid"
            )
        options = _core.FoOptions()
        options.max_spectrum_grid, options.threads = model.max_spectrum_grid, scene.threads
        return Plan(
            **common,
            backend="fo_field",
            options=options,
            reasons=(f"Fourier optics on the {type(scene.system.beam).__name__}'s own grid",),
        )
    if model.path == "radial" or (model.path == "auto" and auto.radial_fo_applies(scene.system)):
        if model.beam_grid is not None or model.beam_window is not None:
            raise ValueError(
                "beam_grid and beam_window apply to the 2-D FO path only; use fo_path='2d'"
            )
        radial = _core.RadialFoOptions()
        radial.threads = scene.threads
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
    options.max_spectrum_grid, options.threads = model.max_spectrum_grid, scene.threads
    return Plan(
        **common,
        backend="fo_2d",
        options=options,
        reasons=(
            f"Fourier optics on the 2d path: the beam sampled on {options.beam_grid}^2 over "
            f"{options.beam_window:g} waist radii",
        ),
    )


def masked_rt(scene: Scene, model: RT) -> Plan:
    """Ray tracing with each scatterer's coupling restricted to the mask."""
    names = ", ".join(scene.system.telescope.mask.names)
    return Plan(
        **scene.base,
        backend="rt_masked",
        tolerance=model.tolerance,
        options=rt_options(model, model.tolerance, scene.threads),
        reasons=(
            f"ray tracing through the aperture mask ({names}), to {model.tolerance:g} on G; G "
            "is normalised to the full aperture",
        ),
    )


def masked_fo(scene: Scene, model: FO) -> Plan:
    """Fourier optics through the sampled pupil cut to the mask."""
    system = scene.system
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
    options.max_grid, options.threads = model.max_spectrum_grid, scene.threads
    names = ", ".join(system.telescope.mask.names)
    return Plan(
        **scene.base,
        backend="fo_masked",
        tolerance=float("nan"),
        options=options,
        reasons=(
            f"Fourier optics through the pupil cut to the aperture mask ({names}), sampled at each "
            "range; G is normalised to the full aperture",
        ),
    )


def aberrated_auto(scene: Scene, model: Auto) -> Plan:
    """The estimate needs two coarse RT curves: made when the plan runs (planning.resolve)."""
    return Plan(
        **scene.base,
        backend="auto_aberrated",
        tolerance=model.tolerance,
        options=fan_options(model.rt, model.tolerance, scene.threads),
        reasons=(
            "receiver aberrations: auto's estimate of ray tracing's diffraction error needs "
            "two coarse aberrated RT curves, so ray tracing or Fourier optics is chosen when "
            "the plan runs",
        ),
    )


def aberrated_rt(scene: Scene, model: RT) -> Plan:
    field_dependent = scene.system.telescope.aberrations.field_dependent
    form = "a ray fan per scatterer" if field_dependent else "the pupil form where it applies"
    return Plan(
        **scene.base,
        backend="rt_aberrated",
        tolerance=model.tolerance,
        options=fan_options(model, model.tolerance, scene.threads),
        reasons=(f"ray tracing through the aberrated pupil ({form}), to {model.tolerance:g} on G",),
    )


def aberrated_fo(scene: Scene, model: FO) -> Plan:
    options = _core.FoAberratedOptions()
    options.max_grid, options.threads = model.max_spectrum_grid, scene.threads
    return Plan(
        **scene.base,
        backend="fo_aberrated",
        tolerance=float("nan"),
        options=options,
        reasons=("Fourier optics: the aberrated pupil sampled and its OTF computed at each range",),
    )


#: The plain receiver: auto from the geometry; FO on the path auto chose.
PLAIN = Receiver(
    auto=geometric_auto(
        "rt",
        lambda scene, model, d: plain_fo(scene, auto_fo(model.fo, d.fo_path, scene.field_beam)),
    ),
    rt=plain_rt,
    fo=plain_fo,
)
#: An aperture mask (telecover): ray tracing with each scatterer's coupling restricted to the mask,
#: or Fourier optics through the sampled pupil cut to it; auto chooses by RT's diffraction
#: estimate, as without a mask.
MASKED = Receiver(
    auto=geometric_auto("rt_masked", lambda scene, model, d: masked_fo(scene, model.fo)),
    rt=masked_rt,
    fo=masked_fo,
)
#: Receiver aberrations: auto decides when the plan runs.
ABERRATED = Receiver(auto=aberrated_auto, rt=aberrated_rt, fo=aberrated_fo)


def aberrated(base, system, model, threads) -> Plan:
    """The plan of ``model`` for a receiver with aberrations (``base``: the plan's base fields)."""
    return ABERRATED.plan(Scene(system, base["ranges"], base, threads), model)


def auto_rt(common: dict, key: str, options, d) -> Plan:
    """Auto's choice of ray tracing: the quadrature gets what the model error leaves, whose
    diffraction is bounded (no warning about it)."""
    return Plan(
        **common,
        backend=key,
        options=options,
        rt_diffraction_warning=False,
        reasons=tuple(d.reasons),
    )


def auto_fo(fo: FO, path: str, field_beam: bool) -> FO:
    """The FO auto runs on ``path``: its grid and window where that is the 2-D path of a Gaussian
    beam."""
    if field_beam:
        return FO(max_spectrum_grid=fo.max_spectrum_grid)
    if path == "radial":
        return FO(path="radial", max_spectrum_grid=fo.max_spectrum_grid)
    return dataclasses.replace(fo, path=path)


def rt_options(model: RT, tolerance: float, threads: int):
    options = _core.RtOptions()
    options.tolerance, options.threads = tolerance, threads
    options.max_segments = model.max_segments
    return options


def fan_options(model: RT, tolerance: float, threads: int):
    options = _core.RtAberratedOptions()
    options.rings, options.ring_rays, options.tolerance = model.rings, model.ring_rays, tolerance
    options.threads, options.max_segments = threads, model.max_segments
    return options
