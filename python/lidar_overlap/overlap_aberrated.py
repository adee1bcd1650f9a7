"""Overlap and point image of a receiver with aberrations (:class:`Aberrations` on the telescope).

- ``method="rt"``: rays through the pupil displaced by d ∇W on the detector plane. For Zernike terms and
  W040 (the same for every scatterer) with no NA cone and no obstruction in front of the aperture, G is one
  smooth pupil integral of the share of the Gaussian beam image each ray leaves on the detector; otherwise
  each scatterer sends a ray fan (``rings`` x ``ring_rays``) whose detector-edge crossings are interpolated.
- ``method="fo"``: the pupil with its aberrations is sampled and its OTF computed by FFT at each range;
  G is the aberration-free radial result plus the Parseval sum of the OTF's change (docs/aberrations.md).
  Field-dependent Seidel terms need ``"rt"``; near ranges whose defocus blur needs a transform beyond
  ``max_grid`` raise ValueError (the blur is geometric there: use ``"rt"``).
- ``method="auto"``: ray tracing when its first-order diffraction error estimate
  (:func:`rt_diffraction_estimate`) fits the tolerance, Fourier optics otherwise; field-dependent Seidel
  terms always take ray tracing (with a warning when the estimate exceeds the tolerance).
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from . import _checks, _core
from .aberrations import Aberrations
from .fields import Field
from .field_beam import FieldBeam
from .result import OverlapResult
from .validity import rt_diffraction_error, warn_if_rt_invalid, warn_if_rt_unconverged

#: Accuracy of the FO path at its default tail_error, measured against finer sampling (docs/aberrations.md).
FO_ABERRATED_ACCURACY = 5e-6
#: Factor on the first-order estimate of RT's diffraction error (largest measured actual/estimate: see docs).
RT_ESTIMATE_SAFETY = 1.25
#: Ranges on which the edge term is sampled (it varies smoothly along the curve).
EDGE_SAMPLES = 16
#: Segments per direction of the two edge curves' beam integrals. They share one adaptive layout, so their
#: difference settles long before either curve: 8 segments give it within 0.2 % of 4000 segments at a fifth of
#: the time (a field-dependent scene at 20 km where each curve stops ~2e-4 short of convergence).
EDGE_MAX_SEGMENTS = 8


def overlap_aberrated(system, z: np.ndarray, method: str, tolerance: float, threads: int, max_grid: int,
                      rings: int = 48, ring_rays: int = 128, tail_error: float = 1e-4) -> OverlapResult:
    """G(z) of an aberrated ``system`` (called by :func:`lidar_overlap.overlap`; arguments checked there)."""
    if isinstance(system.beam, FieldBeam):
        raise ValueError("aberrations with a FieldBeam are not modelled: expected a GaussianBeam (the aberrated "
                         "paths weight the point image by the Gaussian beam image)")
    ab = system.telescope.aberrations
    if method == "auto":
        decision = decide_aberrated(system, z, tolerance, threads, rings, ring_rays)
        if decision.method == "rt":
            if decision.rt_model_error + decision.rt_quadrature_tolerance > tolerance:
                warnings.warn(f"overlap(auto): field-dependent Seidel terms need ray tracing, whose diffraction error "
                              f"here may reach {decision.rt_model_error:.2g} > tolerance {tolerance:g}",
                              RuntimeWarning, stacklevel=3)
            raw = _checked(system, z, decision.rt_raw, decision.rt_quadrature_tolerance, diffraction=False)
            return OverlapResult(ranges=z, overlap=raw.overlap, method="rt",
                                 error_estimate=raw.error_estimate + decision.rt_model_error,
                                 system=system, tolerance=tolerance)
        res = overlap_aberrated(system, z, "fo", tolerance, threads, max_grid, rings, ring_rays, tail_error)
        return dataclasses.replace(res, tolerance=tolerance)
    if method == "rt":
        raw = _checked(system, z, _rt(system, z, tolerance, threads, rings, ring_rays), tolerance, diffraction=True)
        return OverlapResult(ranges=z, overlap=raw.overlap, method="rt",
                             error_estimate=raw.error_estimate, system=system, tolerance=tolerance)
    options = _core.FoAberratedOptions(max_grid=max_grid, tail_error=tail_error, threads=threads)
    raw = _core.overlap_fo_aberrated(system._native, ab._native, z, options)
    return OverlapResult(ranges=z, overlap=raw.overlap, method="fo",
                         error_estimate=np.full(z.size, FO_ABERRATED_ACCURACY), system=system,
                         tolerance=float("nan"))


def decide_aberrated(system, z: np.ndarray, tolerance: float, threads: int = 0, rings: int = 48,
                     ring_rays: int = 128):
    """The :class:`lidar_overlap.auto.Decision` for an aberrated system (see the module docstring)."""
    from .auto import Decision

    # Field-dependent Seidel terms take RT whatever its model error: a quadrature far below the tolerance
    # would only make the ray fan (the slow RT form) slower.
    quadrature = (0.1 if system.telescope.aberrations.field_dependent else 0.01) * tolerance
    raw = _rt(system, z, quadrature, threads, rings, ring_rays)
    error = rt_diffraction_estimate(system, z, raw.overlap, threads, rings, ring_rays, tolerance)
    reasons = [f"receiver aberrations: ray tracing displaces each ray by d grad W; its diffraction error here is up "
               f"to {error:.2g} (Airy tail plus edge blur from the aberrated RT curve, x {RT_ESTIMATE_SAFETY})"]
    if error + quadrature <= tolerance:
        reasons.append(f"{error:.2g} + quadrature {quadrature:.1g} <= tolerance {tolerance:g}: ray tracing is enough")
        return Decision("rt", "", error, quadrature, reasons, raw)
    if system.telescope.aberrations.field_dependent:
        reasons.append("field-dependent Seidel terms exist only in ray tracing: RT, whose model error may exceed the "
                       "tolerance")
        return Decision("rt", "", error, quadrature, reasons, raw)
    reasons.append(f"{error:.2g} > tolerance {tolerance:g}: Fourier optics with the sampled aberrated pupil")
    return Decision("fo", "aberrated", error, 0.0, reasons)


def rt_diffraction_estimate(system, z: np.ndarray, g: np.ndarray, threads: int, rings: int = 48,
                            ring_rays: int = 128, tolerance: float = 1e-3) -> float:
    """Largest |G_RT - G_FO| expected of aberrated ray tracing over ``z`` given its curve ``g``: the Airy tail
    beyond the detector edge, e_tail G, plus the edge blur (λd/D)|∂G/∂r_d| (from RT at r_d (1 ± 1e-2) on
    EDGE_SAMPLES ranges), times RT_ESTIMATE_SAFETY. Diffraction spreads each point image by λd/D whatever the
    aberrations; this first-order bound covers the measured RT-FO difference (docs/aberrations.md).

    The two edge curves are computed to 1e-3 x ``tolerance`` (1e-6 at most): their difference over 2 % of r_d
    then errs by far less than the tolerance, and a loose tolerance does not pay for a tight derivative."""
    zs = z if z.size <= EDGE_SAMPLES else np.geomspace(z[0], z[-1], EDGE_SAMPLES)
    r_d, h = system.detector.radius, 1e-2 * system.detector.radius
    up, down = (_rt(dataclasses.replace(system, detector=dataclasses.replace(system.detector, radius=r_d + s)),
                    zs, max(1e-6, 1e-3 * tolerance), threads, rings, ring_rays, EDGE_MAX_SEGMENTS).overlap
                  for s in (h, -h))
    t, d = system.telescope, system.detector
    blur = system.beam.wavelength * (t.focal_length + d.defocus) / t.diameter
    edge = np.interp(np.log(z), np.log(zs), blur * np.abs(up - down) / (2.0 * h))
    return RT_ESTIMATE_SAFETY * float(np.max(rt_diffraction_error(system) * g + edge))


def _checked(system, z: np.ndarray, raw: _core.RtAberratedOverlap, tolerance: float,
             diffraction: bool) -> _core.RtAberratedOverlap:
    """``raw`` after the warnings plain RT gives: outside its validity, or short of its tolerance."""
    warn_if_rt_invalid(system, z, stacklevel=5, diffraction=diffraction)
    warn_if_rt_unconverged(raw, z, tolerance, "loosen the tolerance", stacklevel=5)
    return raw


def _rt(system, z, tolerance, threads, rings, ring_rays, max_segments=4000) -> _core.RtAberratedOverlap:
    options = _core.RtAberratedOptions(rings=rings, ring_rays=ring_rays, tolerance=tolerance, threads=threads,
                                       max_segments=max_segments)
    return _core.overlap_rt_aberrated(system._native, system.telescope.aberrations._native, z, options)


def point_image(system, z: float, n: int = 256, spacing: float | None = None) -> Field:
    """The image (complex amplitude, detector plane) of a point scatterer on the axis at range ``z`` (m),
    through the telescope's pupil with its defocus at that range and its Zernike aberrations (W040 too).

    ``n`` samples per side at ``spacing`` (m; default λd/(2D), two samples per Airy-ring period), centred on
    the geometric image. Normalised so that ``(abs(values)**2).sum() * spacing**2`` is the share of the full
    aperture's power that the pupil passes (1 without obstruction, less the part outside the window). The
    Strehl ratio is ``abs(values[n//2, n//2])**2`` over the same for the ideal receiver.
    """
    n = _checks.count("n", n, 8)
    z = _checks.real("z", z)
    t = system.telescope
    ab = t.aberrations if t.aberrations is not None else Aberrations()
    d = t.focal_length + system.detector.defocus
    if spacing is None:
        spacing = system.beam.wavelength * d / (2.0 * t.diameter)
    values = _core.point_image(system._native, ab._native, z, n, _checks.real("spacing", spacing))
    return Field(values, spacing, system.beam.wavelength)


def with_aberrations(system, aberrations):
    """``system`` with ``aberrations`` on its telescope (a convenience for dataclasses.replace twice)."""
    return dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, aberrations=aberrations))
