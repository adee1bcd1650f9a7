"""The image a point scatterer makes on the detector plane through the receiver and its
aberrations."""

from __future__ import annotations

from .. import _checks, _core
from ..model.aberrations import Aberrations
from ..model.field import Field


def point_image(system, z: float, n: int = 256, spacing: float | None = None) -> Field:
    """The image (complex amplitude, detector plane) of a point scatterer on the axis at range ``z``
    (m), through the telescope's pupil with its defocus at that range and its Zernike aberrations
    (W040 too).

    ``n`` samples per side at ``spacing`` (m; default λd/(2D), two samples per Airy-ring period),
    centred on the geometric image. Normalised so that ``(abs(values)**2).sum() * spacing**2`` is
    the share of the full aperture's power that the pupil passes (1 without obstruction, less the
    part outside the window). The Strehl ratio is ``abs(values[n//2, n//2])**2`` over the same for
    the ideal receiver.
    """
    n = _checks.count("n", n, 8)
    z = _checks.real("z", z)
    ab = system.telescope.aberrations if system.telescope.aberrations is not None else Aberrations()
    if spacing is None:
        spacing = 0.5 * system.diffraction_blur
    values = _core.point_image(system._native, ab._native, z, n, _checks.real("spacing", spacing))
    return Field(values, spacing, system.beam.wavelength)
