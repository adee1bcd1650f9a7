"""Transmitted beam profiles beyond TEM00, as :class:`~lidar_overlap.Field` at z = 0 (SI units).

Each function samples its profile on the centred (n, n) grid of :class:`Field` (index n//2 is x = 0) and
scales it so that the sampled power Σ|U|² spacing² equals ``power`` (W) exactly, so a coarse grid changes
the shape slightly but never the power.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import eval_genlaguerre, gamma

from . import _checks
from .fields import Field

#: The window half-width must hold this many second-moment radii: beyond 3 w a TEM00 beam carries
#: exp(-18) ~ 2e-8 of its power, below the 1e-6 edge limit that :func:`propagate` warns about.
WINDOW_RADII = 3.0
#: The annulus may reach this fraction of the window (n spacing), leaving the outer n/16 empty.
ANNULUS_WINDOW_FRACTION = 0.45
#: Sub-samples per pixel side for the area fraction of pixels an annulus edge crosses.
EDGE_SUBSAMPLES = 8


def _grid(n, spacing):
    """Validated n and spacing, and the sample coordinates x (row vector) and y (column vector) in m."""
    n = _checks.count("n", n, 8)
    if n % 2:
        raise ValueError(f"n = {n} is invalid: expected an even integer >= 8")
    spacing = _checks.positive("spacing", spacing)
    x = (np.arange(n) - n // 2) * spacing
    return n, spacing, x[None, :], x[:, None]


def _check_window(second_moment_radius, n, spacing):
    half = 0.5 * n * spacing
    if WINDOW_RADII * second_moment_radius > half:
        raise ValueError(
            f"n * spacing = {n * spacing:.4g} m is invalid: expected a window of at least "
            f"{2 * WINDOW_RADII * second_moment_radius:.4g} m ({2 * WINDOW_RADII:g} x the beam's second-moment "
            f"radius {second_moment_radius:.4g} m); increase n or spacing")


def _normalised(values, spacing, wavelength, power):
    sampled = float(np.sum(np.abs(values) ** 2)) * spacing ** 2
    return Field(values * math.sqrt(power / sampled), spacing, wavelength)


def annular_field(wavelength, outer_radius, inner_radius, n, spacing, power=1.0):
    """Uniformly lit annulus ``inner_radius < r <= outer_radius``, flat phase (a disc if inner_radius = 0).

    U = U0 c, with c the fraction of each pixel (spacing²) inside the annulus, from EDGE_SUBSAMPLES²
    sub-samples in the pixels an edge crosses: the sampled aperture keeps the true area and low spatial
    frequencies, so its far field follows [2 J1(v)/v - ε² 2 J1(εv)/(εv)]², v = k a θ, ε = inner/outer.

    Parameters
    ----------
    wavelength, outer_radius, inner_radius, spacing : m; 0 <= inner_radius < outer_radius <= 0.45 n spacing.
    n : samples per side, even >= 8.
    power : W, sets U0.

    Returns
    -------
    Field; raises ValueError naming the parameter for arguments outside these ranges.
    """
    wavelength = _checks.positive("wavelength", wavelength)
    n, spacing, x, y = _grid(n, spacing)
    outer = _checks.positive("outer_radius", outer_radius)
    inner = _checks.real("inner_radius", inner_radius)
    if not 0.0 <= inner < outer:
        raise ValueError(f"inner_radius = {inner!r} is invalid: expected 0 <= inner_radius < outer_radius = {outer!r}")
    if outer > ANNULUS_WINDOW_FRACTION * n * spacing:
        raise ValueError(f"outer_radius = {outer!r} is invalid: expected at most {ANNULUS_WINDOW_FRACTION} n spacing = "
                         f"{ANNULUS_WINDOW_FRACTION * n * spacing:.4g} m; increase n or spacing")
    power = _checks.positive("power", power)

    def inside(r):
        return (r > inner) & (r <= outer)

    r = np.hypot(x, y)
    cover = inside(r).astype(float)
    # Only pixels within half a diagonal of an edge can be partly covered; sub-sample just those.
    half_diagonal = spacing / math.sqrt(2.0)
    edge = (np.abs(r - outer) <= half_diagonal) | ((inner > 0) & (np.abs(r - inner) <= half_diagonal))
    iy, ix = np.nonzero(edge)
    t = ((np.arange(EDGE_SUBSAMPLES) + 0.5) / EDGE_SUBSAMPLES - 0.5) * spacing
    tx, ty = (a.ravel() for a in np.meshgrid(t, t))
    cover[iy, ix] = inside(np.hypot(x[0, ix, None] + tx, y[iy, 0, None] + ty)).mean(axis=1)
    return _normalised(cover.astype(complex), spacing, wavelength, power)


def laguerre_gauss_field(wavelength, waist_radius, l, p=0, *, n, spacing, power=1.0):
    """Laguerre-Gauss mode LG_p^l at its waist (no curvature, no Gouy phase):

    U ∝ (√2 r / w0)^|l| L_p^|l|(2 r² / w0²) exp(-r² / w0²) exp(i l φ),

    L the generalised Laguerre polynomial; second-moment radius w0 √(2p + |l| + 1).

    Parameters
    ----------
    wavelength, waist_radius (w0), spacing : m, > 0.
    l : azimuthal index, any integer: a vortex of charge l, with an on-axis null for l != 0.
    p : radial index, integer >= 0 (p + 1 bright rings).
    n : samples per side, even >= 8; the window n spacing must hold 6 second-moment radii.
    power : W.

    Returns
    -------
    Field; raises ValueError naming the parameter (for a small window, with the size needed).
    """
    wavelength = _checks.positive("wavelength", wavelength)
    w0 = _checks.positive("waist_radius", waist_radius)
    if isinstance(l, (bool, np.bool_)) or not isinstance(l, (int, np.integer)):
        raise ValueError(f"l = {l!r} is invalid: expected an integer (azimuthal index, either sign)")
    l, p = int(l), _checks.count("p", p, 0)
    n, spacing, x, y = _grid(n, spacing)
    _check_window(w0 * math.sqrt(2 * p + abs(l) + 1), n, spacing)
    power = _checks.positive("power", power)
    rho2 = 2.0 * (x ** 2 + y ** 2) / w0 ** 2       # (√2 r / w0)²
    # (√2 (x ± i y) / w0)^|l| = (√2 r / w0)^|l| exp(i l φ) needs no angle, which is undefined at r = 0,
    # and makes the on-axis sample exactly 0 for l != 0.
    vortex = ((x + 1j * np.sign(l) * y) * math.sqrt(2.0) / w0) ** abs(l)
    values = vortex * eval_genlaguerre(p, abs(l), rho2) * np.exp(-rho2 / 2)
    return _normalised(values, spacing, wavelength, power)


def super_gaussian_field(wavelength, radius, order, n, spacing, power=1.0):
    """Super-Gaussian (flat-topped) beam at its waist, flat phase, amplitude √I with irradiance

    I(r) = I0 exp(-2 (r / radius)^(2 order)):

    I0 exp(-2) at r = radius for every order; order 1 is TEM00 with waist ``radius``, large orders approach
    a uniformly lit disc. Second-moment radius: radius √(2^(1-1/N) Γ(2/N) / Γ(1/N)), 0.89 to 1 radius.

    Parameters
    ----------
    wavelength, radius, spacing : m, > 0.
    order : N, real >= 1.
    n : samples per side, even >= 8; the window n spacing must hold 6 second-moment radii.
    power : W, sets I0.

    Returns
    -------
    Field; raises ValueError naming the parameter (for a small window, with the size needed).
    """
    wavelength = _checks.positive("wavelength", wavelength)
    radius = _checks.positive("radius", radius)
    order = _checks.real("order", order)
    if not (1.0 <= order < math.inf):
        raise ValueError(f"order = {order!r} is invalid: expected a finite value >= 1")
    n, spacing, x, y = _grid(n, spacing)
    _check_window(radius * math.sqrt(2 ** (1 - 1 / order) * gamma(2 / order) / gamma(1 / order)), n, spacing)
    power = _checks.positive("power", power)
    with np.errstate(over="ignore"):               # (r/radius)^(2N) -> inf far out gives exactly 0
        values = np.exp(-(np.hypot(x, y) / radius) ** (2 * order))
    return _normalised(values.astype(complex), spacing, wavelength, power)
