"""Tilt statistics of the two paths of a lidar through one turbulent atmosphere (weak fluctuations,
geometric optics; SI units): the ray-traced counterpart of turbulence on both paths
(docs/turbulence.md, "Ray tracing on both paths").

Each thin layer at range r (thickness dr) deflects light by the gradient of its phase averaged over
the footprint the light crosses it with. Its phase spectrum is 2π k² 0.033 Cn²(r) dr
(κ² + κ0²)^(-11/6) exp(-(κ l0 / 5.92)²) (von Kármán with κ0 = 2π / L0, the inner scale as the phase
screens have it; Kolmogorov for L0 = ∞, l0 = 0), so the per-axis covariance of the deflections of
two footprints with transfer functions F1, F2 whose centres are Δ apart is

    C Cn² dr ∫ κ³ (κ² + κ0²)^(-11/6) F1(κ) F2(κ) J0(κ Δ) dκ,   C = 2π² 0.033

(the mean of the parallel and perpendicular components: the J0 of the isotropic average).

- The transmitted beam (Gaussian, 1/e² radius W(r)) is deflected by its irradiance-weighted
  gradient, F = exp(-κ² W² / 8), and a deflection at r moves its centre at range z by s = z - r.
- The light a point scatterer at z sends into the aperture D crosses the layer on a cone of diameter
  d = D s / z, F = 2 J1(κ d / 2) / (κ d / 2) (the hard disc: the image centroid is the mean gradient
  over the aperture, G-tilt), and turns its apparent direction by s / z times the deflection. The
  angle-of-arrival variance is then C D^(-1/3) ∫ Cn² (s / z)^(5/3) ... dr: the spherical-wave path
  weighting (s/z)^(5/3) of a source at the scatterer (Sasiela, "Electromagnetic Wave Propagation in
  Turbulence", 2nd ed., SPIE (2007); Andrews & Phillips, "Laser Beam Propagation through Random
  Media", 2nd ed., SPIE (2005); for Kolmogorov turbulence the G-tilt, 0.170 (λ/D)² (D/r0)^(5/3)
  per axis with r0 on that weighting). Displacing the scene by z times that angle is the same as
  moving its image on the detector by f times it.
- In the beam's frame the apparent scene moves by c + α z = ∫ s (δ_T − δ_R) dr: where the two
  paths cross the same eddies (a coaxial lidar) the wander of the beam and the tilt of its image
  cancel. A biaxial lidar whose beam axis is a from the telescope's crosses layer r with the two
  footprints a s / z apart, so the correlation falls once a s / z exceeds the footprints (the
  beam's W, the cone's D s / z) or the outer scale.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

#: The Kolmogorov spectrum's constant, Γ(8/3) sin(π/3) / (4π²) = 0.033005 (Φ_n = 0.033 Cn²
#: κ^(-11/3)).
KOLMOGOROV = math.gamma(8.0 / 3.0) * math.sin(math.pi / 3.0) / (4.0 * math.pi**2)
#: Per-axis deflection variance per unit Cn² dr and unit ∫ κ³ Φ F1 F2 dκ: (1/k²) π 2π k² 0.033.
LAYER = 2.0 * math.pi**2 * KOLMOGOROV
#: Breaks of the composite Gauss–Legendre rule along the path, as fractions of the range: dense near
#: the lidar, where a vertical path's Cn² is strongest and the beam's footprint smallest.
PATH_BREAKS = (0.0, 1e-3, 1e-2, 0.1, 0.4, 1.0)
#: Gauss–Legendre nodes per piece of the path, and points per decade of the log-spaced κ grid
#: (trapezoid in ln κ), the span of that grid below the largest scale and above the smallest (the
#: part below is added in closed form). Measured against 32 nodes and 200 points per decade
#: (coaxial and 4 and 30 cm biaxial, Kolmogorov and L0 = 1 m, 100 m to 5 km): the moments within
#: 3e-6 and the correlation within 5e-6.
PATH_NODES = 10
KAPPA_PER_DECADE = 24
KAPPA_BELOW, KAPPA_ABOVE = 1e-4, 3e2


# J0 and J1 by Abramowitz & Stegun 9.4.1-9.4.6 (|error| < 1e-7): SciPy is an optional dependency,
# and the two-way path is the default one. Powers of (x/3)² up to 3, of 3/x beyond.
_J0_NEAR = (1.0, -2.2499997, 1.2656208, -0.3163866, 0.0444479, -0.0039444, 0.0002100)
_J1_NEAR = (0.5, -0.56249985, 0.21093573, -0.03954289, 0.00443319, -0.00031761, 0.00001109)
_J0_FAR = (
    (0.79788456, -0.00000077, -0.00552740, -0.00009512, 0.00137237, -0.00072805, 0.00014476),
    (-0.78539816, -0.04166397, -0.00003954, 0.00262573, -0.00054125, -0.00029333, 0.00013558),
)
_J1_FAR = (
    (0.79788456, 0.00000156, 0.01659667, 0.00017105, -0.00249511, 0.00113653, -0.00020033),
    (-2.35619449, 0.12499612, 0.00005650, -0.00637879, 0.00074348, 0.00079824, -0.00029166),
)


def _bessel(x: np.ndarray, near: tuple, far: tuple) -> np.ndarray:
    """J0 (``_J0_*``) or J1 / x (``_J1_*``) at x >= 0 (J1 / x: the disc's transfer function is
    2 J1 / x, finite at 0)."""
    polyval = np.polynomial.polynomial.polyval
    inside = x <= 3.0
    small = polyval(np.where(inside, x / 3.0, 0.0) ** 2, near)
    big = np.where(inside, 3.0, x)
    v = 3.0 / big
    large = polyval(v, far[0]) * np.cos(big + polyval(v, far[1])) / np.sqrt(big)
    if near is _J1_NEAR:
        large = large / big
    return np.where(inside, small, large)


def bessel_j0(x) -> np.ndarray:
    """J0(x) (|error| < 1e-7)."""
    return _bessel(np.abs(np.asarray(x, dtype=float)), _J0_NEAR, _J0_FAR)


def disc_transfer(x) -> np.ndarray:
    """2 J1(x) / x, the transform of a uniform disc normalised to 1 at x = 0 (|error| < 1e-7)."""
    return 2.0 * _bessel(np.abs(np.asarray(x, dtype=float)), _J1_NEAR, _J1_FAR)


@dataclass(frozen=True)
class PathTilts:
    """Per-axis second moments (m²) of the displacements at each range z of the paths' geometry:
    ``beam`` the transmitted beam's centre (its wander, on this layer model), ``image`` z α (α the
    angle of arrival of a scatterer's light over the aperture), ``cross`` the covariance of the
    beam's wander with minus z α (equal to both where both paths average the same eddies: they
    cancel), and ``r0`` the Fried parameter (m) of the returning spherical wave at the wavelength
    given."""

    beam: np.ndarray
    image: np.ndarray
    cross: np.ndarray
    r0: np.ndarray

    @property
    def correlation(self) -> np.ndarray:
        """cross / sqrt(beam image): how much of the image's tilt is the beam's wander seen back
        (1 coaxial with equal footprints, 0 on separate paths)."""
        den = np.sqrt(self.beam * self.image)
        return np.divide(self.cross, den, out=np.zeros_like(den), where=den > 0.0)


def path_nodes(z: float):
    """Composite Gauss–Legendre nodes r (m) and weights on [0, z]."""
    x, w = np.polynomial.legendre.leggauss(PATH_NODES)
    r, weight = [], []
    for a, b in zip(PATH_BREAKS[:-1], PATH_BREAKS[1:]):
        r.append(z * (a + (b - a) * (x + 1.0) / 2.0))
        weight.append(z * (b - a) / 2.0 * w)
    return np.concatenate(r), np.concatenate(weight)


def _low_tail(kappa: float, kappa0: float) -> float:
    """∫_0^κ q³ (q² + κ0²)^(-11/6) dq in closed form: the κ grid's part below its first point, where
    every transfer function is 1 to O((κ scale)²)."""
    v0, v1 = kappa0**2, kappa**2 + kappa0**2

    def primitive(v):
        return 3.0 * v ** (1.0 / 6.0) + (0.6 * kappa0**2 * v ** (-5.0 / 6.0) if kappa0 > 0 else 0.0)

    return primitive(v1) - (primitive(v0) if kappa0 > 0 else 0.0)


def path_tilts(
    cn2_at_range: Callable[[float], float],
    z: np.ndarray,
    *,
    wavelength: float,
    diameter: float,
    beam_radius: Callable[[np.ndarray], np.ndarray],
    separation: float = 0.0,
    outer_scale: float = math.inf,
    inner_scale: float = 0.0,
) -> PathTilts:
    """The tilt moments of the two paths at each range in ``z`` (m): Cn²(r) from ``cn2_at_range``
    (m^-2/3 at range r, m), the aperture ``diameter`` (m), the beam's 1/e² radius (m) at ranges r
    from ``beam_radius``, the beam axis ``separation`` (m) from the telescope's at the lidar, the
    outer and inner scales (m)."""
    z = np.atleast_1d(np.asarray(z, dtype=float))
    kappa0 = 0.0 if math.isinf(outer_scale) else 2.0 * math.pi / outer_scale
    k = 2.0 * math.pi / wavelength
    out = {name: np.empty(z.size) for name in ("beam", "image", "cross", "r0")}
    for i, zi in enumerate(z):
        r, weight = path_nodes(zi)
        t = 1.0 - r / zi  # s / z: the lever of the beam (z t) and of the image (t)
        cn2 = np.array([cn2_at_range(float(ri)) for ri in r])
        w = np.asarray(beam_radius(r), dtype=float)
        d = diameter * t
        scales = np.concatenate([w, d[d > 0], [separation * t.max()] if separation > 0 else []])
        large = max(scales.max(), 1.0 / kappa0 if kappa0 > 0 else 0.0)
        small = scales[scales > 0].min()
        decades = math.log10(KAPPA_ABOVE / small) - math.log10(KAPPA_BELOW / large)
        # J0 of a separation wider than the footprints oscillates: sample it finer
        fine = max(1.0, min(separation / max(diameter, w.min()), 10.0)) if separation > 0 else 1.0
        n = int(math.ceil(decades * KAPPA_PER_DECADE * fine)) + 1
        kappa = np.geomspace(KAPPA_BELOW / large, KAPPA_ABOVE / small, n)
        spectrum = kappa**4 * (kappa**2 + kappa0**2) ** (-11.0 / 6.0)  # κ³ Φ, times κ for d ln κ
        if inner_scale > 0.0:
            spectrum = spectrum * np.exp(-((kappa * inner_scale / 5.92) ** 2))
        x = kappa[None, :] * d[:, None] / 2.0
        disc = disc_transfer(x)
        gauss = np.exp(-((kappa[None, :] * w[:, None]) ** 2) / 8.0)
        across = bessel_j0(kappa[None, :] * (separation * t)[:, None]) if separation > 0 else 1.0
        tail = _low_tail(float(kappa[0]), kappa0)
        lnk = np.log(kappa)

        # per unit Cn² dr: C ∫ κ³ Φ F1 F2 dκ, the grid plus its closed-form tail (this layer's grid
        # bound now: the loop moves on)
        def layer(f, spectrum=spectrum, lnk=lnk, tail=tail):
            return LAYER * (np.trapezoid(f * spectrum[None, :], lnk, axis=1) + tail)

        lever = (zi * t) ** 2 * cn2 * weight
        out["beam"][i] = np.sum(lever * layer(gauss**2))
        out["image"][i] = np.sum(lever * layer(disc**2))
        out["cross"][i] = np.sum(lever * layer(disc * gauss * across))
        weighted = np.sum(cn2 * t ** (5.0 / 3.0) * weight)  # ∫ Cn² (s/z)^(5/3) dr
        out["r0"][i] = (0.423 * k**2 * weighted) ** (-0.6) if weighted > 0 else math.inf
    return PathTilts(**out)


def spherical_rytov(cn2_at_range: Callable[[float], float], wavelength: float, z: float) -> float:
    """Spherical-wave Rytov variance β0² = 2.25 k^(7/6) ∫ Cn²(r) r^(5/6) (1 − r/z)^(5/6) dr over
    [0, z], a point source's (Andrews & Phillips; 0.4 σ_R² for a constant Cn²)."""
    r, weight = path_nodes(z)
    cn2 = np.array([cn2_at_range(float(ri)) for ri in r])
    k = 2.0 * math.pi / wavelength
    return float(
        2.25 * k ** (7.0 / 6.0) * np.sum(cn2 * (r * (1.0 - r / z)) ** (5.0 / 6.0) * weight)
    )
