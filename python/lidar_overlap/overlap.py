"""Overlap function G(z) and single-scatterer coupling.

G(z) is the power reaching the detector over the power entering the full, unobstructed aperture,
summed over all scatterers at range z weighted by the beam irradiance (so a central obstruction lowers
the far-range value to 1 - (r_obs/R)²).
"""

from __future__ import annotations

import warnings
from typing import Sequence

import numpy as np

from . import _checks, _core
from .result import OverlapResult
from .auto import FO_2D_ACCURACY, FO_RADIAL_ACCURACY, decide, radial_fo_applies
from .field_beam import FieldBeam
from .overlap_aberrated import overlap_aberrated
from .system import LidarSystem
from .fields import EDGE_POWER_LIMIT, SamplingWarning
from .validity import warn_if_rt_invalid, warn_if_rt_unconverged

METHODS = ("rt", "fo", "auto")
FO_PATHS = ("auto", "radial", "2d")


def overlap(system: LidarSystem, ranges: Sequence[float] | np.ndarray, method: str = "rt", *,
            tolerance: float = 1e-4, threads: int = 0, max_segments: int = 4000, fo_path: str = "auto",
            beam_grid: int | None = None, beam_window: float | None = None,
            max_spectrum_grid: int = 4096, turbulence=None, realizations: int = 20, seed: int = 0,
            screens: int = 10) -> OverlapResult:
    """Overlap function of ``system`` at each range.

    Parameters
    ----------
    system : the lidar.
    ranges : m, strictly increasing 1-D array; each > 0 and beyond the obstruction distance.
    method : ``"rt"``, paraxial ray tracing (paper Appendix B) with exact circle geometry; ``"fo"``,
        Fourier optics (Appendix C): the transmitted field propagated to each range, imaged through the
        receiver's pupil with diffraction (see ``docs/fo_overlap.md``). A :class:`FieldBeam` or
        :class:`FlatTopBeam` needs ``"fo"``; a Gaussian beam with M² > 1 is taken in FO as a Gaussian
        Schell-model beam (Gaussian irradiance of radius w(z) at every range). ``"auto"``: the cheapest
        model whose error stays within ``tolerance`` (see :mod:`lidar_overlap.auto` and :func:`explain`).
    tolerance : absolute error allowed on G at each range, in (0, 1). RT: the adaptive beam integral (radial
        with Rice weights about each coupling term's centre of symmetry, two-dimensional where there is
        none) stops when its error estimate is below it. auto: the model error plus the numerical error.
    fo_path : FO with a Gaussian beam: ``"radial"`` (one integral per range, the beam image's offset as J0, no
        grids, exact to ~1e-9), ``"2d"`` (the sampled beam propagated on a grid, ~1e-6), or ``"auto"``
        (radial whenever the scene allows it).
    threads : OpenMP threads across ranges; 0 uses all cores. Results do not depend on it.
    max_segments : RT only: cap on adaptive subdivisions per integral; reaching it warns (RuntimeWarning).
    beam_grid, beam_window : FO with a Gaussian beam only: samples per side of the transmitted field and
        its window in waist radii (default 256 and 10: ±5 w0). A FieldBeam brings its own grid.
    max_spectrum_grid : FO only: cap on the zero-padded beam spectrum (or, with aberrations, on the pupil
        transform), which grows with the defocus blur at short range; a range that needs more raises
        ValueError (use "rt" there).

    With ``system.telescope.aberrations`` set, both methods model them (see
    :mod:`lidar_overlap.overlap_aberrated`); field-dependent Seidel terms need ``"rt"``.

    turbulence : a :class:`Turbulence` along the path, or ``None``. The result is then a
        :class:`TurbulentOverlapResult`: the mean over ``realizations`` draws of the atmosphere
        (reproducible with ``seed``), with ``std`` and a 5–95 % band; ``error_estimate`` is the standard
        error of the mean. FO carries the beam through ``screens`` phase screens (``beam_grid`` samples,
        default 256, over ``beam_window`` long-term radii, default 8); RT displaces the short-term beam
        by the random wander. Zero turbulence gives the turbulence-free result exactly.

    Warns (RuntimeWarning) when ray tracing is used outside its validity: a detector within a few
    tens of Airy radii, or ranges so short that paraxial slopes err by more than 1 %
    (see :mod:`lidar_overlap.validity`).
    """
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {system!r} is invalid: expected a LidarSystem")
    _checks.choice("method", method, METHODS)
    z = _checks.ranges("ranges", ranges)
    system._native.validate_ranges(z)   # before any path derives quantities from them
    tolerance = _checks.unit_interval("tolerance", tolerance)
    threads = _checks.threads(threads)
    max_segments = _checks.count("max_segments", max_segments, 1)
    max_spectrum_grid = _checks.count("max_spectrum_grid", max_spectrum_grid, 16)
    _checks.choice("fo_path", fo_path, FO_PATHS)
    field_beam = isinstance(system.beam, FieldBeam)
    if system.aberrated:
        if turbulence is not None:
            raise ValueError("turbulence with receiver aberrations is not modelled yet: set telescope.aberrations "
                             "to None or turbulence to None")
        return overlap_aberrated(system, z, method, tolerance, threads, max_spectrum_grid)
    if turbulence is not None:
        return _overlap_turbulent(system, z, method, turbulence, _checks.count("realizations", realizations, 1),
                                  _checks.count("seed", seed, 0, 2**64 - 1), _checks.count("screens", screens, 1), tolerance,
                                  beam_grid, beam_window, threads)
    if method == "auto":
        return _overlap_auto(system, z, tolerance, threads, max_segments)
    if field_beam and method == "rt":
        raise ValueError(f"method = 'rt' is invalid for a {type(system.beam).__name__}: ray tracing models Gaussian "
                         "beams only; use method='fo'")
    if field_beam and (beam_grid is not None or beam_window is not None):
        raise ValueError("beam_grid and beam_window apply to Gaussian beams only: a FieldBeam is propagated on its "
                         "own grid")
    if method == "fo" and field_beam:
        f = system.beam.field
        raw = _core.overlap_fo_field(system._native, z, f.values, f.spacing, f.wavelength,
                                     _core.FoOptions(max_spectrum_grid=max_spectrum_grid, threads=threads))
        return _fo_result(system, z, raw, "enlarge the field's grid (zero-pad it)")
    if method == "fo" and (fo_path == "radial" or (fo_path == "auto" and radial_fo_applies(system))):
        if beam_grid is not None or beam_window is not None:
            raise ValueError("beam_grid and beam_window apply to the 2-D FO path only; use fo_path='2d'")
        # axisymmetry checked in the core
        raw = _core.overlap_fo_radial(system._native, z, _core.RadialFoOptions(threads=threads))
        return OverlapResult(ranges=z, overlap=raw.overlap, method="fo",
                             error_estimate=np.full(z.size, FO_RADIAL_ACCURACY), system=system,
                             tolerance=float("nan"))
    if method == "fo":
        options = _core.FoOptions(beam_grid=_checks.count("beam_grid", 256 if beam_grid is None else beam_grid, 16),
                                  beam_window=_checks.real("beam_window", 10.0 if beam_window is None else beam_window),
                                  max_spectrum_grid=max_spectrum_grid, threads=threads)
        raw = _core.overlap_fo(system._native, z, options)
        return _fo_result(system, z, raw, "enlarge beam_window or beam_grid")
    raw = _core.overlap_rt(system._native, z, _core.RtOptions(tolerance=tolerance, threads=threads,
                                                              max_segments=max_segments))  # validates the ranges
    return _rt_result(system, z, raw, tolerance)


def _rt_result(system: LidarSystem, z: np.ndarray, raw: _core.RtOverlap, tolerance: float,
               diffraction_bounded: bool = False) -> OverlapResult:
    """The RT result from the core's output, with the validity and convergence warnings (not the diffraction
    one when auto has bounded RT's diffraction error within its tolerance)."""
    warn_if_rt_invalid(system, z, stacklevel=4, diffraction=not diffraction_bounded)
    warn_if_rt_unconverged(raw, z, tolerance, "raise max_segments or loosen tolerance", stacklevel=4)
    return OverlapResult(ranges=z, overlap=raw.overlap, method="rt",
                         error_estimate=raw.error_estimate, system=system, tolerance=tolerance)


def _overlap_turbulent(system, z, method, turbulence, realizations, seed, screens, tolerance, beam_grid,
                       beam_window, threads):
    from .turbulence import Turbulence, TurbulentOverlapResult, overlap_fo_turbulent, overlap_rt_turbulent

    if not isinstance(turbulence, Turbulence):
        raise ValueError(f"turbulence = {turbulence!r} is invalid: expected a lidar_overlap.Turbulence or None")
    if isinstance(system.beam, FieldBeam):
        raise ValueError("turbulence with a FieldBeam is not modelled yet: expected a GaussianBeam")
    if method == "auto":
        method = decide(system, z, tolerance).method
    if turbulence.rytov_variance(system.beam.wavelength, float(z[-1])) == 0.0:   # no turbulence at all
        plain = overlap(system, z, method, tolerance=tolerance, threads=threads)
        samples = np.tile(plain.overlap, (realizations, 1))
        return TurbulentOverlapResult(ranges=z, overlap=plain.overlap, method=method, error_estimate=np.zeros(z.size),
                                      system=system, tolerance=plain.tolerance, realizations=samples,
                                      std=np.zeros(z.size), low=plain.overlap.copy(), high=plain.overlap.copy())
    if method == "rt":
        return overlap_rt_turbulent(system, z, turbulence, realizations, seed, tolerance)
    return overlap_fo_turbulent(system, z, turbulence, realizations, seed, screens,
                                _checks.count("beam_grid", 256 if beam_grid is None else beam_grid, 32),
                                _checks.real("beam_window", 8.0 if beam_window is None else beam_window), threads)


def _overlap_auto(system: LidarSystem, z: np.ndarray, tolerance: float, threads: int,
                  max_segments: int) -> OverlapResult:
    decision = decide(system, z, tolerance, threads)
    if decision.method == "rt":
        raw = decision.rt_raw   # the RT curve the estimate was made from
        if max_segments != 4000 or not np.all(raw.converged):
            raw = _core.overlap_rt(system._native, z, _core.RtOptions(tolerance=decision.rt_quadrature_tolerance,
                                                                      threads=threads, max_segments=max_segments))
        res = _rt_result(system, z, raw, decision.rt_quadrature_tolerance, diffraction_bounded=True)
        error = res.error_estimate + decision.rt_model_error
    else:
        res = overlap(system, z, "fo", threads=threads, fo_path=decision.fo_path)
        error = np.full(z.size, FO_RADIAL_ACCURACY if decision.fo_path == "radial" else FO_2D_ACCURACY)
    return OverlapResult(ranges=z, overlap=res.overlap, method=res.method, error_estimate=error, system=system,
                         tolerance=tolerance)


def _fo_result(system: LidarSystem, z: np.ndarray, raw: _core.FoOverlap, fix: str) -> OverlapResult:
    for zi, report in zip(z, raw.beam_reports):
        worst = max(report.output_edge_power, report.input_edge_power, report.band_limit_loss)
        if worst > EDGE_POWER_LIMIT:
            warnings.warn(f"overlap(fo): the transmitted field at {zi:.4g} m loses {worst:.2g} of its power to the "
                          f"window edge or the band limit; {fix}", SamplingWarning,
                          stacklevel=3)
    return OverlapResult(ranges=z, overlap=raw.overlap, method="fo",
                         error_estimate=np.full(z.size, FO_2D_ACCURACY), system=system, tolerance=float("nan"))


def emitter_coupling(system: LidarSystem, z: float, position: Sequence[float] = (0.0, 0.0),
                     method: str = "rt") -> float:
    """Coupling of one point scatterer at transverse ``position`` (x, y in m) and range ``z`` (m):
    power reaching the detector over the power it sends into the full, unobstructed aperture.
    ``method="rt"``: geometric (a uniform circle of confusion); ``"fo"``: with diffraction (for an in-focus
    point, the Airy encircled energy within the detector)."""
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {system!r} is invalid: expected a LidarSystem")
    _checks.choice("method", method, METHODS)
    z, position = _checks.real("z", z), _checks.pair("position", position)
    if system.aberrated:
        if method == "fo":
            raise ValueError("emitter_coupling(method='fo') with aberrations is not modelled: use method='rt' "
                             "(rays displaced by the wavefront slope) or lo.point_image for the image itself")
        return _core.emitter_coupling_rt_aberrated(system._native, system.telescope.aberrations._native, z,
                                                   position)  # the core's finer point-coupling fan
    couple = _core.emitter_coupling_fo if method == "fo" else _core.emitter_coupling_rt
    return couple(system._native, z, position)


def optimal_focus_range(focal_length: float, defocus: float) -> float:
    """Range (m) best focused on a detector displaced ``defocus`` (m, >= 0) behind the focal plane of a
    lens of ``focal_length`` (m): z_opt = f (f + δf) / δf, the paper's Eq. (5); ``inf`` for δf = 0."""
    return _core.optimal_focus_range(_checks.real("focal_length", focal_length), _checks.real("defocus", defocus))
