"""Transmitted beam profiles beyond TEM00, as :class:`~lidar_overlap.Field` at z = 0 (SI units).

Each function samples its profile on the centred (n, n) grid of :class:`Field` (index n//2 is x = 0)
and scales it so that the sampled power Σ|U|² spacing² equals ``power`` (W) exactly, so a coarse
grid changes the shape slightly but never the power.
"""

from __future__ import annotations

import math

import numpy as np

from .. import _checks, _core
from .._checks import check_memory, length
from ..model.field import MAX_POWER, Field

#: The window half-width must hold this many second-moment radii: beyond 3 w a TEM00 beam carries
#: exp(-18) ~ 2e-8 of its power, below the 1e-6 edge limit that :func:`propagate` warns about.
WINDOW_RADII = 3.0
#: The annulus may reach this fraction of the window (n spacing), leaving the outer n/16 empty.
ANNULUS_WINDOW_FRACTION = 0.45
#: Sub-samples per pixel side for the area fraction of pixels an annulus edge crosses.
EDGE_SUBSAMPLES = 8
#: Peak bytes per grid sample while a profile is built (measured 72-137, the Field's checks
#: included).
BYTES_PER_SAMPLE = 160
#: Largest |l| and p of a Laguerre-Gauss mode: its rings then span sqrt(2p + |l| + 1) <= 17 waists
#: and its polynomial stays far inside double range.
MAX_MODE_INDEX = 100
#: Natural logarithm of the smallest positive double (subnormal): below it a sample is exactly 0.
LOG_SMALLEST = math.log(5e-324)


def _grid(n, spacing):
    """Validated n and spacing, and the sample coordinates x (row vector) and y (column vector) in
    m."""
    n = _checks.count("n", n, 8, _core.MAX_GRID_SIDE)
    if n % 2:
        raise ValueError(
            f"n = {n} is invalid: expected an even integer from 8 to {_core.MAX_GRID_SIDE}"
        )
    check_memory("n", n, BYTES_PER_SAMPLE * float(n) ** 2, "use a smaller n")
    spacing = length("spacing", spacing)
    x = (np.arange(n) - n // 2) * spacing
    return n, spacing, x[None, :], x[:, None]


def _power(value) -> float:
    """The ``power`` argument: W, in (0, MAX_POWER]."""
    power = _checks.real("power", value)
    if not 0.0 < power <= MAX_POWER:
        raise ValueError(
            f"power = {power!r} is invalid: expected a power > 0 and at most {MAX_POWER:g} W"
        )
    return power


def _check_window(second_moment_radius, n, spacing):
    half = 0.5 * n * spacing
    if WINDOW_RADII * second_moment_radius > half:
        raise ValueError(
            f"n * spacing = {n * spacing:.4g} m is invalid: expected a window of at least "
            f"{2 * WINDOW_RADII * second_moment_radius:.4g} m ({2 * WINDOW_RADII:g} x the beam's "
            f"second-moment radius {second_moment_radius:.4g} m); increase n or spacing"
        )


def _normalised(values, spacing, wavelength, power):
    """``values`` scaled to sampled power ``power`` (W); refused, naming spacing, when the samples
    miss the profile (a grid far coarser than the beam samples no power, or all of it in one
    sample)."""
    peak = float(np.max(np.abs(values)))
    if peak > 0.0:
        values = values / peak  # peak 1: the sum of squares cannot overflow
    sampled = float(np.sum(np.abs(values) ** 2)) * spacing**2
    if not sampled > 0.0:
        raise ValueError(
            f"spacing = {spacing!r} is invalid: the grid samples none of the beam's power; "
            "expected a spacing well below the beam's size"
        )
    field = Field(values * math.sqrt(power / sampled), spacing, wavelength)
    if not field.beam_radius > 0.0:
        raise ValueError(
            f"spacing = {spacing!r} is invalid: the beam's power falls in a single sample; "
            "expected a spacing well below the beam's size"
        )
    return field


def annular_field(wavelength, outer_radius, inner_radius, n, spacing, power=1.0):
    """Uniformly lit annulus ``inner_radius < r <= outer_radius``, flat phase (a disc if
    inner_radius = 0).

    U = U0 c, with c the fraction of each pixel (spacing²) inside the annulus, from EDGE_SUBSAMPLES²
    sub-samples in the pixels an edge crosses: the sampled aperture keeps the true area and low
    spatial frequencies, so its far field follows [2 J1(v)/v - ε² 2 J1(εv)/(εv)]², v = k a θ, ε =
    inner/outer.

    Parameters
    ----------
    wavelength, outer_radius, inner_radius, spacing : m; 0 <= inner_radius < outer_radius <= 0.45 n
        spacing.
    n : samples per side, even >= 8.
    power : W, sets U0.

    Returns
    -------
    Field; raises ValueError naming the parameter for arguments outside these ranges.
    """
    wavelength = length("wavelength", wavelength)
    n, spacing, x, y = _grid(n, spacing)
    outer = length("outer_radius", outer_radius)
    inner = _checks.real("inner_radius", inner_radius)
    if not 0.0 <= inner < outer:
        raise ValueError(
            f"inner_radius = {inner!r} is invalid: expected 0 <= inner_radius < outer_radius = "
            f"{outer!r}"
        )
    if outer > ANNULUS_WINDOW_FRACTION * n * spacing:
        raise ValueError(
            f"outer_radius = {outer!r} is invalid: expected at most {ANNULUS_WINDOW_FRACTION} n "
            f"spacing = {ANNULUS_WINDOW_FRACTION * n * spacing:.4g} m; increase n or spacing"
        )
    power = _power(power)

    def inside(r):
        return (r > inner) & (r <= outer)

    r = np.hypot(x, y)
    cover = inside(r).astype(float)
    # Only pixels within half a diagonal of an edge can be partly covered; sub-sample just those.
    half_diagonal = spacing / math.sqrt(2.0)
    edge = (np.abs(r - outer) <= half_diagonal) | (
        (inner > 0) & (np.abs(r - inner) <= half_diagonal)
    )
    iy, ix = np.nonzero(edge)
    t = ((np.arange(EDGE_SUBSAMPLES) + 0.5) / EDGE_SUBSAMPLES - 0.5) * spacing
    tx, ty = (a.ravel() for a in np.meshgrid(t, t))
    cover[iy, ix] = inside(np.hypot(x[0, ix, None] + tx, y[iy, 0, None] + ty)).mean(axis=1)
    return _normalised(cover.astype(complex), spacing, wavelength, power)


def laguerre_gauss_field(wavelength, waist_radius, l, p=0, *, n, spacing, power=1.0):
    """Laguerre-Gauss mode LG_p^l at its waist (no curvature, no Gouy phase):

    U ∝ (√2 r / w0)^|l| L_p^|l|(2 r² / w0²) exp(-r² / w0²) exp(i l φ),

    L the generalised Laguerre polynomial; second-moment radius w0 √(2p + ``|l|`` + 1).

    Parameters
    ----------
    wavelength, waist_radius (w0), spacing : m, > 0.
    l : azimuthal index, an integer from -100 to 100: a vortex of charge l, with an on-axis null for
        l != 0.
    p : radial index, integer from 0 to 100 (p + 1 bright rings).
    n : samples per side, even >= 8; the window n spacing must hold 6 second-moment radii.
    power : W.

    Returns
    -------
    Field; raises ValueError naming the parameter (for a small window, with the size needed).
    """
    wavelength = length("wavelength", wavelength)
    w0 = length("waist_radius", waist_radius)
    if (
        isinstance(l, (bool, np.bool_))
        or not isinstance(l, (int, np.integer))
        or not abs(l) <= MAX_MODE_INDEX
    ):
        raise ValueError(
            f"l = {_checks.shown(l)} is invalid: expected an integer from -{MAX_MODE_INDEX} to "
            f"{MAX_MODE_INDEX} (azimuthal index, either sign)"
        )
    l, p = int(l), _checks.count("p", p, 0, MAX_MODE_INDEX)
    n, spacing, x, y = _grid(n, spacing)
    _check_window(w0 * math.sqrt(2 * p + abs(l) + 1), n, spacing)
    power = _power(power)
    m = abs(l)
    rho2 = 2.0 * (x**2 + y**2) / w0**2  # (√2 r / w0)²
    # (√2 r / w0)^|l| exp(-r² / w0²) through its logarithm: the power alone overflows for large |l|
    # far out. It is exactly 0 on the axis for l != 0, and samples where it underflows stay 0.
    with np.errstate(divide="ignore"):
        log_envelope = -0.5 * rho2 if m == 0 else 0.5 * m * np.log(rho2) - 0.5 * rho2
    lit = log_envelope > LOG_SMALLEST
    values = np.zeros(lit.shape, dtype=complex)
    xs, ys, q = np.broadcast_to(x, lit.shape)[lit], np.broadcast_to(y, lit.shape)[lit], rho2[lit]
    # exp(i l φ) as ((x ± i y) / r)^|l|: no angle, which is undefined at r = 0 (never lit for l !=
    # 0).
    vortex = ((xs + 1j * np.sign(l) * ys) / np.hypot(xs, ys)) ** m if m else 1.0
    values[lit] = vortex * _laguerre()(p, m, q) * np.exp(log_envelope[lit])
    return _normalised(values, spacing, wavelength, power)


def super_gaussian_field(wavelength, radius, order, n, spacing, power=1.0):
    """Super-Gaussian (flat-topped) beam at its waist, flat phase, amplitude √I with irradiance

    I(r) = I0 exp(-2 (r / radius)^(2 order)):

    I0 exp(-2) at r = radius for every order; order 1 is TEM00 with waist ``radius``, large orders
    approach a uniformly lit disc. Second-moment radius: radius √(2^(1-1/N) Γ(2/N) / Γ(1/N)), 0.89
    to 1 radius.

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
    wavelength = length("wavelength", wavelength)
    radius = length("radius", radius)
    order = _checks.real("order", order)
    if not (1.0 <= order < math.inf):
        raise ValueError(f"order = {order!r} is invalid: expected a finite value >= 1")
    n, spacing, x, y = _grid(n, spacing)
    # Γ(2/N) / Γ(1/N) through log-gammas: each gamma alone overflows for N near the largest double.
    ratio = 2 ** (1 - 1 / order) * math.exp(math.lgamma(2 / order) - math.lgamma(1 / order))
    _check_window(radius * math.sqrt(ratio), n, spacing)
    power = _power(power)
    with np.errstate(over="ignore"):  # (r/radius)^(2N) -> inf far out gives exactly 0
        values = np.exp(-((np.hypot(x, y) / radius) ** (2 * order)))
    return _normalised(values.astype(complex), spacing, wavelength, power)


def _laguerre():
    """scipy's generalised Laguerre polynomials (the ``[fit]`` extra), imported when a mode needs
    them."""
    try:
        from scipy.special import eval_genlaguerre
    except ImportError:
        raise ImportError(
            "laguerre_gauss_field needs scipy: pip install 'lidar-overlap[fit]'"
        ) from None
    return eval_genlaguerre
