"""Atmospheric turbulence along the lidar's line of sight (paper Section 3, step 2; SI units).

``Turbulence`` describes Cn² along the path (a constant, the Hufnagel–Valley 5/7 model, or any function of
height) and gives the weak-fluctuation quantities of a path: Fried parameter, Rytov variance, isoplanatic
angle, and the beam wander and long-term spread of a collimated Gaussian beam (after Andrews & Phillips,
"Laser Beam Propagation through Random Media", 2nd ed.; see ``cpp/include/lidar_overlap/turbulence.hpp``).

``lo.overlap(system, ranges, method, turbulence=..., realizations=K, seed=...)`` returns a
:class:`TurbulentOverlapResult`: the mean overlap over K realisations of the atmosphere and its spread.
- FO: the beam is carried through phase screens (modified von Kármán, FFT with subharmonics) by
  split-step Fresnel propagation, one realisation per draw of the screens (C++, in parallel).
- RT: each realisation is the short-term beam (radius W_ST) displaced by a random wander drawn from a
  Gaussian whose per-axis variance (W_LT² − W_ST²)/4 makes the short-term beam, averaged over it, the
  long-term beam W_LT; the mean overlap is then that of the long-term beam (G is linear in the irradiance).
  With Andrews & Phillips' W_ST² = W_LT² − <r_c²> that 2-D wander variance is <r_c²>/2, 2^(-1/3) = 0.79
  times the centroid variance of the FO screens for a collimated beam: the RT band is a little narrower.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Callable, Optional, Union

import numpy as np

from . import _checks, _core
from ._checks import check_memory, choice
from .result import OverlapResult

#: Percentiles of the spread band reported per range.
BAND = (5.0, 95.0)
#: Cn² (m^-2/3) a profile may reach: the core's bound, a thousand times the strongest turbulence measured
#: near the ground.
MAX_CN2 = 1e-9
#: Realisations one turbulent overlap may draw (the core's bound on the FO path).
MAX_REALIZATIONS = 1_000_000
#: Bytes per sample (realisation x range) of the RT path: the samples and the copies percentile and std make.
BYTES_PER_SAMPLE = 32


class Turbulence:
    """Cn² along the path and the path geometry.

    Parameters
    ----------
    cn2 : m^-2/3: a constant, ``"hv57"`` (Hufnagel–Valley 5/7: r0 = 5 cm and θ0 = 7 µrad at 0.5 µm from the
        ground to space), or a function of the height above ground (m).
    elevation : rad, angle of the line of sight above the horizon, in (0, π/2]; range z is at height
        altitude + z sin(elevation).
    altitude : m, the lidar's height above ground.
    outer_scale, inner_scale : m, L0 and l0 of the phase screens (inf and 0: Kolmogorov).
    hv_ground, hv_wind : the Hufnagel–Valley ground term A (m^-2/3) and rms wind (m/s) for ``"hv57"``.
    """

    def __init__(self, cn2: Union[float, str, Callable[[float], float]] = "hv57", *, elevation: float = math.pi / 2,
                 altitude: float = 0.0, outer_scale: float = math.inf, inner_scale: float = 0.0,
                 hv_ground: float = 1.7e-14, hv_wind: float = 21.0) -> None:
        if isinstance(cn2, str):
            choice("cn2", cn2, ("hv57",))
            native = _core.Cn2Profile.hufnagel_valley(_checks.real("hv_ground", hv_ground), _checks.real("hv_wind", hv_wind))
        elif callable(cn2):
            native = _core.Cn2Profile.custom(_checked_profile(cn2))
        else:
            native = _core.Cn2Profile.constant(_checks.real("cn2", cn2))
        native.elevation = _checks.real("elevation", elevation)
        native.altitude = _checks.real("altitude", altitude)
        native.outer_scale = _checks.real("outer_scale", outer_scale)
        native.inner_scale = _checks.real("inner_scale", inner_scale)
        native.validate()
        self.cn2, self._native = cn2, native

    def cn2_at_range(self, z: float) -> float:
        """Cn² (m^-2/3) at range z (m), 0 <= z <= 1e10 m."""
        z = _checks.real("z", z)
        if not 0.0 <= z <= _core.MAX_LENGTH:
            raise ValueError(f"z = {z!r} is invalid: expected a range from 0 to {_core.MAX_LENGTH:g} m")
        return self._native.cn2_at_range(z)

    def fried_parameter(self, wavelength: float, path_length: float, wave: str = "spherical") -> float:
        """r0 (m) over [0, path_length]: ``"spherical"`` (a point source at the lidar) or ``"plane"``."""
        choice("wave", wave, ("spherical", "plane"))
        f = self._native.fried_parameter_spherical if wave == "spherical" else self._native.fried_parameter_plane
        return f(*_reals(wavelength=wavelength, path_length=path_length))

    def rytov_variance(self, wavelength: float, path_length: float) -> float:
        """Plane-wave Rytov variance σ_R² (weak fluctuations below ~1); wavelength and path_length in m."""
        return self._native.rytov_variance(*_reals(wavelength=wavelength, path_length=path_length))

    def isoplanatic_angle(self, wavelength: float, path_length: float) -> float:
        """θ0 (rad) seen from the lidar; wavelength and path_length in m."""
        return self._native.isoplanatic_angle(*_reals(wavelength=wavelength, path_length=path_length))

    def beam_wander_variance(self, waist_radius: float, wavelength: float, path_length: float) -> float:
        """Andrews & Phillips' beam-wander variance <r_c²> (m², 2-D) of a collimated Gaussian beam at
        path_length, 2.42 Cn² L³ W0^(-1/3) for a constant Cn². It is the large-scale part of their W_LT²
        (eddies filtered by exp(-κ² W0²)); the centroid of the irradiance-weighted tilt, which the FO
        screens reproduce, has 2^(-2/3) = 0.63 of it."""
        return self._native.beam_wander_variance(
            *_reals(waist_radius=waist_radius, wavelength=wavelength, path_length=path_length))

    def long_term_radius(self, waist_radius: float, wavelength: float, path_length: float) -> float:
        """W_LT (m): the 1/e² radius of the Gaussian core of the beam averaged over time (spread and wander),
        set by its mean irradiance on the axis. The second-moment radius of that mean irradiance is
        larger: scattered light makes its wings, unbounded for a zero inner scale."""
        return self._native.long_term_radius(
            *_reals(waist_radius=waist_radius, wavelength=wavelength, path_length=path_length))

    def short_term_radius(self, waist_radius: float, wavelength: float, path_length: float) -> float:
        """W_ST (m): the instantaneous beam's radius about its wandering centre, sqrt(W_LT² − <r_c²>)."""
        return self._native.short_term_radius(
            *_reals(waist_radius=waist_radius, wavelength=wavelength, path_length=path_length))

    def __repr__(self) -> str:
        return f"Turbulence(cn2={self.cn2!r}, elevation={self._native.elevation:.4g} rad)"


def _reals(**values) -> list:
    """Each value as a float, refused by name unless it is a real number (the core checks its range)."""
    return [_checks.real(name, value) for name, value in values.items()]


def _checked_profile(cn2: Callable[[float], float]) -> Callable[[float], float]:
    """The caller's Cn²(height) function, its answers checked and named ``cn2(<height> m)``: a real number from
    0 to MAX_CN2 m^-2/3."""
    def at(height: float) -> float:
        name = f"cn2({height:.6g} m)"
        value = _checks.real(name, cn2(height))
        if not 0.0 <= value <= MAX_CN2:
            raise ValueError(f"{name} = {value!r} is invalid: expected a value from 0 to {MAX_CN2:g} m^-2/3")
        return value
    return at


@dataclass(frozen=True)
class TurbulentOverlapResult(OverlapResult):
    """An :class:`OverlapResult` whose ``overlap`` is the mean over ``realizations`` (K × N array, one
    row per draw of the atmosphere), with ``std`` and the 5–95 % percentile band ``low``, ``high``."""

    realizations: Optional[np.ndarray] = None
    std: Optional[np.ndarray] = None
    low: Optional[np.ndarray] = None
    high: Optional[np.ndarray] = None


def _statistics(system, z, samples, method, tolerance) -> TurbulentOverlapResult:
    low, high = np.percentile(samples, BAND, axis=0)
    k = samples.shape[0]
    std = samples.std(axis=0, ddof=1) if k > 1 else np.zeros(z.size)
    return TurbulentOverlapResult(ranges=z, overlap=samples.mean(axis=0), method=method,
                                  error_estimate=std / math.sqrt(k), system=system, tolerance=tolerance,
                                  realizations=samples, std=std, low=low, high=high)


def _spread(beam, z: float, radius: float) -> float:
    """Far-field half-angle (rad) of a beam from ``beam``'s waist, on its width law, whose 1/e² radius at range
    z (m) is ``radius``."""
    w0 = beam.waist_radius
    if beam.width_law == "linear":                          # w = w0 + θz
        return max(radius - w0, 0.0) / z
    return math.sqrt(max(radius**2 - w0**2, 0.0)) / z      # w² = w0² + (θz)²


def _beam_for(beam, z: float, radius: float, center=(0.0, 0.0)):
    """A Gaussian beam whose 1/e² radius at range z is ``radius`` and whose centre there is ``center``."""
    axis = beam.center(z)
    offset = (axis[0] + center[0], axis[1] + center[1])
    return dataclasses.replace(beam, divergence=max(_spread(beam, z, radius), beam.half_angle_divergence),
                               offset=offset, tilt=(0.0, 0.0))


def _check_rt_work(z: np.ndarray, realizations: int) -> None:
    """Refuse, naming ``realizations``, more draws than the FO path allows or samples beyond the memory budget."""
    if realizations > MAX_REALIZATIONS:
        raise ValueError(f"realizations = {realizations} is invalid: expected a count from 1 to {MAX_REALIZATIONS}")
    check_memory("realizations", realizations, BYTES_PER_SAMPLE * realizations * z.size,
                 "lower realizations or the number of ranges")


def overlap_rt_turbulent(system, z: np.ndarray, turbulence: Turbulence, realizations: int, seed: int,
                         tolerance: float) -> TurbulentOverlapResult:
    """RT through turbulence (see the module docstring); one RT call per range and realisation. A range the
    plain overlap refuses, or where the turbulent beam leaves the paraxial model (it spreads or wanders
    beyond its angles or lengths), is refused naming ``ranges[i]`` and the turbulence."""
    from .auto import validate_ranges
    from .overlap import overlap

    validate_ranges(system, z)
    _check_rt_work(z, realizations)
    beam, lam = system.beam, system.beam.wavelength
    rng = np.random.default_rng(seed)
    samples = np.empty((realizations, z.size))
    for i, zi in enumerate(z):
        where = f"ranges[{i}] = {float(zi)!r} m with turbulence = {turbulence!r}"
        st = turbulence.short_term_radius(beam.waist_radius, lam, zi)
        lt = turbulence.long_term_radius(beam.waist_radius, lam, zi)
        if _spread(beam, zi, st) > _core.MAX_ANGLE:
            raise ValueError(f"{where} is invalid: the short-term beam there ({st:.4g} m) spreads at "
                             f"{_spread(beam, zi, st):.4g} rad, beyond the paraxial model's {_core.MAX_ANGLE:g} rad; "
                             "expected weaker turbulence (cn2) or shorter ranges")
        sigma = 0.5 * math.sqrt(max(lt**2 - st**2, 0.0))   # per axis: W_LT^2 / 4 = W_ST^2 / 4 + sigma^2
        for k in range(realizations):
            shift = rng.normal(0.0, sigma, 2)
            try:
                s = dataclasses.replace(system, beam=_beam_for(beam, zi, st, shift))
            except ValueError as exc:       # the drawn beam's offset or divergence beyond the core's scales
                raise ValueError(f"{where} is invalid: ray tracing cannot model the wandering beam there "
                                 f"({exc}); its axis (offset + tilt x range) and wander must stay within the model's "
                                 "lengths and angles: expected shorter ranges, a smaller tilt or weaker turbulence "
                                 "(cn2)") from None
            samples[k, i] = overlap(s, [zi], "rt", tolerance=tolerance).overlap[0]
    return _statistics(system, z, samples, "rt", tolerance)


def overlap_fo_turbulent(system, z: np.ndarray, turbulence: Turbulence, realizations: int, seed: int,
                         screens: int, beam_grid: int, beam_window: float, threads: int) -> TurbulentOverlapResult:
    """FO through phase screens (see the module docstring)."""
    options = _core.TurbulenceOptions(realizations=realizations, screens=screens, seed=seed, beam_grid=beam_grid,
                                      beam_window=beam_window, threads=threads)
    raw = _core.overlap_fo_turbulent(system._native, z, turbulence._native, options)
    return _statistics(system, z, raw.overlap, "fo", float("nan"))
