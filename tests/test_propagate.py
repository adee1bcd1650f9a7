"""Fourier-optics propagation (paper Appendix A, Eqs. A1-A7) against closed forms.

- TEM00 radius w(z) = w0 sqrt(1 + (lambda z/(pi w0^2))^2) (paper D1, error D2), w0 = 5 mm, 355/1064
  nm, 1 mm to 100 km, with "auto" and each method in its region; far-field divergence lambda/(pi
  w0);
- complex fields: TEM00 a0 exp(ikz)/q exp(-r^2/(w0^2 q)), q = 1 + i z/zR (full phase kept), the
  exact A7 integral of a Gaussian, a 1-D quadrature of A1 (non-paraxial); power conservation; AS(z1)
  AS(z2) = AS(z1 + z2);
- on-axis irradiance behind a uniformly lit disc, I/I0 = 4 sin^2(pi a^2/(2 lambda z)); Airy focal
  plane I0 [2 J1(v)/v]^2 with I0 = P pi a^2/(lambda f)^2, encircled energy 1 - J0(v)^2 - J1(v)^2;
- no SamplingWarning inside each method's region (its boundaries and bad arguments:
  test_propagate_validity.py).
"""

import math
import warnings

import numpy as np
import pytest
from _propagation import (
    D1_RTOL,
    DX,
    W0,
    WAVELENGTHS,
    N,
    critical,
    d1,
    d1_errors,
    quiet,
    rayleigh,
    recorded,
)
from scipy.integrate import quad
from scipy.special import j0, j1

import lidar_overlap as lo

EPS = np.finfo(float).eps
# w/z overshoots lambda/(pi w0) by (zR/z)^2 / 2 = 5e-7 at z = 1000 zR; sampling adds ~1e-12.
DIVERGENCE_RTOL = 1e-6
# AS and single-FFT Fresnel are unitary (Parseval) when band limit and window cut nothing (Gaussian
# tails ~exp(-50)); the scaled transform is a Riemann sum of a Gaussian with 8 samples per radius
# (Poisson error ~exp(-300)). Left: rounding of FFT sums over 2.6e5 points.
POWER_RTOL = 1e-10
# Chained AS (max |difference| / max |U|): transfer functions multiply exactly inside the band, and
# with k z <= 4.2e3 the phases are rounded to ~1e-12 rad.
CHAIN_TOL = 1e-10
# Complex TEM00 field (max |U - U_closed| / max |U|): AS is exact, the closed form paraxial; a plane
# wave at angle t*theta (theta = 3.4e-4) is off by k z (t theta)^4 / 8 = 3.6e-9 t^4 at z = 0.37 m,
# ~1e-8 over the spectrum. Fresnel and A7 of a Gaussian are exact. Phases k z (up to 5e9 rad) are
# rounded by a few eps k z.
FIELD_TOL = 3e-8
PHASE_ROUNDING = 16 * EPS
# A1 quadrature (quad to ~1e-13; the spectrum beyond 1/lambda and the band limit carries exp(-39) of
# the amplitude), relative to the waist amplitude.
AS_EXACT_TOL = 1e-9
# On-axis aperture irradiance: the anti-aliased disc is a coverage-weighted Riemann sum whose edge
# error is second order, 8 pi^2 kappa (1 - cos(pi N)) (N dx/a)^2 with kappa ~ 0.045 for pixel
# coverage of a circle (the phase pi r^2/(lambda z) changes by 2 pi N dx/a across an edge pixel).
# Allowed: twice the worst case (odd N), 14 (N dx/a)^2: 0.034 of the peak value 4 at N = 5 with a/dx
# = 102, 1.3e-3 at N = 1.
ON_AXIS_EDGE_COEFF = 14.0
# Airy profile relative to I0: the disc edge (a/dx = 190) perturbs the core by ~(dx/a)^2 ~ 3e-5 of
# I0.
AIRY_PROFILE_ATOL = 3e-5
# Encircled energy at the dark rings (I and dI/dr vanish on the circle, so fractional-coverage
# weights on a grid of pi/16 in v err only at second order) and at v = 20: ~3e-5 from the disc edge;
# allowed 1e-4.
AIRY_EE_ATOL = 1e-4


def gaussian_beam(x, y, z, w0, wavelength, a0):
    """Paraxial TEM00 field at z (waist at 0 with on-axis amplitude a0)."""
    q = 1.0 + 1j * z / rayleigh(w0, wavelength)
    return (
        a0
        * np.exp(2j * math.pi / wavelength * z)
        / q
        * np.exp(-(x[None, :] ** 2 + y[:, None] ** 2) / (w0**2 * q))
    )


def fraunhofer_gaussian(x, y, z, w0, wavelength, a0):
    """Eq. (A7) applied to a0 exp(-r^2/w0^2), integrated exactly."""
    k, r2 = 2 * math.pi / wavelength, x[None, :] ** 2 + y[:, None] ** 2
    return (
        a0
        * math.pi
        * w0**2
        / (1j * wavelength * z)
        * np.exp(1j * k * z + 1j * k * r2 / (2 * z))
        * np.exp(-r2 * (math.pi * w0 / (wavelength * z)) ** 2)
    )


def angular_spectrum_gaussian(r, z, w0, wavelength, a0, paraxial=False):
    """Eq. (A1) for a0 exp(-r^2/w0^2) as a Hankel integral over the propagating frequencies rho <
    1/lambda."""
    k = 2 * math.pi / wavelength

    def part(rho, imag):
        s = (wavelength * rho) ** 2
        phase = k * z * ((1 - s / 2) if paraxial else math.sqrt(1 - s))
        amp = (
            2
            * math.pi**2
            * w0**2
            * rho
            * math.exp(-((math.pi * w0 * rho) ** 2))
            * j0(2 * math.pi * rho * r)
        )
        return amp * (math.sin(phase) if imag else math.cos(phase))

    re, im = (
        quad(part, 0, 1 / wavelength, args=(i,), epsabs=1e-14, epsrel=1e-13, limit=200)[0]
        for i in (0, 1)
    )
    return a0 * (re + 1j * im)


def disc(n, spacing, radius, sub=32):
    """Fractional pixel coverage of a centred disc (sub x sub samples in the pixels its edge
    crosses)."""
    x = (np.arange(n) - n // 2) * spacing
    xx, yy = np.meshgrid(x, x)
    r = np.hypot(xx, yy)
    cover = (r <= radius).astype(float)
    edge = np.abs(r - radius) <= spacing * 0.7072
    t = ((np.arange(sub) + 0.5) / sub - 0.5) * spacing
    tx, ty = np.meshgrid(t, t)
    cover[edge] = (
        np.hypot(xx[edge][:, None] + tx.ravel(), yy[edge][:, None] + ty.ravel()) <= radius
    ).mean(1)
    return cover


@pytest.fixture(scope="module", params=WAVELENGTHS, ids=["355nm", "1064nm"])
def beam(request):
    return lo.Field.gaussian(request.param, W0, N, DX)


# --- D1: beam radius from 1 mm to 100 km
# ---------------------------------------------------------------


def test_d1_auto_every_distance(beam):
    distances = np.logspace(-3, 5, 25)
    errors = d1_errors(beam, distances)
    worst = int(np.argmax(errors))
    assert errors[worst] <= D1_RTOL, (
        f"z = {distances[worst]:.4g} m: relative error {errors[worst]:.3g}"
    )
    zc = critical(beam)
    for z in (
        distances[0],
        0.99 * zc,
        1.01 * zc,
        distances[-1],
    ):  # AS up to z_c, then single-FFT Fresnel
        expected = DX if z <= zc else beam.wavelength * z / (N * DX)
        assert quiet(beam, z).spacing == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("method", ["angular_spectrum", "fresnel", "fraunhofer"])
def test_d1_each_method_in_its_region(beam, method):
    zc, zr = critical(beam), rayleigh(W0, beam.wavelength)
    distances = {
        "angular_spectrum": np.geomspace(1e-3, 0.999 * zc, 7),
        "fresnel": np.geomspace(1.001 * zc, 1e5, 7),
        "fraunhofer": np.geomspace(100 * zr, 1000 * zr, 4),
    }[method]
    errors = d1_errors(beam, distances, method=method)
    worst = int(np.argmax(errors))
    assert errors[worst] <= D1_RTOL, (
        f"{method}, z = {distances[worst]:.4g} m: error {errors[worst]:.3g}"
    )
    z = distances[-1]
    expected = DX if method == "angular_spectrum" else beam.wavelength * z / (N * DX)
    assert quiet(beam, z, method=method).spacing == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("method", ["fresnel", "fraunhofer"])
def test_far_field_divergence(beam, method):
    z = 1000 * rayleigh(W0, beam.wavelength)
    theta = quiet(beam, z, method=method).beam_radius / z
    assert theta == pytest.approx(beam.wavelength / (math.pi * W0), rel=DIVERGENCE_RTOL)


# --- complex field, power, chaining
# ------------------------------------------------------------------

SMALL = dict(
    wavelength=1064e-9, waist_radius=1e-3, n=256, spacing=1e-2 / 256
)  # +-5 w0; zR = 2.95 m


@pytest.mark.parametrize(
    "method, where, zoom",
    [
        ("angular_spectrum", "zc", None),
        ("fresnel", "3zc", None),
        ("fresnel", "10zr", 1 / 8),
        ("auto", "10zr", 1 / 8),
        ("fresnel", "300zr", None),
        ("fraunhofer", "300zr", None),
    ],
)
def test_complex_field(method, where, zoom):
    f = lo.Field.gaussian(**SMALL)
    w0, lam = SMALL["waist_radius"], SMALL["wavelength"]
    z = {
        "zc": 0.999 * critical(f),
        "3zc": 3 * critical(f),
        "10zr": 10 * rayleigh(w0, lam),
        "300zr": 300 * rayleigh(w0, lam),
    }[where]
    kwargs = (
        {} if zoom is None else dict(output_spacing=zoom * d1(z, w0, lam))
    )  # scaled (chirp-z) output
    g = quiet(f, z, method=method, **kwargs)
    if zoom is not None:
        assert g.spacing == pytest.approx(kwargs["output_spacing"], rel=1e-12)
    a0 = f.values[f.n // 2, f.n // 2]  # waist amplitude on axis, with whatever global phase it has
    closed = fraunhofer_gaussian if method == "fraunhofer" else gaussian_beam
    expected = closed(g.x, g.y, z, w0, lam, a0)
    diff = np.max(np.abs(g.values - expected)) / np.max(np.abs(expected))
    assert diff <= FIELD_TOL + PHASE_ROUNDING * 2 * math.pi / lam * z, (
        f"{method}, z = {z:.4g} m: {diff:.3g}"
    )


def test_angular_spectrum_is_not_paraxial():
    # w0 = 2 lambda (divergence 0.16 rad): the exact transfer function and its paraxial form differ
    # by ~5e-3 of the amplitude at z_c, so a Fresnel kernel fails here. 8 samples per w0, window +-8
    # w0.
    lam, w0, n, dx = 1e-6, 2e-6, 128, 0.25e-6
    f = lo.Field.gaussian(lam, w0, n, dx)
    z = 0.999 * critical(f)
    g = quiet(f, z, method="angular_spectrum")
    a0, c = f.values[n // 2, n // 2], n // 2
    for j in (0, 3, 8, 13, 20):
        exact = angular_spectrum_gaussian(j * dx, z, w0, lam, a0)
        for got in (g.values[c, c + j], g.values[c - j, c]):
            assert abs(got - exact) <= AS_EXACT_TOL * abs(a0), (
                f"r = {j * dx:.3g} m: {got} vs {exact}"
            )
    assert abs(
        angular_spectrum_gaussian(0.0, z, w0, lam, a0, paraxial=True) - g.values[c, c]
    ) > 1e-3 * abs(a0)


@pytest.mark.parametrize(
    "method, factor, scaled",
    [
        ("angular_spectrum", 0.5, False),
        ("angular_spectrum", 0.999, False),
        ("fresnel", 10.0, False),
        ("fresnel", 1e4, False),
        ("fresnel", 1e3, True),
        ("auto", 1e3, True),
    ],
)
def test_power_conserved(method, factor, scaled):
    f = lo.Field.gaussian(355e-9, W0, N, DX, power=0.37)
    z = factor * critical(f)
    kwargs = dict(output_spacing=d1(z, W0, 355e-9) / 8) if scaled else {}
    assert quiet(f, z, method=method, **kwargs).power == pytest.approx(f.power, rel=POWER_RTOL)


def test_angular_spectrum_chaining():
    # Offset, tilted TEM00 beam (w0 = 25 um, 10 samples per w0, zR = 1.85 mm): asymmetric, so a
    # flipped or shifted spectrum would not chain; it moves and spreads noticeably within z_c = 0.75
    # mm.
    n, dx, lam, w0 = 128, 2.5e-6, 1064e-9, 25e-6
    f0 = lo.Field.gaussian(lam, w0, n, dx, center=(20e-6, -12e-6))
    f = lo.Field(
        f0.values * np.exp(2j * math.pi * 2e4 * f0.x)[None, :], dx, lam
    )  # 0.021 rad along x
    z1, z2 = 0.3e-3, 0.4e-3
    assert z1 + z2 <= critical(f)
    twice = quiet(quiet(f, z1, method="angular_spectrum"), z2, method="angular_spectrum")
    once = quiet(f, z1 + z2, method="angular_spectrum")
    assert np.max(np.abs(twice.values - once.values)) <= CHAIN_TOL * np.max(np.abs(once.values))
    assert np.max(np.abs(once.values - f.values)) > 0.1 * np.max(
        np.abs(f.values)
    )  # not an identity


# --- uniformly lit circular aperture; Airy pattern in the focal plane of a lens
# ------------------------

AP_LAM, AP_A, AP_N, AP_NMAX = 355e-9, 10e-3, 2048, 5.0
AP_DX = 0.99 * AP_A / math.sqrt(AP_NMAX * AP_N)  # a/dx = 102; z_c = 0.98 a^2 / (lambda N_max)


@pytest.fixture(scope="module")
def aperture():
    return lo.Field(disc(AP_N, AP_DX, AP_A), AP_DX, AP_LAM)  # unit irradiance: I0 = 1


@pytest.mark.parametrize("fresnel_number", [1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0])
def test_on_axis_behind_circular_aperture(aperture, fresnel_number):
    g, _ = recorded(
        aperture, AP_A**2 / (AP_LAM * fresnel_number), method="fresnel"
    )  # warnings: see below
    on_axis = g.intensity[g.n // 2, g.n // 2]
    expected = 4.0 * math.sin(math.pi * fresnel_number / 2) ** 2
    tol = ON_AXIS_EDGE_COEFF * (fresnel_number * AP_DX / AP_A) ** 2
    assert abs(on_axis - expected) <= tol, (
        f"N = {fresnel_number}: I/I0 = {on_axis:.6f}, expected {expected}"
    )


AIRY_LAM, AIRY_F, AIRY_A, AIRY_N = 355e-9, 1.0, 5e-3, 512
AIRY_DX = 0.99 * math.sqrt(AIRY_LAM * AIRY_F / AIRY_N)  # critical distance just below f; a/dx = 190
AIRY_DXO = AIRY_LAM * AIRY_F / (2 * AIRY_A) / 16  # pi/16 in v; output window v = +-50


@pytest.fixture(scope="module")
def lens_aperture():
    x = (np.arange(AIRY_N) - AIRY_N // 2) * AIRY_DX
    lens = np.exp(-1j * math.pi / (AIRY_LAM * AIRY_F) * (x[None, :] ** 2 + x[:, None] ** 2))
    return lo.Field(disc(AIRY_N, AIRY_DX, AIRY_A) * lens, AIRY_DX, AIRY_LAM)


def test_airy_focal_plane(lens_aperture):
    g, _ = recorded(
        lens_aperture, AIRY_F, method="fresnel", output_spacing=AIRY_DXO
    )  # warnings: see below
    lam, focal, a, n = AIRY_LAM, AIRY_F, AIRY_A, AIRY_N
    power = math.pi * a**2  # unit irradiance through the aperture
    i0 = power * math.pi * a**2 / (lam * focal) ** 2
    v = 2 * math.pi * a * g.x / (lam * focal)
    vs = np.where(v == 0, 1.0, v)
    airy = np.where(v == 0, 1.0, (2 * j1(vs) / vs) ** 2)
    for profile in (g.intensity[n // 2, :], g.intensity[:, n // 2]):
        err = np.max(np.abs(profile / i0 - airy)[np.abs(v) <= 20])
        assert err <= AIRY_PROFILE_ATOL, f"Airy profile: max |I/I0 - [2J1(v)/v]^2| = {err:.3g}"
    for vr in (3.8317, 7.0156, 10.1735, 13.3237, 20.0):  # dark rings, then a generic radius
        r = vr * lam * focal / (2 * math.pi * a)
        ee = float(np.sum(disc(n, AIRY_DXO, r) * g.intensity)) * AIRY_DXO**2 / power
        expected = 1.0 - j0(vr) ** 2 - j1(vr) ** 2
        assert abs(ee - expected) <= AIRY_EE_ATOL, (
            f"EE(v = {vr}) = {ee:.6f}, expected {expected:.6f}"
        )


def test_hard_edge_single_fft_reports_its_aliased_spectrum(aperture):
    # A hard edge has power up to the input's Nyquist frequency, and the single-FFT output window
    # lambda z/dx is exactly that band: its outer part is aliased. The closed form is still met to
    # the pixel-edge tolerance (above), but the warning must say why the outer region cannot be
    # trusted.
    with warnings.catch_warnings(record=True):
        with pytest.warns(lo.SamplingWarning, match=r"Nyquist.*aliased"):
            lo.propagate(aperture, AP_A**2 / AP_LAM, method="fresnel")  # Fresnel number 1


def test_zoomed_focus_is_inside_validity(lens_aperture):
    # A chirp-z output window is the caller's choice: Airy rings outside it are not computed,
    # nothing wraps around, so no warning (A3 holds, the input chirp is sampled).
    quiet(lens_aperture, AIRY_F, method="fresnel", output_spacing=AIRY_DXO)
