"""Where the ray-tracing model stops describing the physics, and by how much.

RT (paper Appendix B) is paraxial geometric optics. Two things break it:
- diffraction at the receiver: a point scatterer images to an Airy pattern, not a point, and the part
  of it beyond the detector edge is lost. For a centred image the lost fraction is 1 - EE(v) with
  v = π D r_d / (λ f); its large-v asymptote 2/(π v) = 2 λ f / (π² D r_d) is the RT model error at full
  overlap. Fourier optics (method "fo") includes it.
- the paraxial approximation: ray slopes of about R / z must stay small; the error grows like slope².
"""

from __future__ import annotations

import math
import warnings

import numpy as np

#: Model errors above this fraction of G trigger a RuntimeWarning from the RT path.
RT_MODEL_ERROR_LIMIT = 0.01


def rt_diffraction_error(system) -> float:
    """Fraction of a focused point image's power that diffraction moves beyond the detector edge,
    2 λ f / (π² D r_d): the geometric-optics error of RT where the overlap is full."""
    t, d = system.telescope, system.detector
    return 2.0 * system.beam.wavelength * (t.focal_length + d.defocus) / (math.pi**2 * t.diameter * d.radius)


def rt_paraxial_error(system, ranges: np.ndarray) -> float:
    """Relative error of the paraxial slope tan u ≈ u at the steepest ray: (R / z_min)² / 3."""
    slope = 0.5 * system.telescope.diameter / float(np.min(ranges))
    return slope**2 / 3.0


def warn_if_rt_invalid(system, ranges: np.ndarray, stacklevel: int = 3) -> None:
    """Warn when RT is used where its model error exceeds RT_MODEL_ERROR_LIMIT."""
    diffraction = rt_diffraction_error(system)
    if diffraction > RT_MODEL_ERROR_LIMIT:
        airy = 1.22 * system.beam.wavelength * system.telescope.focal_length / system.telescope.diameter
        warnings.warn(
            f"ray tracing outside its validity: the detector radius is {system.detector.radius / airy:.3g} Airy "
            f"radii, and diffraction moves about {diffraction:.2%} of the image power across its edge; "
            "geometric optics ignores this. Use Fourier optics (method='fo') for this receiver.",
            RuntimeWarning, stacklevel=stacklevel)
    paraxial = rt_paraxial_error(system, ranges)
    if paraxial > RT_MODEL_ERROR_LIMIT:
        warnings.warn(
            f"ray tracing outside its validity: at {float(np.min(ranges)):.3g} m the aperture is seen under slopes "
            f"whose paraxial error is about {paraxial:.2%}; start the ranges farther away.",
            RuntimeWarning, stacklevel=stacklevel)
