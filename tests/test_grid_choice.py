"""propagate(..., grid_size=...): zero padding chosen by the library (or given) so that a
propagation neither wraps around nor loses power, checked against the TEM00 closed form (paper D1)
and against an independent NumPy zero padding."""

import warnings

import numpy as np
import pytest

import lidar_overlap as lo

W0, WAVELENGTH = 0.2e-3, 1064e-9
Z_R = np.pi * W0**2 / WAVELENGTH
N, SPACING = 128, 4 * W0 / 64  # a window of 8 w0: tight, so that the beam soon outgrows it
# Angular spectrum on the padded grid: the band limit and the window cut ~1e-7 of the power (the
# sizing fraction); the second-moment radius moves by ~1e-6.
AS_D1_RTOL = 1e-5
# Fresnel of a Gaussian is exact; padding only adds rounding.
FRESNEL_D1_RTOL = 1e-11
# Padding by hand and by the core feed the same numbers to the same plans.
PAD_ATOL = 1e-12
# The Fresnel output spacing must sample the irradiance at Nyquist: window >= twice the input's
# diameter, where the diameter holds all but 1e-7 of the power (2 * 2.84 w0 for TEM00).
TEM00_RADIUS_1E7 = np.sqrt(np.log(1e7) / 2) * W0


def d1(z):
    return W0 * np.sqrt(1 + (z / Z_R) ** 2)


def tem00():
    return lo.Field.gaussian(WAVELENGTH, W0, N, SPACING)


def propagate_quietly(*args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("error", lo.SamplingWarning)
        return lo.propagate(*args, **kwargs)


def test_fixed_grid_wraps_where_auto_grid_does_not():
    z = 3 * Z_R
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        clipped = lo.propagate(tem00(), z, method="angular_spectrum")
    reasons = " ".join(str(w.message) for w in caught if w.category is lo.SamplingWarning)
    assert "window edge" in reasons and "band-limited" in reasons
    assert abs(clipped.beam_radius / d1(z) - 1) > 1e-2  # the wrapped field is wrong
    out = propagate_quietly(tem00(), z, method="angular_spectrum", grid_size="auto")
    assert out.n > N and out.n & (out.n - 1) == 0  # padded, to a power of two
    assert out.spacing == SPACING
    assert abs(out.beam_radius / d1(z) - 1) < AS_D1_RTOL
    assert abs(out.power / tem00().power - 1) < 1e-6


@pytest.mark.parametrize("z_over_zr", [0.3, 3.0, 30.0, 300.0])
def test_auto_grid_and_method_follow_d1(z_over_zr):
    z = z_over_zr * Z_R
    out = propagate_quietly(tem00(), z, grid_size="auto")
    tol = AS_D1_RTOL if out.spacing == SPACING else FRESNEL_D1_RTOL
    assert abs(out.beam_radius / d1(z) - 1) < tol
    if out.spacing != SPACING:  # Fresnel: the window spans twice the input diameter
        assert out.n * SPACING >= 4 * TEM00_RADIUS_1E7


def test_explicit_grid_size_is_a_zero_padding():
    field, z, n = tem00(), 0.5 * Z_R, 256
    by_core = lo.propagate(field, z, method="angular_spectrum", grid_size=n)
    pad = (n - N) // 2
    by_hand = lo.propagate(
        lo.Field(np.pad(field.values, pad), SPACING, WAVELENGTH), z, method="angular_spectrum"
    )
    assert by_core.n == n
    np.testing.assert_allclose(
        by_core.values, by_hand.values, rtol=0, atol=PAD_ATOL * np.abs(by_hand.values).max()
    )


def test_auto_grid_never_shrinks_a_large_grid():
    big = lo.Field.gaussian(WAVELENGTH, W0, 512, SPACING)
    assert propagate_quietly(big, 0.1 * Z_R, method="angular_spectrum", grid_size="auto").n == 512


def test_tilted_beam_is_followed_off_axis():
    # A plane-wave tilt of 20 diffraction angles walks the beam 0.9 window half-widths off the axis
    # in z.
    field = tem00()
    tilt = 20 * WAVELENGTH / (np.pi * W0)
    x = field.x[None, :]
    tilted = lo.Field(
        field.values * np.exp(2j * np.pi * np.sin(tilt) * x / WAVELENGTH), SPACING, WAVELENGTH
    )
    z = 0.9 * (N / 2 * SPACING) / tilt
    out = propagate_quietly(tilted, z, method="angular_spectrum", grid_size="auto")
    assert abs(out.centroid[0] / (z * np.tan(np.arcsin(np.sin(tilt)))) - 1) < 1e-4
    assert abs(out.beam_radius / d1(z) - 1) < 1e-4


@pytest.mark.parametrize(
    "grid_size, match",
    [
        (100, "integer >= 128"),
        (130.0, "integer >= 128"),
        (129, "even size"),
        ("large", "grid_size"),
    ],
)
def test_bad_grid_size(grid_size, match):
    with pytest.raises(ValueError, match=match):
        lo.propagate(tem00(), Z_R, grid_size=grid_size)


def test_auto_grid_refuses_beyond_its_cap():
    with pytest.raises(ValueError, match="grid_size .* at most 8192"):
        lo.propagate(tem00(), 300 * Z_R, method="angular_spectrum", grid_size="auto")
