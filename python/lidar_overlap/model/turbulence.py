"""Atmospheric turbulence along the lidar's line of sight (paper Section 3, step 2; SI units).

``Turbulence`` describes Cn² along the path (a constant, the Hufnagel–Valley 5/7 model, or any
function of height) and gives the weak-fluctuation quantities of a path: Fried parameter, Rytov
variance, isoplanatic angle, and the beam wander and long-term spread of a collimated Gaussian beam
(after Andrews & Phillips, "Laser Beam Propagation through Random Media", 2nd ed.; see
``cpp/include/lidar_overlap/turbulence.hpp``).

``lo.overlap(system, ranges, lo.Turbulent(turbulence, method, realizations=K, seed=...))`` (or the
shortcut ``lo.overlap(system, ranges, method, turbulence=..., realizations=K, seed=...)``) returns a
:class:`TurbulentOverlapResult`: the mean overlap over K realisations of the atmosphere and its
spread (computed in :mod:`lidar_overlap.forward.backends.turbulent`).
- FO: the beam is carried through phase screens (modified von Kármán, FFT with subharmonics) by
  split-step Fresnel propagation, one realisation per draw of the screens (C++, in parallel).
- RT: each realisation is the short-term beam (radius W_ST) displaced by a random wander drawn from
  a Gaussian whose per-axis variance (W_LT² − W_ST²)/4 makes the short-term beam, averaged over it,
  the long-term beam W_LT; the mean overlap is then that of the long-term beam (G is linear in the
  irradiance). With Andrews & Phillips' W_ST² = W_LT² − <r_c²> that 2-D wander variance is <r_c²>/2,
  2^(-1/3) = 0.79 times the centroid variance of the FO screens for a collimated beam: the RT band
  is a little narrower. With ``paths="both"`` (the default) the return path tilts the image of the
  scattering volume by its angle of arrival (:meth:`Turbulence.angle_of_arrival_variance`,
  correlated with the wander on the layer model of :mod:`lidar_overlap.model.tilt`) and blurs it.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Callable, Union

import numpy as np

from .. import _checks, _core
from .._checks import choice
from .._pickling import ByArguments
from .tilt import path_tilts

#: Largest mean G with turbulence on both paths: the backscatter amplification of a point receiver
#: in strong turbulence tends to 2 (docs/turbulence.md); a finite aperture and the detector's field
#: of view only lower it.
TWO_WAY_BOUND = 2.0
#: Cn² (m^-2/3) a profile may reach: the core's bound, a thousand times the strongest turbulence
#: measured near the ground.
MAX_CN2 = 1e-9


@dataclass(frozen=True, init=False, repr=False)
class Turbulence(ByArguments):
    """Cn² along the path and the path geometry; immutable (:func:`dataclasses.replace` gives a
    variant).

    Parameters
    ----------
    cn2 : m^-2/3: a constant, ``"hv57"`` (Hufnagel–Valley 5/7: r0 = 5 cm and θ0 = 7 µrad at 0.5 µm
        from the ground to space), or a function of the height above ground (m).
    elevation : rad, angle of the line of sight above the horizon, in (0, π/2]; range z is at height
        altitude + z sin(elevation).
    altitude : m, the lidar's height above ground.
    outer_scale, inner_scale : m, L0 and l0 of the phase screens (inf and 0: Kolmogorov).
    hv_ground, hv_wind : the Hufnagel–Valley ground term A (m^-2/3) and rms wind (m/s) for
        ``"hv57"``.
    """

    cn2: Union[float, str, Callable[[float], float]]
    elevation: float
    altitude: float
    outer_scale: float
    inner_scale: float
    hv_ground: float
    hv_wind: float
    _native: _core.Cn2Profile = dataclasses.field(init=False, repr=False, compare=False)

    def __init__(
        self,
        cn2: Union[float, str, Callable[[float], float]] = "hv57",
        *,
        elevation: float = math.pi / 2,
        altitude: float = 0.0,
        outer_scale: float = math.inf,
        inner_scale: float = 0.0,
        hv_ground: float = 1.7e-14,
        hv_wind: float = 21.0,
    ) -> None:
        # checked whatever cn2 is: a value holds no field it would not accept
        hv = {k: _hv_term(k, v) for k, v in (("hv_ground", hv_ground), ("hv_wind", hv_wind))}
        if isinstance(cn2, str):
            choice("cn2", cn2, ("hv57",))
            native = _core.Cn2Profile.hufnagel_valley(hv["hv_ground"], hv["hv_wind"])
        elif callable(cn2):
            native = _core.Cn2Profile.custom(_checked_profile(cn2))
        else:
            native = _core.Cn2Profile.constant(_checks.real("cn2", cn2))
        native.elevation = _checks.real("elevation", elevation)
        native.altitude = _checks.real("altitude", altitude)
        native.outer_scale = _checks.real("outer_scale", outer_scale)
        native.inner_scale = _checks.real("inner_scale", inner_scale)
        native.validate()
        for name, value in (
            ("cn2", cn2),
            ("elevation", native.elevation),
            ("altitude", native.altitude),
            ("outer_scale", native.outer_scale),
            ("inner_scale", native.inner_scale),
            *hv.items(),
            ("_native", native),
        ):
            object.__setattr__(self, name, value)

    def cn2_at_range(self, z: float) -> float:
        """Cn² (m^-2/3) at range z (m), 0 <= z <= 1e10 m."""
        z = _checks.real("z", z)
        if not 0.0 <= z <= _core.MAX_LENGTH:
            raise ValueError(
                f"z = {z!r} is invalid: expected a range from 0 to {_core.MAX_LENGTH:g} m"
            )
        return self._native.cn2_at_range(z)

    def fried_parameter(
        self, wavelength: float, path_length: float, wave: str = "spherical"
    ) -> float:
        """r0 (m) over [0, path_length]: ``"spherical"`` (a point source at the lidar) or
        ``"plane"``."""
        choice("wave", wave, ("spherical", "plane"))
        f = (
            self._native.fried_parameter_spherical
            if wave == "spherical"
            else self._native.fried_parameter_plane
        )
        return f(*_reals(wavelength=wavelength, path_length=path_length))

    def rytov_variance(self, wavelength: float, path_length: float) -> float:
        """Plane-wave Rytov variance σ_R² (weak fluctuations below ~1); wavelength and path_length
        in m."""
        return self._native.rytov_variance(*_reals(wavelength=wavelength, path_length=path_length))

    def isoplanatic_angle(self, wavelength: float, path_length: float) -> float:
        """θ0 (rad) seen from the lidar; wavelength and path_length in m."""
        return self._native.isoplanatic_angle(
            *_reals(wavelength=wavelength, path_length=path_length)
        )

    def beam_wander_variance(
        self, wavelength: float, waist_radius: float, path_length: float
    ) -> float:
        """Andrews & Phillips' beam-wander variance <r_c²> (m², 2-D) of a collimated Gaussian beam
        at path_length, 2.42 Cn² L³ W0^(-1/3) for a constant Cn². It is the large-scale part of
        their W_LT² (eddies filtered by exp(-κ² W0²)); the centroid of the irradiance-weighted tilt,
        which the FO screens reproduce, has 2^(-2/3) = 0.63 of it."""
        lam, w0, length = _reals(
            wavelength=wavelength, waist_radius=waist_radius, path_length=path_length
        )
        return self._native.beam_wander_variance(
            waist_radius=w0, wavelength=lam, path_length=length
        )

    def long_term_radius(self, wavelength: float, waist_radius: float, path_length: float) -> float:
        """W_LT (m): the 1/e² radius of the Gaussian core of the beam averaged over time (spread and
        wander), set by its mean irradiance on the axis. The second-moment radius of that mean
        irradiance is
        larger: scattered light makes its wings, unbounded for a zero inner scale."""
        lam, w0, length = _reals(
            wavelength=wavelength, waist_radius=waist_radius, path_length=path_length
        )
        return self._native.long_term_radius(waist_radius=w0, wavelength=lam, path_length=length)

    def short_term_radius(
        self, wavelength: float, waist_radius: float, path_length: float
    ) -> float:
        """W_ST (m): the instantaneous beam's radius about its wandering centre, sqrt(W_LT² −
        <r_c²>)."""
        lam, w0, length = _reals(
            wavelength=wavelength, waist_radius=waist_radius, path_length=path_length
        )
        return self._native.short_term_radius(waist_radius=w0, wavelength=lam, path_length=length)

    def angle_of_arrival_variance(self, diameter: float, path_length: float) -> float:
        """Per-axis variance (rad²) of the angle of arrival over an aperture of ``diameter`` (m) of
        the light a point at ``path_length`` (m) sends back to the lidar: the G-tilt of a spherical
        wave, C D^(-1/3) ∫ Cn²(r) (1 − r/L)^(5/3) dr for Kolmogorov turbulence (C = 2.84; 0.170
        (λ/D)² (D/r0)^(5/3)), less with an outer scale (:mod:`lidar_overlap.model.tilt`; geometric,
        the same at every wavelength). It is what tilts the image of the scattering volume in
        ray tracing with turbulence on both paths."""
        d, length = _reals(diameter=diameter, path_length=path_length)
        for name, value in (("diameter", d), ("path_length", length)):
            if not _core.MIN_LENGTH <= value <= _core.MAX_LENGTH:
                raise ValueError(
                    f"{name} = {value!r} is invalid: expected a length from {_core.MIN_LENGTH:g} "
                    f"to {_core.MAX_LENGTH:g} m"
                )
        moments = path_tilts(
            self._native.cn2_at_range,
            np.array([length]),
            wavelength=1e-6,  # enters r0 only, not returned here
            diameter=d,
            beam_radius=lambda r: np.full(np.shape(r), d / 2.0),  # the beam's moments unused
            outer_scale=self._native.outer_scale,
            inner_scale=self._native.inner_scale,
        )
        return float(moments.image[0]) / length**2

    def __repr__(self) -> str:
        return f"Turbulence(cn2={self.cn2!r}, elevation={self._native.elevation:.4g} rad)"


def _reals(**values) -> list:
    """Each value as a float, refused by name unless it is a real number (the core checks its
    range)."""
    return [_checks.real(name, value) for name, value in values.items()]


def _checked_profile(cn2: Callable[[float], float]) -> Callable[[float], float]:
    """The caller's Cn²(height) function, its answers checked and named ``cn2(<height> m)``: a real
    number from 0 to MAX_CN2 m^-2/3."""

    def at(height: float) -> float:
        name = f"cn2({height:.6g} m)"
        value = _checks.real(name, cn2(height))
        if not 0.0 <= value <= MAX_CN2:
            raise ValueError(
                f"{name} = {value!r} is invalid: expected a value from 0 to {MAX_CN2:g} m^-2/3"
            )
        return value

    return at


def _hv_term(name: str, value) -> float:
    """A Hufnagel–Valley term: finite and >= 0 (the core refuses the rest for ``"hv57"``)."""
    v = _checks.real(name, value)
    if not (math.isfinite(v) and v >= 0.0):
        raise ValueError(f"{name} = {v!r} is invalid: expected a finite value >= 0")
    return v
