"""Plan, then run: what one overlap computation will do, decided before anything is computed.

:func:`plan` turns (system, ranges, method) into a :class:`Plan`: the checked inputs, the backend that
will compute G (ray tracing, radial / 2-D / field / aberrated Fourier optics, or their turbulent forms),
the core's options for it, and the error the result will state. It may make cheap estimates (auto's
diffraction bound; for aberrated receivers two coarse RT curves on at most 16 ranges) and carries them, so
running the plan computes each curve once. :func:`lidar_overlap.run` executes a plan;
:func:`explain` prints one.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Optional, Tuple

import numpy as np

from . import _checks, _core, auto
from .field_beam import FieldBeam
from .methods import FO, RT, Auto, Method, Turbulent, from_shortcuts
from .system import LidarSystem

#: What each backend computes, for the plan's description.
BACKENDS = {
    "rt": "ray tracing",
    "rt_aberrated": "ray tracing through the aberrated pupil",
    "rt_masked": "ray tracing through the aperture mask",
    "fo_masked": "Fourier optics through the aperture mask (sampled pupil)",
    "fo_radial": "Fourier optics (radial path)",
    "fo_2d": "Fourier optics (2d path)",
    "fo_field": "Fourier optics (2d path, the field's own grid)",
    "fo_aberrated": "Fourier optics (aberrated path)",
    "rt_turbulent": "ray tracing of the wandering short-term beam (all draws in one core call)",
    "fo_turbulent": "Fourier optics through phase screens",
}
#: The 2-D path of the turbulent FO overlap needs this many samples per side at least.
MIN_TURBULENT_GRID = 32


@dataclass(frozen=True, eq=False)
class Plan:
    """One overlap computation, decided.

    method : the model that computes G, ``"rt"`` or ``"fo"``; fo_path : ``"radial"``, ``"2d"``,
    ``"aberrated"``, ``"masked"`` or ``""`` (RT). backend : the key of the code that runs (:data:`BACKENDS`);
    options : the core's options for it (``_core.RtOptions`` and its kin). tolerance : what the result states (NaN for
    plain FO). error_kind : ``"bound"`` (RT: quadrature bound, plus the model error auto estimated),
    ``"nominal"`` (FO: the path's measured accuracy) or ``"standard_error"`` (turbulence: of the mean).
    rt_model_error : auto's estimate of RT's diffraction error (0 when not estimated, NaN where RT cannot
    model the beam); rt_quadrature_tolerance : the tolerance RT's quadrature runs at. turbulence : the
    :class:`Turbulent` request, or None; reasons : why, one line each; warnings : said when the plan runs.
    """

    system: LidarSystem
    ranges: np.ndarray
    request: Method
    method: str
    fo_path: str
    backend: str
    options: Any
    tolerance: float
    error_kind: str
    rt_model_error: float = 0.0
    rt_quadrature_tolerance: float = 0.0
    rt_diffraction_warning: bool = True
    turbulence: Optional[Turbulent] = None
    reasons: Tuple[str, ...] = ()
    warnings: Tuple[str, ...] = ()

    def subset(self, index) -> "Plan":
        """The same plan (same decisions, same estimates) on ``ranges[index]`` (a slice): to run a long curve in
        parts."""
        return dataclasses.replace(self, ranges=self.ranges[index])

    def __str__(self) -> str:
        head = ("auto: " if isinstance(self.request, Auto) or isinstance(getattr(self.request, "method", None), Auto)
                else "plan: ") + BACKENDS[self.backend]
        return "\n".join([head] + [f"  - {r}" for r in self.reasons])


def plan(system: LidarSystem, ranges, method="rt", *, threads: int = 0, **shortcuts) -> Plan:
    """The :class:`Plan` of ``lo.overlap(system, ranges, method, threads=threads, **shortcuts)``: every input
    checked and every choice made, no overlap computed. ``method``: ``"rt"``, ``"fo"``, ``"auto"`` (with the
    shortcut options of :func:`lidar_overlap.overlap`) or an RT, FO, Auto or Turbulent object."""
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    request = from_shortcuts(method, **shortcuts)
    z = _checks.ranges("ranges", ranges)
    system._native.validate_ranges(z)   # before any path derives quantities from them
    threads = _checks.threads(threads)
    if isinstance(request, Turbulent):
        return _turbulent(system, z, request, threads)
    return _plain(system, z, request, request, threads)


def explain(system, ranges, method="auto", *, threads: int = 0, **shortcuts) -> Plan:
    """Print and return the :class:`Plan` ``lo.overlap(system, ranges, method, **shortcuts)`` follows, with the
    estimates behind it (``lo.explain(system, ranges, tolerance=1e-3)``: what auto does at that tolerance)."""
    p = plan(system, ranges, method, threads=threads, **shortcuts)
    print(p)
    return p


def _plain(system, z, model, request, threads) -> Plan:
    """The plan of ``model`` (RT, FO or Auto) without turbulence; ``request`` is what the caller asked for."""
    base = dict(system=system, ranges=z, request=request)
    if system.telescope.mask is not None:
        return _masked(base, system, z, model, threads)
    if system.aberrated:
        if isinstance(system.beam, FieldBeam):
            raise ValueError("aberrations with a FieldBeam are not modelled: expected a GaussianBeam (the aberrated "
                             "paths weight the point image by the Gaussian beam image)")
        return _aberrated(base, system, z, model, threads)
    field_beam = isinstance(system.beam, FieldBeam)
    if isinstance(model, Auto):
        d = auto.decide(system, z, model.tolerance)
        common = dict(base, tolerance=model.tolerance, rt_model_error=d.rt_model_error, reasons=tuple(d.reasons))
        if d.method == "rt":
            return _auto_rt(common, "rt", _rt_options(model.rt, d.rt_quadrature_tolerance, threads), d)
        return dataclasses.replace(_fo(base, system, _auto_fo(model.fo, d.fo_path, field_beam), threads, field_beam),
                                   **common)
    if isinstance(model, RT):
        if field_beam:
            raise ValueError(f"method = 'rt' is invalid for a {type(system.beam).__name__}: ray tracing models "
                             "Gaussian beams only; use method='fo'")
        return Plan(**base, method="rt", fo_path="", backend="rt", error_kind="bound", tolerance=model.tolerance,
                    options=_rt_options(model, model.tolerance, threads), rt_quadrature_tolerance=model.tolerance,
                    reasons=(f"ray tracing asked for, to {model.tolerance:g} on G",))
    return _fo(base, system, model, threads, field_beam)


def _fo(base, system, model: FO, threads, field_beam) -> Plan:
    common = dict(base, method="fo", error_kind="nominal", tolerance=float("nan"))
    if field_beam:
        if model.beam_grid is not None or model.beam_window is not None:
            raise ValueError("beam_grid and beam_window apply to Gaussian beams only: a FieldBeam is propagated on "
                             "its own grid")
        options = _core.FoOptions()
        options.max_spectrum_grid, options.threads = model.max_spectrum_grid, threads
        return Plan(**common, fo_path="2d", backend="fo_field", options=options,
                    reasons=(f"Fourier optics on the {type(system.beam).__name__}'s own grid",))
    if model.path == "radial" or (model.path == "auto" and auto.radial_fo_applies(system)):
        if model.beam_grid is not None or model.beam_window is not None:
            raise ValueError("beam_grid and beam_window apply to the 2-D FO path only; use fo_path='2d'")
        options = _core.RadialFoOptions()
        options.threads = threads
        return Plan(**common, fo_path="radial", backend="fo_radial", options=options,
                    reasons=("Gaussian beam: Fourier optics on the radial path (one integral per range)",))
    options = _core.FoOptions()
    if model.beam_grid is not None:
        options.beam_grid = model.beam_grid
    if model.beam_window is not None:
        options.beam_window = model.beam_window
    options.max_spectrum_grid, options.threads = model.max_spectrum_grid, threads
    return Plan(**common, fo_path="2d", backend="fo_2d", options=options,
                reasons=(f"Fourier optics on the 2d path: the beam sampled on {options.beam_grid}^2 over "
                         f"{options.beam_window:g} waist radii",))


def _masked(base, system, z, model, threads) -> Plan:
    """An aperture mask (telecover): ray tracing with each scatterer's coupling restricted to the mask, or Fourier
    optics through the sampled pupil cut to it; auto chooses by RT's diffraction estimate, as without a mask."""
    if system.aberrated:
        raise ValueError("telescope.mask with aberrations is not modelled: set telescope.aberrations or "
                         "telescope.mask to None")
    if isinstance(system.beam, FieldBeam):
        raise ValueError(f"telescope.mask is invalid for a {type(system.beam).__name__}: the masked paths model "
                         "Gaussian beams only")
    names = ", ".join(system.telescope.mask.names)
    if isinstance(model, Auto):
        d = auto.decide(system, z, model.tolerance)
        common = dict(base, tolerance=model.tolerance, rt_model_error=d.rt_model_error, reasons=tuple(d.reasons))
        if d.method == "rt":
            return _auto_rt(common, "rt_masked", _rt_options(model.rt, d.rt_quadrature_tolerance, threads), d)
        return dataclasses.replace(_masked(base, system, z, model.fo, threads), **common)
    if isinstance(model, RT):
        return Plan(**base, method="rt", fo_path="", backend="rt_masked", error_kind="bound",
                    tolerance=model.tolerance, options=_rt_options(model, model.tolerance, threads),
                    rt_quadrature_tolerance=model.tolerance,
                    reasons=(f"ray tracing through the aperture mask ({names}), to {model.tolerance:g} on G; G is "
                             "normalised to the full aperture",))
    if model.path != "auto" or model.beam_grid is not None or model.beam_window is not None:
        raise ValueError("fo_path, beam_grid and beam_window do not apply with telescope.mask: the masked Fourier-"
                         "optics path samples the pupil cut to the mask (leave them at their defaults)")
    options = _core.FoAberratedOptions()
    options.max_grid, options.threads = model.max_spectrum_grid, threads
    return Plan(**base, method="fo", fo_path="masked", backend="fo_masked", error_kind="nominal",
                tolerance=float("nan"), options=options,
                reasons=(f"Fourier optics through the pupil cut to the aperture mask ({names}), sampled at each "
                         "range; G is normalised to the full aperture",))


def _aberrated(base, system, z, model, threads) -> Plan:
    ab = system.telescope.aberrations
    if isinstance(model, Auto):
        d = auto.decide(system, z, model.tolerance, model.rt)
        common = dict(base, tolerance=model.tolerance, rt_model_error=d.rt_model_error, reasons=tuple(d.reasons),
                      warnings=(f"overlap(auto): {d.warning}",) if d.warning else ())
        if d.method == "rt":
            return _auto_rt(common, "rt_aberrated", _fan_options(model.rt, d.rt_quadrature_tolerance, threads), d)
        return dataclasses.replace(_aberrated(base, system, z, model.fo, threads), **common)
    if isinstance(model, RT):
        form = "a ray fan per scatterer" if ab.field_dependent else "the pupil form where it applies"
        return Plan(**base, method="rt", fo_path="", backend="rt_aberrated", error_kind="bound",
                    tolerance=model.tolerance, options=_fan_options(model, model.tolerance, threads),
                    rt_quadrature_tolerance=model.tolerance,
                    reasons=(f"ray tracing through the aberrated pupil ({form}), to {model.tolerance:g} on G",))
    options = _core.FoAberratedOptions()
    options.max_grid, options.threads = model.max_spectrum_grid, threads
    return Plan(**base, method="fo", fo_path="aberrated", backend="fo_aberrated", error_kind="nominal",
                tolerance=float("nan"), options=options,
                reasons=("Fourier optics: the aberrated pupil sampled and its OTF computed at each range",))


def _turbulent(system, z, request: Turbulent, threads) -> Plan:
    if system.telescope.mask is not None:
        raise ValueError("turbulence with telescope.mask is not modelled: set telescope.mask or turbulence to None")
    if system.aberrated:
        raise ValueError("turbulence with receiver aberrations is not modelled yet: set telescope.aberrations "
                         "to None or turbulence to None")
    if isinstance(system.beam, FieldBeam):
        raise ValueError("turbulence with a FieldBeam is not modelled yet: expected a GaussianBeam")
    model = request.method
    tolerance = model.tolerance if isinstance(model, (RT, Auto)) else float("nan")
    if isinstance(model, Auto) and request.paths == "both":
        model = model.fo                      # the return path through the turbulence is Fourier optics only
    elif isinstance(model, Auto):
        d = auto.decide(system, z, model.tolerance)
        model = dataclasses.replace(model.rt, tolerance=model.tolerance) if d.method == "rt" else model.fo
    if request.turbulence.rytov_variance(system.beam.wavelength, float(z[-1])) == 0.0:   # no turbulence at all
        p = _plain(system, z, model, request, threads)
        return dataclasses.replace(p, turbulence=request, tolerance=tolerance if p.method == "rt" else p.tolerance,
                                   reasons=p.reasons + ("the turbulence is zero along the path: every draw is the "
                                                        "turbulence-free curve",))
    common = dict(system=system, ranges=z, request=request, turbulence=request, error_kind="standard_error")
    if isinstance(model, RT):
        if request.paths == "both":
            raise ValueError("paths = 'both' is invalid with ray tracing: the return path through the turbulence is "
                             "modelled in Fourier optics only; expected method FO or paths = 'transmit'")
        return Plan(**common, method="rt", fo_path="", backend="rt_turbulent", tolerance=model.tolerance,
                    options=_rt_options(model, model.tolerance, threads), rt_quadrature_tolerance=model.tolerance,
                    reasons=(f"{request.realizations} draws of the beam wander, ray traced to {model.tolerance:g}",))
    options = _core.TurbulenceOptions()
    options.realizations, options.screens, options.seed = request.realizations, request.screens, request.seed
    if model.beam_grid is not None:
        options.beam_grid = _checks.count("beam_grid", model.beam_grid, MIN_TURBULENT_GRID)
    if model.beam_window is not None:
        options.beam_window = model.beam_window
    options.max_spectrum_grid, options.threads = model.max_spectrum_grid, threads
    options.paths, options.receiver_fields = request.paths, request.receiver_fields
    both = (f"; the return path through the same screens ({request.receiver_fields} random-phase receiver fields)"
            if request.paths == "both" else "")
    return Plan(**common, method="fo", fo_path="2d", backend="fo_turbulent", tolerance=float("nan"), options=options,
                reasons=(f"{request.realizations} draws of {request.screens} phase screens, the beam on "
                         f"{options.beam_grid}^2{both}",))


def _auto_rt(common: dict, backend: str, options, d) -> Plan:
    """Auto's choice of ray tracing: the quadrature gets what the model error leaves, whose diffraction is
    bounded (no warning about it)."""
    return Plan(**common, method="rt", fo_path="", backend=backend, error_kind="bound", options=options,
                rt_quadrature_tolerance=d.rt_quadrature_tolerance, rt_diffraction_warning=False)


def _auto_fo(fo: FO, path: str, field_beam: bool) -> FO:
    """The FO auto runs on ``path``: its grid and window where that is the 2-D path of a Gaussian beam."""
    if field_beam:
        return FO(max_spectrum_grid=fo.max_spectrum_grid)
    if path == "radial":
        return FO(path="radial", max_spectrum_grid=fo.max_spectrum_grid)
    return dataclasses.replace(fo, path=path)


def _rt_options(model: RT, tolerance: float, threads: int):
    options = _core.RtOptions()
    options.tolerance, options.threads, options.max_segments = tolerance, threads, model.max_segments
    return options


def _fan_options(model: RT, tolerance: float, threads: int):
    options = _core.RtAberratedOptions()
    options.rings, options.ring_rays, options.tolerance = model.rings, model.ring_rays, tolerance
    options.threads, options.max_segments = threads, model.max_segments
    return options
