"""Beam profiles beyond TEM00 (annulus, Laguerre-Gauss, super-Gaussian) against closed forms.

Checked against:
- LG_p^l vortices: the phase winds by 2 pi l around the axis and the on-axis irradiance is 0 (l !=
  0), at the waist and in the far field (Fresnel, 50 Rayleigh ranges); LG_0^0 is the TEM00 of
  Field.gaussian; the second-moment radius is w0 sqrt(2p + |l| + 1);
- a uniformly lit annulus (radii b < a, eps = b/a): Fraunhofer pattern I/I(0) = [(2 J1(v)/v - eps^2
  2 J1(eps v)/(eps v)) / (1 - eps^2)]^2, v = k a theta; its area pi (a^2 - b^2); power conservation;
- super-Gaussian I = I0 exp(-2 (r/R)^(2N)): N = 1 is TEM00, N = 10 is flat inside R/2 and exp(-2) I0
  at R;
- every profile carries the requested power; bad arguments raise ValueError naming the parameter.
"""

import math
import warnings

import numpy as np
import pytest
from scipy.special import j1

import lidar_overlap as lo
from lidar_overlap.optics.beam_fields import (
    annular_field,
    laguerre_gauss_field,
    super_gaussian_field,
)

# The profiles are scaled by their sampled power: what is left is the rounding of a sum of n^2 <=
# 2.6e5 terms.
POWER_RTOL = 1e-12
# Same formula as Field.gaussian; its analytic amplitude differs from the sampled-power scaling by
# the tail beyond the window (exp(-2 * 16^2) for LG, exp(-2 * 6.4^2) for the super-Gaussian) and the
# Poisson error of the Riemann sum (exp(-pi^2 (w/dx)^2 / 2) < 1e-100): rounding only.
TEM00_RTOL = 1e-12
# The sampled loop is closed, so the unwrapped phase returns to its start plus 2 pi times an
# integer, up to the rounding of 512 differences (~1e-13); a wrong charge is off by at least 1.
WINDING_ATOL = 1e-9
# Far-field on-axis irradiance / peak: an exact zero of the field and, by the grid's 4-fold
# symmetry, of the DFT sum (l = 1, 2, 3 mod 4); FFT rounding leaves an amplitude ~eps log2(n^2) ~
# 4e-15 of the peak, i.e. ~1e-29 in irradiance (measured <= 2e-34). Allowed: 1e-24.
FAR_NULL_RTOL = 1e-24
# Second moments of LG modes with 8 samples per w0 in a +-16 w0 window: Poisson and truncation
# errors are below 1e-100, so rounding (measured ~1e-14); the same target as the TEM00 radius in
# test_field.
RADIUS_RTOL = 1e-9
# Annulus far field relative to I(0), for |v| <= 4 pi (past the third dark ring for eps = 0, 0.3 and
# 0.5): area-weighted edge pixels perturb the core by ~(dx/a)^2 / 3 (measured 1.5e-5 to 3.1e-5 at
# a/dx = 100); allowed twice that. A binary (not anti-aliased) mask errs by 1.7e-4 to 3.7e-4 and
# fails.
ANNULUS_PROFILE_ATOL = 6e-5
ANNULUS_V_MAX = 4 * math.pi
# Sampled annulus area sum(U)/U0 dx^2 vs pi (a^2 - b^2): ~1e3 edge pixels whose 8x8 coverage errs by
# up to 1/128 of a pixel, mostly cancelling: ~1e-5 of the area (a/dx = 100). A binary mask errs by
# ~1e-3.
ANNULUS_AREA_RTOL = 1e-4
# Single-FFT Fraunhofer is unitary (Parseval); rounding of FFTs over 2.6e5 points, as in
# test_propagate.
FAR_POWER_RTOL = 1e-10
# Order-10 top-hat inside r < R/2: the closed form droops by 1 - exp(-2 (1/2)^20) = 1.9e-6 at R/2
# itself (1e-6 holds only inside 0.484 R); allowed 2e-6.
FLAT_TOP_RTOL = 2e-6

LAM = 1064e-9
W0 = 1e-3
N = 256
DX = W0 / 8  # 8 samples per w0, window +-16 w0


def lg(l, p=0, n=N, spacing=DX, power=1.0):
    return laguerre_gauss_field(LAM, W0, l, p, n=n, spacing=spacing, power=power)


def winding(field, radius, curvature=math.inf):
    """Total phase change / 2 pi once around a closed loop of the samples nearest the circle of
    ``radius`` (m) about the grid centre, after removing a spherical phase k r^2 / (2 curvature)."""
    c, t = field.n // 2, np.linspace(0, 2 * np.pi, 512, endpoint=False)
    ix = c + np.rint(radius * np.cos(t) / field.spacing).astype(int)
    iy = c + np.rint(radius * np.sin(t) / field.spacing).astype(int)
    r2 = field.x[ix] ** 2 + field.y[iy] ** 2
    phase = np.angle(
        field.values[iy, ix] * np.exp(-1j * math.pi * r2 / (field.wavelength * curvature))
    )
    return (np.unwrap(np.append(phase, phase[0]))[-1] - phase[0]) / (2 * np.pi)


# --- Laguerre-Gauss
# ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("l", [1, 2, -3])
def test_vortex_winding_and_null_at_waist_and_far_field(l):
    f = lg(l, power=2.5)
    assert f.power == pytest.approx(2.5, rel=POWER_RTOL)
    assert f.values[N // 2, N // 2] == 0.0  # (sqrt2 r / w0)^|l| vanishes on the axis
    assert winding(f, W0) == pytest.approx(l, abs=WINDING_ATOL)
    zr = math.pi * W0**2 / LAM
    z = 50 * zr
    with warnings.catch_warnings():
        warnings.simplefilter("error", lo.SamplingWarning)
        g = lo.propagate(f, z, method="fresnel")
    c = g.n // 2
    assert g.intensity[c, c] <= FAR_NULL_RTOL * g.intensity.max(), f"l = {l}: on-axis null filled"
    # The far field carries the Gaussian-beam wavefront, radius R(z) = z (1 + (zR/z)^2), on top of l
    # phi.
    w_z = W0 * math.hypot(1.0, z / zr)
    assert winding(g, w_z, curvature=z * (1 + (zr / z) ** 2)) == pytest.approx(l, abs=WINDING_ATOL)


def test_lg00_is_tem00():
    f, g = lg(0, 0, power=0.7), lo.Field.gaussian(LAM, W0, N, DX, power=0.7)
    np.testing.assert_allclose(f.values, g.values, rtol=0, atol=TEM00_RTOL * np.abs(g.values).max())
    assert winding(f, W0) == pytest.approx(0, abs=WINDING_ATOL)


@pytest.mark.parametrize("l, p", [(0, 0), (1, 0), (-3, 0), (0, 2), (2, 1), (3, 2)])
def test_lg_second_moment_radius(l, p):
    f = lg(l, p)
    assert f.power == pytest.approx(1.0, rel=POWER_RTOL)
    assert f.beam_radius == pytest.approx(W0 * math.sqrt(2 * p + abs(l) + 1), rel=RADIUS_RTOL)
    assert np.hypot(*f.centroid) <= RADIUS_RTOL * W0


# --- uniformly lit annulus
# --------------------------------------------------------------------------------

A_N, A_DX, A_LAM = 512, 1e-4, 532e-9
A_OUTER = 100 * A_DX


@pytest.mark.parametrize("eps", [0.0, 0.3, 0.5])
def test_annulus_far_field_is_difference_of_airy_patterns(eps):
    f = annular_field(A_LAM, A_OUTER, eps * A_OUTER, A_N, A_DX, power=3.0)
    assert f.power == pytest.approx(3.0, rel=POWER_RTOL)
    u0 = np.abs(f.values).max()
    area = float(np.sum(f.values.real)) / u0 * A_DX**2
    assert area == pytest.approx(math.pi * A_OUTER**2 * (1 - eps**2), rel=ANNULUS_AREA_RTOL)

    z = 1000 * A_OUTER**2 / A_LAM  # Fraunhofer phase pi a^2/(lambda z) = 3e-3 rad
    dv = math.pi / 16  # output sampled every pi/16 in v, out to |v| = 50
    with warnings.catch_warnings():
        warnings.simplefilter(
            "error", lo.SamplingWarning
        )  # scaled output: nothing aliased, no warning
        g = lo.propagate(
            f, z, method="fraunhofer", output_spacing=dv * A_LAM * z / (2 * math.pi * A_OUTER)
        )
    v = 2 * math.pi / A_LAM * A_OUTER * g.x / z
    vs = np.where(v == 0, 1.0, v)
    inner = eps**2 * 2 * j1(eps * vs) / (eps * vs) if eps > 0 else 0.0
    expected = np.where(v == 0, 1.0, ((2 * j1(vs) / vs - inner) / (1 - eps**2)) ** 2)
    c, near = g.n // 2, np.abs(v) <= ANNULUS_V_MAX
    for profile in (g.intensity[c, :], g.intensity[:, c]):
        err = np.max(np.abs(profile / profile[c] - expected)[near])
        assert err <= ANNULUS_PROFILE_ATOL, f"eps = {eps}: max |I/I(0) - analytic| = {err:.3g}"


def test_annulus_far_field_conserves_power():
    f = annular_field(A_LAM, A_OUTER, 0.5 * A_OUTER, A_N, A_DX)
    # The hard edge has power up to the Nyquist frequency, which lands in the outer window and is
    # reported.
    with pytest.warns(lo.SamplingWarning, match="aliased"):
        g = lo.propagate(f, 1000 * A_OUTER**2 / A_LAM, method="fraunhofer")
    assert g.power == pytest.approx(f.power, rel=FAR_POWER_RTOL)


# --- super-Gaussian
# ---------------------------------------------------------------------------------------

S_R = 20 * DX  # window +-6.4 R


def test_super_gaussian_order_one_is_tem00():
    f, g = (
        super_gaussian_field(LAM, S_R, 1, N, DX, power=0.3),
        lo.Field.gaussian(LAM, S_R, N, DX, power=0.3),
    )
    np.testing.assert_allclose(f.values, g.values, rtol=0, atol=TEM00_RTOL * np.abs(g.values).max())


def test_super_gaussian_order_ten_is_flat_topped():
    f = super_gaussian_field(LAM, S_R, 10, N, DX, power=4.0)
    assert f.power == pytest.approx(4.0, rel=POWER_RTOL)
    i, c = f.intensity, N // 2
    r = np.hypot(f.x[None, :], f.y[:, None])
    assert 1 - i[r < 0.5 * S_R].min() / i[c, c] <= FLAT_TOP_RTOL
    assert i[c, c + 20] / i[c, c] == pytest.approx(math.exp(-2), rel=TEM00_RTOL)  # r = R exactly
    assert i[c, c + 18] / i[c, c] == pytest.approx(math.exp(-2 * 0.9**20), rel=TEM00_RTOL)
    assert np.all(f.values.imag == 0)


# --- bad input
# --------------------------------------------------------------------------------------------

BAD = [
    (lambda: annular_field(LAM, 1e-3, 1e-3, 64, 1e-4), r"^inner_radius = "),
    (lambda: annular_field(LAM, 1e-3, 2e-3, 64, 1e-4), r"^inner_radius = "),
    (lambda: annular_field(LAM, 1e-3, -1e-4, 64, 1e-4), r"^inner_radius = "),
    (lambda: annular_field(LAM, 3e-3, 0.0, 64, 1e-4), r"^outer_radius = .*0\.45"),  # 0.45 * 6.4 mm
    (lambda: annular_field(LAM, 1e-3, 0.0, 63, 1e-4), r"^n = 63"),
    (lambda: annular_field(-LAM, 1e-3, 0.0, 64, 1e-4), r"^wavelength = "),
    (lambda: laguerre_gauss_field(LAM, -W0, 1, n=N, spacing=DX), r"^waist_radius = "),
    (lambda: laguerre_gauss_field(LAM, W0, 1, -1, n=N, spacing=DX), r"^p = -1"),
    (lambda: laguerre_gauss_field(LAM, W0, 1.5, n=N, spacing=DX), r"^l = 1\.5"),
    (lambda: laguerre_gauss_field(LAM, W0, "1", n=N, spacing=DX), r"^l = "),
    (
        lambda: laguerre_gauss_field(LAM, W0, 3, n=64, spacing=DX),
        r"^n \* spacing = .*increase n or spacing",
    ),
    (lambda: laguerre_gauss_field(LAM, W0, 0, 5, n=128, spacing=DX), r"^n \* spacing = "),
    (lambda: laguerre_gauss_field(LAM, W0, 1, n=N, spacing=DX, power=0.0), r"^power = "),
    (lambda: super_gaussian_field(LAM, S_R, 0.5, N, DX), r"^order = 0\.5"),
    (lambda: super_gaussian_field(LAM, S_R, math.nan, N, DX), r"^order = nan"),
    (lambda: super_gaussian_field(LAM, -S_R, 2, N, DX), r"^radius = "),
    (lambda: super_gaussian_field(LAM, S_R, 2, N, -DX), r"^spacing = "),
    (lambda: super_gaussian_field(LAM, 1e-3, 2, 32, 1e-4), r"^n \* spacing = "),
]


@pytest.mark.parametrize("call, match", BAD)
def test_bad_input_names_the_parameter(call, match):
    with pytest.raises(ValueError, match=match):
        call()
