"""Overlap and point image of a receiver with aberrations (:class:`Aberrations` on the telescope).

- ``method="rt"``: rays through the pupil displaced by d ∇W on the detector plane. For Zernike terms and
  W040 (the same for every scatterer) with no NA cone and no obstruction in front of the aperture, G is one
  smooth pupil integral of the share of the Gaussian beam image each ray leaves on the detector; otherwise
  each scatterer sends a ray fan (``rings`` x ``ring_rays``) whose detector-edge crossings are interpolated.
- ``method="fo"``: the pupil with its aberrations is sampled and its OTF computed by FFT at each range;
  G is the aberration-free radial result plus the Parseval sum of the OTF's change (docs/aberrations.md).
  Field-dependent Seidel terms need ``"rt"``; near ranges whose defocus blur needs a transform beyond
  ``max_grid`` raise ValueError (the blur is geometric there: use ``"rt"``).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from . import _checks, _core
from .fields import Field
from .field_beam import FieldBeam
from .result import OverlapResult

#: Accuracy of the FO path at its default tail_error, measured against finer sampling (docs/aberrations.md).
FO_ABERRATED_ACCURACY = 2e-6


def overlap_aberrated(system, z: np.ndarray, method: str, tolerance: float, threads: int, max_grid: int,
                      rings: int = 48, ring_rays: int = 128, tail_error: float = 1e-4) -> OverlapResult:
    """G(z) of an aberrated ``system`` (called by :func:`lidar_overlap.overlap`; arguments checked there)."""
    if isinstance(system.beam, FieldBeam):
        raise ValueError("aberrations with a FieldBeam are not modelled: expected a GaussianBeam (the aberrated "
                         "paths weight the point image by the Gaussian beam image)")
    ab = system.telescope.aberrations
    if method == "auto":
        raise ValueError("method = 'auto' is not available with aberrations yet: expected 'rt' or 'fo'")
    if method == "rt":
        raw = _rt(system, z, tolerance, threads, rings, ring_rays)
        return OverlapResult(ranges=z, overlap=np.asarray(raw["overlap"]), method="rt",
                             error_estimate=np.asarray(raw["error_estimate"]), system=system, tolerance=tolerance)
    raw = _core.overlap_fo_aberrated(system._native, ab._native, z, max_grid, tail_error, threads)
    return OverlapResult(ranges=z, overlap=np.asarray(raw["overlap"]), method="fo",
                         error_estimate=np.full(z.size, FO_ABERRATED_ACCURACY), system=system,
                         tolerance=float("nan"))


def _rt(system, z, tolerance, threads, rings, ring_rays) -> dict:
    return _core.overlap_rt_aberrated(system._native, system.telescope.aberrations._native, z, rings, ring_rays,
                                      tolerance, 32, threads, 4000)


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
    ab = t.aberrations if t.aberrations is not None else _ideal()
    d = t.focal_length + system.detector.defocus
    if spacing is None:
        spacing = system.beam.wavelength * d / (2.0 * t.diameter)
    values = _core.point_image(system._native, ab._native, z, n, _checks.real("spacing", spacing))
    return Field(values, spacing, system.beam.wavelength)


def _ideal():
    from .aberrations import Aberrations

    return Aberrations()


def with_aberrations(system, aberrations):
    """``system`` with ``aberrations`` on its telescope (a convenience for dataclasses.replace twice)."""
    return dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, aberrations=aberrations))
