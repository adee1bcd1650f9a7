"""Scattering atmosphere for the elastic lidar equation: molecules of the US Standard Atmosphere
1976 plus optional aerosol (SI units: m, K, Pa, m⁻¹, m⁻¹ sr⁻¹).

Molecules. Temperature and pressure of the US Standard Atmosphere 1976 (NOAA/NASA/USAF, 1976) from
-5 km to 86 km geometric height (its seven layers of constant lapse rate in geopotential height),
number density N = p/(k T) of an ideal gas. The Rayleigh cross section per molecule is computed from
first principles as Bodhaine et al. (1999, J. Atmos. Oceanic Technol. 16, 1854) recommend:

    σ(λ) = 24 π³ (n_s² - 1)² / (λ⁴ N_s² (n_s² + 2)²) · F_K(λ)

with the refractive index n_s of standard air (288.15 K, 101325 Pa, 360 ppm CO₂, their Eq. 4, after
Peck and Reeves 1972), N_s = p/(k T) at those conditions, and the King factor F_K of air from Bates
(1984) (Bodhaine's Eqs. 5-6). σ includes the rotational Raman lines (the whole Rayleigh line, as an
elastic lidar with a filter of a few nm receives it). The backscatter uses the Rayleigh phase
function with depolarisation (Chandrasekhar; Bucholtz 1995, Appl. Opt. 34, 2765): P(π) = 3 (1 + γ) /
(2 (1 + 2γ)), γ = ρ/(2 - ρ), with the depolarisation ratio ρ = 6 (F_K - 1)/(3 + 7 F_K) that belongs
to the same King factor, so

    α_m = N σ,    β_m = α_m P(π) / (4π) = α_m / S_m,    S_m = (8π/3) (1 + 2γ)/(1 + γ)  (≈ 8.50 sr at
    532 nm).

Valid for 200 nm to 2 µm (the refractive-index formula), dry air.

Aerosol. A Gaussian layer, β_a = peak · exp(-(h - centre)² / (2 width²)), and a boundary layer of
constant backscatter from the lidar up to a depth above it, each with its own lidar ratio S_a (α_a =
S_a β_a). Both are given at the lidar's wavelength (no Ångström scaling).

Geometry. A flat Earth: height h = altitude + z sin(elevation) along the line of sight at range z
(the curvature lowers a horizontal path by z²/(2 R_E), 18 m at 15 km, which is neglected).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _checks

#: Boltzmann constant (J/K, exact in SI since 2019).
BOLTZMANN = 1.380649e-23
#: US76 constants: sea-level gravity (m/s²), gas constant (J/(mol K)), molar mass of air (kg/mol),
#: the Earth radius of its geopotential height (m).
G0, R_GAS, MOLAR_MASS, EARTH_RADIUS = 9.80665, 8.31432, 28.9644e-3, 6356766.0
#: US76 layers: base geopotential height (m) and lapse rate (K/m); base temperature and pressure
#: follow from sea level (288.15 K, 101325 Pa) by the hydrostatic equation, layer by layer.
_LAYER_BASES = np.array([0.0, 11e3, 20e3, 32e3, 47e3, 51e3, 71e3])
_LAPSE = np.array([-6.5e-3, 0.0, 1.0e-3, 2.8e-3, 0.0, -2.8e-3, -2.0e-3])
#: Geometric heights (m) where the model holds: US76's table from -5 km to 86 km.
MIN_HEIGHT, MAX_HEIGHT = -5e3, 86e3
#: Wavelengths (m) where the refractive index formula holds.
MIN_WAVELENGTH, MAX_WAVELENGTH = 200e-9, 2e-6
#: Standard air of the refractive index: temperature (K), pressure (Pa), CO₂ (percent by volume).
T_STANDARD, P_STANDARD, CO2_PERCENT = 288.15, 101325.0, 0.036
#: Largest aerosol backscatter (m⁻¹ sr⁻¹) and lidar ratio (sr) accepted: beyond any atmosphere, and
#: far from overflowing the optical depth.
MAX_BACKSCATTER, MAX_LIDAR_RATIO = 1.0, 1e3
#: Longest line of sight (m) integrated: the flat-Earth geometry means nothing beyond.
MAX_RANGE = 1e6
#: Optical depth quadrature: Gauss-Legendre nodes per interval, longest interval (m), and the
#: layer's breakpoints (in widths from its centre) that resolve a thin layer.
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(8)
_MAX_STEP = 100.0
_LAYER_SIGMAS = np.arange(-8.0, 9.0)


def _base_states():
    """Temperature (K) and pressure (Pa) at each layer base, from the hydrostatic equation."""
    temps, press = [288.15], [101325.0]
    for i in range(len(_LAYER_BASES) - 1):
        dh = _LAYER_BASES[i + 1] - _LAYER_BASES[i]
        t1 = temps[-1] + _LAPSE[i] * dh
        if _LAPSE[i] == 0.0:
            p1 = press[-1] * math.exp(-G0 * MOLAR_MASS * dh / (R_GAS * temps[-1]))
        else:
            p1 = press[-1] * (temps[-1] / t1) ** (G0 * MOLAR_MASS / (R_GAS * _LAPSE[i]))
        temps.append(t1)
        press.append(p1)
    return np.array(temps), np.array(press)


_BASE_T, _BASE_P = _base_states()


def _heights(value, name: str = "height") -> np.ndarray:
    """Geometric heights (m) as a float array, each finite and within US76's -5 km to 86 km."""
    try:
        h = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} is invalid: expected heights in m ({exc})") from None
    bad = ~((h >= MIN_HEIGHT) & (h <= MAX_HEIGHT))  # NaN is bad too
    if bad.any():
        raise ValueError(
            f"{name} = {float(h[bad].flat[0])!r} is invalid: expected a height from {MIN_HEIGHT:g} "
            f"m to {MAX_HEIGHT:g} m (the US Standard Atmosphere 1976 model)"
        )
    return h


def us76(height):
    """Temperature (K) and pressure (Pa) of the US Standard Atmosphere 1976 at geometric ``height``
    (m, -5 km to 86 km, any shape)."""
    h = _heights(height)
    geopotential = EARTH_RADIUS * h / (EARTH_RADIUS + h)
    i = np.clip(
        np.searchsorted(_LAYER_BASES, geopotential, side="right") - 1, 0, len(_LAYER_BASES) - 1
    )
    lapse, tb, pb = _LAPSE[i], _BASE_T[i], _BASE_P[i]
    t = tb + lapse * (geopotential - _LAYER_BASES[i])
    with np.errstate(
        divide="ignore", invalid="ignore"
    ):  # each branch is computed where the other is selected
        p = np.where(
            lapse == 0.0,
            pb * np.exp(-G0 * MOLAR_MASS * (geopotential - _LAYER_BASES[i]) / (R_GAS * tb)),
            pb * (tb / t) ** (G0 * MOLAR_MASS / (R_GAS * np.where(lapse == 0.0, 1.0, lapse))),
        )
    return t, p


def _wavelength(wavelength) -> float:
    lam = _checks.real("wavelength", wavelength)
    if not MIN_WAVELENGTH <= lam <= MAX_WAVELENGTH:
        raise ValueError(
            f"wavelength = {lam!r} is invalid: expected {MIN_WAVELENGTH:g} m to {MAX_WAVELENGTH:g} "
            "m (where the refractive index of air is modelled)"
        )
    return lam


def _king_factor(lam_um: float) -> float:
    """King factor of dry air (Bates 1984, as in Bodhaine et al. 1999, Eqs. 5-6), λ in µm."""
    f_n2 = 1.034 + 3.17e-4 / lam_um**2
    f_o2 = 1.096 + 1.385e-3 / lam_um**2 + 1.448e-4 / lam_um**4
    return (78.084 * f_n2 + 20.946 * f_o2 + 0.934 * 1.0 + CO2_PERCENT * 1.15) / (
        78.084 + 20.946 + 0.934 + CO2_PERCENT
    )


def rayleigh_cross_section(wavelength: float) -> float:
    """Rayleigh scattering cross section of one air molecule (m²) at ``wavelength`` (m), 200 nm to 2
    µm."""
    lam = _wavelength(wavelength)
    nu2 = (1e-6 / lam) ** 2  # µm⁻²
    n = 1.0 + 1e-8 * (8060.77 + 2481070.0 / (132.274 - nu2) + 17456.3 / (39.32957 - nu2))
    n_s = P_STANDARD / (BOLTZMANN * T_STANDARD)
    return (
        24
        * math.pi**3
        * (n**2 - 1) ** 2
        / (lam**4 * n_s**2 * (n**2 + 2) ** 2)
        * _king_factor(lam * 1e6)
    )


def molecular_lidar_ratio(wavelength: float) -> float:
    """Extinction over backscatter of air molecules (sr), (8π/3)(1 + 2γ)/(1 + γ) with the
    depolarisation of the King factor."""
    f = _king_factor(_wavelength(wavelength) * 1e6)
    rho = 6 * (f - 1) / (3 + 7 * f)
    gamma = rho / (2 - rho)
    return 8 * math.pi / 3 * (1 + 2 * gamma) / (1 + gamma)


def _bounded(name: str, value, low: float, high: float, include_low: bool = True) -> float:
    v = _checks.real(name, value)
    if not ((low <= v if include_low else low < v) and v <= high):
        raise ValueError(
            f"{name} = {v!r} is invalid: expected a value in {'[' if include_low else '('}{low:g}, "
            f"{high:g}]"
        )
    return v


@dataclass(frozen=True)
class Atmosphere:
    """Molecules (US Standard Atmosphere 1976) plus optional aerosol, seen along a lidar's line of
    sight.

    Parameters
    ----------
    altitude : m above sea level of the lidar, -5 km to 86 km.
    elevation : rad above the horizon of the line of sight, 0 to π/2 (zenith, the default).
    layer_backscatter : m⁻¹ sr⁻¹, peak backscatter of a Gaussian aerosol layer, 0 (none, the
        default) to 1.
    layer_height : m above sea level of the layer's centre.
    layer_width : m, its standard deviation in height (FWHM = 2.355 width), 1e-10 m to 1e10 m.
    layer_lidar_ratio : sr, its extinction over backscatter, (0, 1000].
    boundary_layer_backscatter : m⁻¹ sr⁻¹, constant aerosol backscatter from the lidar up to
        ``boundary_layer_depth`` above it, 0 (none, the default) to 1.
    boundary_layer_depth : m above the lidar (not above sea level), 0 to 86 km.
    boundary_layer_lidar_ratio : sr, (0, 1000].

    Coefficients are functions of height (m above sea level); :meth:`height` converts ranges, and
    :meth:`optical_depth` and :meth:`transmission` integrate along the line of sight from the lidar.
    """

    altitude: float = 0.0
    elevation: float = math.pi / 2
    layer_backscatter: float = 0.0
    layer_height: float = 2000.0
    layer_width: float = 200.0
    layer_lidar_ratio: float = 50.0
    boundary_layer_backscatter: float = 0.0
    boundary_layer_depth: float = 1000.0
    boundary_layer_lidar_ratio: float = 50.0

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "altitude", float(_heights(_checks.real("altitude", self.altitude), "altitude")))
        elevation = _checks.real("elevation", self.elevation)
        if not 0.0 <= elevation <= math.pi / 2:
            raise ValueError(
                f"elevation = {elevation!r} is invalid: expected 0 (horizontal) to π/2 rad (zenith)"
            )
        set_(self, "elevation", elevation)
        for name in ("layer_backscatter", "boundary_layer_backscatter"):
            set_(self, name, _bounded(name, getattr(self, name), 0.0, MAX_BACKSCATTER))
        for name in ("layer_lidar_ratio", "boundary_layer_lidar_ratio"):
            set_(
                self,
                name,
                _bounded(name, getattr(self, name), 0.0, MAX_LIDAR_RATIO, include_low=False),
            )
        set_(
            self,
            "layer_height",
            float(_heights(_checks.real("layer_height", self.layer_height), "layer_height")),
        )
        set_(self, "layer_width", _checks.length("layer_width", self.layer_width))
        set_(
            self,
            "boundary_layer_depth",
            _bounded(
                "boundary_layer_depth", self.boundary_layer_depth, 0.0, MAX_HEIGHT - MIN_HEIGHT
            ),
        )

    # ------------------------------------------------------------ along the line of sight
    def height(self, ranges):
        """Height (m above sea level) at each range (m) of the line of sight: altitude + z
        sin(elevation)."""
        return self.altitude + np.asarray(ranges, dtype=float) * math.sin(self.elevation)

    def _line_of_sight(self, ranges) -> np.ndarray:
        """``ranges`` checked (finite, > 0, increasing, within MAX_RANGE and the model's
        heights)."""
        z = _checks.ranges("ranges", ranges)
        if not (z[0] > 0 and z[-1] <= MAX_RANGE):
            i = 0 if not z[0] > 0 else len(z) - 1
            raise ValueError(
                f"ranges[{i}] = {float(z[i])!r} is invalid: expected a range > 0 and <= "
                f"{MAX_RANGE:g} m"
            )
        top = float(self.height(z[-1]))
        if top > MAX_HEIGHT:
            raise ValueError(
                f"ranges[{len(z) - 1}] = {float(z[-1])!r} m reaches {top:.6g} m above sea level: "
                "expected ranges up to "
                f"{(MAX_HEIGHT - self.altitude) / math.sin(self.elevation):.6g} m, where the line "
                f"of sight leaves the model's atmosphere ({MAX_HEIGHT:g} m)"
            )
        return z

    def optical_depth(self, wavelength: float, ranges):
        """One-way optical depth ∫₀^z α dz' (dimensionless) from the lidar to each range (m):
        Gauss-Legendre quadrature (8 nodes) on intervals of at most 100 m, split at the US76 layer
        bases, the boundary-layer top and the aerosol layer's centre ± k widths (k = 0..8), so each
        piece is smooth."""
        lam = _wavelength(wavelength)
        z = self._line_of_sight(ranges)
        edges = np.unique(
            np.concatenate(
                [[0.0], z, np.arange(_MAX_STEP, z[-1], _MAX_STEP), self._breakpoints(z[-1])]
            )
        )
        half = np.diff(edges)[:, None] / 2
        nodes = edges[:-1, None] + half * (1 + _NODES)
        pieces = (half * _WEIGHTS * self.extinction(lam, self.height(nodes))).sum(axis=1)
        return np.concatenate([[0.0], np.cumsum(pieces)])[np.searchsorted(edges, z)]

    def transmission(self, wavelength: float, ranges):
        """One-way transmission exp(-optical depth) from the lidar to each range (m); the lidar
        equation uses its square."""
        return np.exp(-self.optical_depth(wavelength, ranges))

    def _breakpoints(self, z_max: float) -> np.ndarray:
        """Ranges (m) in (0, z_max) where the extinction has a kink, a step or a narrow feature."""
        sin_el = math.sin(self.elevation)
        if sin_el == 0.0:
            return np.empty(0)
        bases = EARTH_RADIUS * _LAYER_BASES / (EARTH_RADIUS - _LAYER_BASES)  # geometric heights
        heights = np.concatenate([bases, self.layer_height + _LAYER_SIGMAS * self.layer_width])
        z = np.append((heights - self.altitude) / sin_el, self.boundary_layer_depth / sin_el)
        return z[(z > 0) & (z < z_max)]

    # ------------------------------------------------------------ coefficients at a height
    def temperature(self, height):
        """US76 temperature (K) at ``height`` (m above sea level)."""
        return us76(height)[0]

    def pressure(self, height):
        """US76 pressure (Pa) at ``height`` (m above sea level)."""
        return us76(height)[1]

    def number_density(self, height):
        """Molecules per m³ at ``height`` (m above sea level): p / (k T)."""
        t, p = us76(height)
        return p / (BOLTZMANN * t)

    def molecular_extinction(self, wavelength: float, height):
        """Rayleigh extinction α_m = N σ (m⁻¹) at ``wavelength`` (m) and ``height`` (m above sea
        level)."""
        return self.number_density(height) * rayleigh_cross_section(wavelength)

    def molecular_backscatter(self, wavelength: float, height):
        """Rayleigh backscatter β_m = α_m / S_m (m⁻¹ sr⁻¹) at ``wavelength`` (m) and ``height`` (m
        a.s.l.)."""
        return self.molecular_extinction(wavelength, height) / molecular_lidar_ratio(wavelength)

    def _aerosol(self, height):
        """Aerosol backscatter (m⁻¹ sr⁻¹) of the layer and of the boundary layer at ``height`` (m
        a.s.l.)."""
        h = _heights(height)
        layer = self.layer_backscatter * np.exp(
            -0.5 * ((h - self.layer_height) / self.layer_width) ** 2
        )
        boundary = np.where(
            h <= self.altitude + self.boundary_layer_depth, self.boundary_layer_backscatter, 0.0
        )
        return layer, boundary

    def backscatter(self, wavelength: float, height):
        """Total backscatter coefficient β (m⁻¹ sr⁻¹): molecules plus aerosol."""
        layer, boundary = self._aerosol(height)
        return self.molecular_backscatter(wavelength, height) + layer + boundary

    def extinction(self, wavelength: float, height):
        """Total extinction coefficient α (m⁻¹): molecules plus aerosol (α_a = S_a β_a)."""
        layer, boundary = self._aerosol(height)
        return (
            self.molecular_extinction(wavelength, height)
            + self.layer_lidar_ratio * layer
            + self.boundary_layer_lidar_ratio * boundary
        )
