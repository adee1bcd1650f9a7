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
from .system import LidarSystem
from .validity import warn_if_rt_invalid

METHODS = ("rt",)


def overlap(system: LidarSystem, ranges: Sequence[float] | np.ndarray, method: str = "rt", *,
            tolerance: float = 1e-4, threads: int = 0, max_segments: int = 4000) -> OverlapResult:
    """Overlap function of ``system`` at each range.

    Parameters
    ----------
    system : the lidar.
    ranges : m, strictly increasing 1-D array; each > 0 and beyond the obstruction distance.
    method : ``"rt"``, paraxial ray tracing (paper Appendix B) with exact circle geometry.
    tolerance : absolute error allowed on G at each range, in (0, 1). The beam integral is adaptive
        (radial with Rice weights about each coupling term's centre of symmetry, two-dimensional where
        there is none) until its error estimate is below it.
    threads : OpenMP threads across ranges; 0 uses all cores. Results do not depend on it.
    max_segments : cap on adaptive subdivisions per integral; reaching it warns (RuntimeWarning).

    Warns (RuntimeWarning) when ray tracing is used outside its validity: a detector within a few
    tens of Airy radii, or ranges so short that paraxial slopes err by more than 1 %
    (see :mod:`lidar_overlap.validity`).
    """
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {system!r} is invalid: expected a LidarSystem")
    _checks.choice("method", method, METHODS)
    z = _checks.ranges("ranges", ranges)
    tolerance = _checks.unit_interval("tolerance", tolerance)
    threads = _checks.count("threads", threads, 0)
    max_segments = _checks.count("max_segments", max_segments, 1)
    raw = _core.overlap_rt(system._native, z, tolerance, threads, max_segments)  # validates the ranges
    warn_if_rt_invalid(system, z)
    converged = np.asarray(raw["converged"], dtype=bool)
    if not converged.all():
        worst = float(np.max(raw["error_estimate"][~converged]))
        warnings.warn(f"overlap: tolerance {tolerance:g} not reached at {int((~converged).sum())} of {z.size} "
                      f"ranges (largest error estimate {worst:.3g}); raise max_segments or loosen tolerance",
                      RuntimeWarning, stacklevel=2)
    return OverlapResult(ranges=z, overlap=np.asarray(raw["overlap"]), method="rt",
                         error_estimate=np.asarray(raw["error_estimate"]), system=system, tolerance=tolerance)


def emitter_coupling(system: LidarSystem, z: float, position: Sequence[float] = (0.0, 0.0),
                     method: str = "rt") -> float:
    """Coupling of one point scatterer at transverse ``position`` (x, y in m) and range ``z`` (m):
    power reaching the detector over the power it sends into the full, unobstructed aperture."""
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {system!r} is invalid: expected a LidarSystem")
    _checks.choice("method", method, METHODS)
    return _core.emitter_coupling_rt(system._native, _checks.real("z", z), _checks.pair("position", position))


def optimal_focus_range(focal_length: float, defocus: float) -> float:
    """Range (m) best focused on a detector displaced ``defocus`` (m, >= 0) behind the focal plane of a
    lens of ``focal_length`` (m): z_opt = f (f + δf) / δf, the paper's Eq. (5); ``inf`` for δf = 0."""
    return _core.optimal_focus_range(_checks.real("focal_length", focal_length), _checks.real("defocus", defocus))
