"""How each model is planned: the backend, the core's options and the reasons for a plain
receiver (ray tracing, radial / 2-D / field Fourier optics, auto's choice between them), an aperture
mask, receiver aberrations, turbulence and a beam of incoherent Gaussian components. Each returns a
:class:`~lidar_overlap.forward.plans.Plan`; :func:`lidar_overlap.forward.planning.plan` picks the
planner."""

from __future__ import annotations

import dataclasses
from typing import Any, Dict, Tuple

from .. import _checks, _core
from ..model.field_beam import FieldBeam
from . import auto
from .methods import FO, RT, Auto, Turbulent
from .plans import Plan, base_fields, power_weighted

#: The 2-D path of the turbulent FO overlap needs this many samples per side at least.
MIN_TURBULENT_GRID = 32


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
    base = base_fields(system, z, request)
    if system.telescope.mask is not None:
        return masked(base, system, z, model, threads)
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
        return aberrated(base, system, model, threads)
    field_beam = isinstance(system.beam, FieldBeam)
    if isinstance(model, Auto):
        d = auto.decide(system, z, model.tolerance)
        common: Dict[str, Any] = dict(
            base, tolerance=model.tolerance, rt_model_error=d.rt_model_error
        )
        if d.method == "rt":
            options = rt_options(model.rt, d.rt_quadrature_tolerance, threads)
            return auto_rt(common, "rt", options, d)
        fo = fo_plan(base, system, auto_fo(model.fo, d.fo_path, field_beam), threads, field_beam)
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
            options=rt_options(model, model.tolerance, threads),
            reasons=(f"ray tracing asked for, to {model.tolerance:g} on G",),
        )
    return fo_plan(base, system, model, threads, field_beam)


def fo_plan(base, system, model: FO, threads, field_beam) -> Plan:
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


def masked(base, system, z, model, threads) -> Plan:
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
            options = rt_options(model.rt, d.rt_quadrature_tolerance, threads)
            return auto_rt(common, "rt_masked", options, d)
        fo = masked(base, system, z, model.fo, threads)
        return dataclasses.replace(fo, reasons=tuple(d.reasons), **common)
    if isinstance(model, RT):
        return Plan(
            **base,
            backend="rt_masked",
            tolerance=model.tolerance,
            options=rt_options(model, model.tolerance, threads),
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


def aberrated(base, system, model, threads) -> Plan:
    if isinstance(model, Auto):
        # the estimate needs two coarse RT curves: made when the plan runs (resolve)
        return Plan(
            **base,
            backend="auto_aberrated",
            tolerance=model.tolerance,
            options=fan_options(model.rt, model.tolerance, threads),
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
            options=fan_options(model, model.tolerance, threads),
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


def turbulent(system, z, request: Turbulent, threads) -> Plan:
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
    warned: Tuple[str, ...] = ()
    wavelength = system.beam.wavelength
    calm = request.turbulence.rytov_variance(wavelength, float(z[-1])) == 0.0
    if isinstance(model, Auto):
        if request.paths == "both" and not calm:
            # FO only on a grid the core accepts and auto allows (auto.turbulent_fo_grid)
            grid = auto.turbulent_fo_grid(
                system,
                z,
                request.turbulence,
                fo_options(request, model.fo, threads),
                model.fo.beam_grid,
                threads,
            )
            d = auto.decide_both_paths(system, z, model.tolerance, request.turbulence, grid)
        else:
            d = auto.decide(system, z, model.tolerance)
        # through turbulence Fourier optics is always the 2-D path through the screens
        chosen = tuple(r for r in d.reasons if not r.startswith("Gaussian beam: the radial FO"))
        warned = (f"overlap(auto): {d.warning}",) if d.warning else ()
        if d.method == "rt":
            model = dataclasses.replace(model.rt, tolerance=model.tolerance)
        elif request.paths == "both" and not calm:
            model = dataclasses.replace(model.fo, beam_grid=grid.grid)
        else:
            model = model.fo
    if calm:  # no turbulence at all
        p = plain(system, z, model, request, threads)
        return dataclasses.replace(
            p,
            tolerance=tolerance if p.method == "rt" else p.tolerance,
            reasons=p.reasons
            + ("the turbulence is zero along the path: every draw is the turbulence-free curve",),
        )
    base = base_fields(system, z, request)
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
            options=rt_options(model, model.tolerance, threads),
            warnings=warned,
            reasons=chosen
            + (
                f"{request.realizations} draws of the beam wander{both}, ray traced to "
                f"{model.tolerance:g}",
            ),
        )
    options = fo_options(request, model, threads)
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


def fo_options(request: Turbulent, model: FO, threads: int):
    """The core's options of the turbulent FO path for ``request`` and the FO ``model``."""
    options = _core.TurbulenceOptions()
    options.realizations, options.screens = request.realizations, request.screens
    options.seed = request.seed
    if model.beam_grid is not None:
        options.beam_grid = _checks.count("beam_grid", model.beam_grid, MIN_TURBULENT_GRID)
    if model.beam_window is not None:
        options.beam_window = model.beam_window
    options.max_spectrum_grid, options.threads = model.max_spectrum_grid, threads
    options.paths, options.receiver_fields = request.paths, request.receiver_fields
    return options


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
