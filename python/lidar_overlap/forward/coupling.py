"""One point scatterer: its coupling to the detector, and the range a defocused detector sees
sharpest."""

from __future__ import annotations

from typing import Sequence

from .. import _checks, _core
from ..model.system import LidarSystem

METHODS = ("rt", "fo")


def emitter_coupling(
    system: LidarSystem, z: float, position: Sequence[float] = (0.0, 0.0), method: str = "rt"
) -> float:
    """Coupling of one point scatterer at transverse ``position`` (x, y in m) and range ``z`` (m):
    power reaching the detector over the power it sends into the full, unobstructed aperture.
    ``method="rt"``: geometric (a uniform circle of confusion; with aberrations, a ray fan displaced
    by d ∇W, finer than the overlap's since one scatterer is not averaged over a beam; with
    ``telescope.mask``, the part through the mask); ``"fo"``: with diffraction (for an in-focus
    point, the Airy encircled energy within the detector)."""
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {system!r} is invalid: expected a LidarSystem")
    _checks.choice("method", method, METHODS + ("auto",))
    z, position = _checks.real("z", z), _checks.pair("position", position)
    mask = system.telescope.mask
    if mask is not None:
        if method != "rt" or system.aberrated:
            raise ValueError(
                "emitter_coupling with telescope.mask is modelled by ray tracing without "
                "aberrations only: use method='rt' and telescope.aberrations=None"
            )
        return _core.emitter_coupling_rt_masked(system._native, z, position, mask._native)
    if system.aberrated:
        if method == "fo":
            raise ValueError(
                "emitter_coupling(method='fo') with aberrations is not modelled: use method='rt' "
                "(rays displaced by the wavefront slope) or lo.point_image for the image itself"
            )
        aberrations = system.telescope.aberrations
        assert aberrations is not None  # system.aberrated
        return _core.emitter_coupling_rt_aberrated(system._native, aberrations._native, z, position)
    couple = _core.emitter_coupling_fo if method == "fo" else _core.emitter_coupling_rt
    return couple(system._native, z, position)


def optimal_focus_range(focal_length: float, defocus: float) -> float:
    """Range (m) best focused on a detector displaced ``defocus`` (m, >= 0) behind the focal plane
    of a lens of ``focal_length`` (m): z_opt = f (f + δf) / δf, the paper's Eq. (5); ``inf`` for δf
    = 0."""
    return _core.optimal_focus_range(
        _checks.real("focal_length", focal_length), _checks.real("defocus", defocus)
    )
