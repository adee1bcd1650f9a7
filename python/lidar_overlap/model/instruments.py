"""Starting systems of widespread lidar classes, from their published designs, for fits of measured
overlap curves (SI units). Each states which values its sources give and which are assumptions:
the assumed ones (axis separation, expanded beam size, obstruction) differ between units and are
what a fit of the unit's overlap curve should free. Where the sources bound an assumed value, the
preset's ``*_bounds`` function gives those bounds ({path: (low, high)}, SI units) and the system
it makes carries them as its ``fit_bounds``: every fit takes them as its default bounds, under the
caller's ``bounds`` (``dataclasses.replace(system, fit_bounds=None)`` drops them). A fitted value
that ends on one is named in the result's ``at_bounds``.
"""

from __future__ import annotations

import math
from typing import Optional

from .system import Detector, GaussianBeam, LidarSystem, Telescope

_CHANNELS = ("far", "near")
#: PollyXT: a divergence of "a few tenths of a mrad" (the sources), taken as 0.05-1 mrad (1/e²
#: half-angle), a factor of two beyond either end of that phrase.
POLLYXT_DIVERGENCE = (0.05e-3, 1.0e-3)
#: CHM15k: the laser's divergence below 0.3 mrad full angle (the manual), 0.15 mrad half-angle.
CHM15K_MAX_DIVERGENCE = 0.15e-3
#: CHM15k: the 90 mm expanded beam (45 mm radius) beside the 0.1 m lens (0.05 m radius): their
#: axes at least 0.095 m apart (the beam cannot leave through the lens), at most 0.5 m (one
#: housing).
CHM15K_OFFSET = (0.095, 0.5)
#: CHM15k: 1064 nm, the expanded beam's 1/e² radius (m).
CHM15K_WAVELENGTH, CHM15K_BEAM_RADIUS = 1064e-9, 45e-3


def pollyxt(
    channel: str = "far",
    wavelength: float = 355e-9,
    beam_offset: float = 0.2,
    beam_tilt: float = 0.0,
    divergence: float = 0.2e-3,
    numerical_aperture: Optional[float] = None,
) -> LidarSystem:
    """A PollyXT multiwavelength Raman lidar (biaxial; the network's automated instrument).

    Sources: Althausen, D., et al. (2009), Portable Raman lidar PollyXT for automated profiling of
    aerosol backscatter, extinction, and depolarization, J. Atmos. Oceanic Technol. 26, 2366-2378,
    doi:10.1175/2009JTECHA1304.1; Engelmann, R., et al. (2016), The automated multiwavelength
    Raman polarization and water-vapor lidar PollyXT: the neXT generation, Atmos. Meas. Tech. 9,
    1767-1784, doi:10.5194/amt-9-1767-2016.

    From the sources: far range, a Newtonian telescope with a 0.3 m primary of 0.9 m focal length
    and a 1 mrad full field of view; near range, a 50 mm refractor with a 2.2 mrad full field of
    view; a flash-lamp-pumped Nd:YAG laser (355, 532, 1064 nm) whose beam is expanded before it
    leaves the instrument, with a divergence of a few tenths of a mrad.

    Assumed (fit them): ``beam_offset`` (m, the beam axis's distance from the receiver axis, along
    x), ``beam_tilt`` (rad, along x), ``divergence`` (rad, 1/e² half-angle), the expanded beam's
    1/e² radius (15 mm), and for the far range a secondary mirror of 35 mm radius 0.6 m in front of
    the primary's aperture stop; the near-range refractor has no obstruction, its focal length is
    taken as 0.2 m. ``numerical_aperture``: the acceptance of the field stop's relay (None: every
    ray; give a value, e.g. 0.22, to fit it). ``channel``: ``"far"`` or ``"near"``. The system's
    ``fit_bounds`` are :func:`pollyxt_bounds`.
    """
    if channel not in _CHANNELS:
        raise ValueError(f"channel = {channel!r} is invalid: expected 'far' or 'near'")
    if channel == "far":
        telescope = Telescope(
            diameter=0.3, focal_length=0.9, obstruction_radius=0.035, obstruction_distance=0.6
        )
        detector = Detector.from_fov(
            fov=1.0e-3, focal_length=0.9, numerical_aperture=numerical_aperture
        )
    else:
        telescope = Telescope(diameter=0.05, focal_length=0.2)
        detector = Detector.from_fov(
            fov=2.2e-3, focal_length=0.2, numerical_aperture=numerical_aperture
        )
    beam = GaussianBeam(
        wavelength=wavelength,
        waist_radius=15e-3,
        divergence=divergence,
        offset=(beam_offset, 0.0),
        tilt=(beam_tilt, 0.0),
    )
    return LidarSystem(
        beam=beam, telescope=telescope, detector=detector, fit_bounds=pollyxt_bounds()
    )


def chm15k(beam_offset: float = 0.1, beam_tilt: float = 0.0) -> LidarSystem:
    """A CHM 15k class ceilometer: a biaxial 1064 nm lidar with a diode-pumped microchip Nd:YAG
    laser, the most widespread aerosol ceilometer in European networks.

    Sources: Lufft CHM 15k operating manual (technical data: beam expanded to 90 mm, laser
    divergence below 0.3 mrad, receiver field of view 0.45 mrad); Heese, B., et al. (2010),
    Ceilometer lidar comparison: backscatter coefficient retrieval and signal-to-noise ratio
    determination, Atmos. Meas. Tech. 3, 1763-1770, doi:10.5194/amt-3-1763-2010; Hervo, M., et
    al. (2016), An empirical method to correct for temperature-dependent variations in the overlap
    function of CHM15k ceilometers, Atmos. Meas. Tech. 9, 2947-2959,
    doi:10.5194/amt-9-2947-2016 (full overlap from several hundred metres to a few km).

    From the sources: 1064 nm; a 45 mm 1/e² beam radius (the 90 mm expanded beam); a divergence
    below 0.3 mrad, read as a full angle (0.15 mrad 1/e² half-angle: as a half-angle it would exceed
    the 0.225 mrad half field of view and full overlap would never be reached); a 0.45 mrad full
    field of view. Assumed (fit them):
    a 0.1 m receiver lens of 0.5 m focal length, ``beam_offset`` (m, along x) and ``beam_tilt``
    (rad, along x). The system's ``fit_bounds`` are :func:`chm15k_bounds`.
    """
    beam = GaussianBeam(
        wavelength=CHM15K_WAVELENGTH,
        waist_radius=CHM15K_BEAM_RADIUS,
        divergence=0.15e-3,
        offset=(beam_offset, 0.0),
        tilt=(beam_tilt, 0.0),
    )
    telescope = Telescope(diameter=0.1, focal_length=0.5)
    return LidarSystem(
        beam=beam,
        telescope=telescope,
        detector=Detector.from_fov(fov=0.45e-3, focal_length=0.5),
        fit_bounds=chm15k_bounds(),
    )


def pollyxt_bounds() -> dict:
    """Default fit bounds of a :func:`pollyxt` system that its sources allow: the divergence
    (rad)."""
    return {"beam.divergence": POLLYXT_DIVERGENCE}


def chm15k_bounds() -> dict:
    """Default fit bounds of a :func:`chm15k` system that its sources allow: the divergence (rad;
    from 1.05 times the diffraction limit of the 90 mm expanded beam to the manual's upper value)
    and the axis separation beside the expanded beam (m)."""
    limit = 1.05 * CHM15K_WAVELENGTH / (math.pi * CHM15K_BEAM_RADIUS)
    return {
        "beam.divergence": (limit, CHM15K_MAX_DIVERGENCE),
        "beam.offset[0]": CHM15K_OFFSET,
    }
