"""Field: construction, centred coordinates, power, centroid and second-moment radius against closed
forms.

Checked against:
- the coordinate convention x_j = y_j = (j - n//2) * spacing (index n//2 is 0), row index = y,
  column = x;
- intensity = |values|^2 and power = sum(intensity) * spacing^2 for arbitrary values;
- the TEM00 irradiance at its waist, I(r) = 2 P / (pi w0^2) exp(-2 r^2 / w0^2), with flat phase: its
  integral is P, its centroid is its centre and its second-moment radius sqrt(2 (sigma_x^2 +
  sigma_y^2)) is w0;
- an elliptical Gaussian (radius sqrt((wx^2 + wy^2) / 2)) and two unequal spots (power-weighted
  centroid);
- bad arguments raise ValueError naming the parameter.
"""

import dataclasses
import math

import numpy as np
import pytest

import lidar_overlap as lo

EPS = np.finfo(float).eps
# Coordinates are integers times the spacing: exact, or off by a few ulps of the half-window if the
# library forms them as j*spacing - (n/2)*spacing.
COORD_ATOL_ULPS = 4 * EPS
# Sums of n^2 <= 65536 products, rounded in any order: well below 1e-13 relative.
ROUNDING_RTOL = 1e-13
# Riemann sum of a sampled Gaussian with w0/spacing >= 8: by Poisson summation its error is ~2
# exp(-pi^2 (w0/spacing)^2 / 2) < 1e-100; the window (>= +-4 w0) cuts off erfc(4 sqrt 2) ~ 1e-15 of
# the power; what is left is the rounding of ~6e4 terms.
GAUSS_POWER_RTOL = 1e-12
# Pointwise TEM00 profile (analytic amplitude sqrt(2P / (pi w0^2))): rounding of exp and sqrt only,
# or at most the ~1e-15 truncated power if the library normalises the sampled sum instead.
GAUSS_PROFILE_RTOL = 1e-12
# Second moments: same Poisson and truncation arguments (the tail beyond 4 w0 carries ~1e-13 of the
# second moment); the brief's target for a grid spanning +-4 w0 with >= 8 samples per w0.
RADIUS_RTOL = 1e-9
# First moments of coordinates up to 8 w0 summed over 65536 samples: the rounding bound n^2 eps * 8
# w0 is ~1e-10 w0 (pairwise summation does far better); the sampling error is again ~exp(-100).
CENTROID_ATOL_W0 = 1e-10

NOT_POSITIVE = [0.0, -1e-3, math.nan, math.inf, -math.inf]

# (n, spacing / w0): window half-widths 4 w0 (8 samples per w0, the minimum quoted), 6.4 w0 and 4.17
# w0.
GRIDS = [(64, 1 / 8), (256, 1 / 20), (100, 1 / 12)]


def tem00(x, y, w0, power, center=(0.0, 0.0)):
    """Irradiance of a TEM00 beam at its waist (W/m^2)."""
    r2 = (x[None, :] - center[0]) ** 2 + (y[:, None] - center[1]) ** 2
    return 2.0 * power / (math.pi * w0**2) * np.exp(-2.0 * r2 / w0**2)


# --- construction and attributes
# ---------------------------------------------------------------------


def test_attributes_of_arbitrary_values():
    rng = np.random.default_rng(1)
    values = rng.normal(size=(16, 16)) + 1j * rng.normal(size=(16, 16))
    f = lo.Field(values, 2.5e-5, 1064e-9)
    assert f.n == 16
    assert f.spacing == 2.5e-5 and f.wavelength == 1064e-9
    assert f.values.shape == (16, 16) and f.values.dtype == np.complex128
    np.testing.assert_array_equal(f.values, values)
    np.testing.assert_allclose(f.intensity, np.abs(values) ** 2, rtol=ROUNDING_RTOL)
    expected = float(np.sum(np.abs(values) ** 2)) * 2.5e-5**2
    assert f.power == pytest.approx(expected, rel=ROUNDING_RTOL)


def test_real_values_become_complex():
    f = lo.Field(np.ones((8, 8)), 1e-3, 355e-9)
    assert f.values.dtype == np.complex128
    np.testing.assert_array_equal(f.values, np.ones((8, 8)))
    assert f.power == pytest.approx(64 * 1e-6, rel=ROUNDING_RTOL)


@pytest.mark.parametrize("n", [8, 64, 256, 1000])
def test_coordinates_are_centred(n):
    spacing = 3.7e-5
    f = lo.Field(np.zeros((n, n), complex), spacing, 532e-9)
    expected = (np.arange(n) - n // 2) * spacing
    atol = COORD_ATOL_ULPS * n * spacing
    assert f.x.shape == (n,) and f.y.shape == (n,)
    np.testing.assert_allclose(f.x, expected, rtol=0, atol=atol)
    np.testing.assert_allclose(f.y, expected, rtol=0, atol=atol)
    assert f.x[n // 2] == 0.0 and f.y[n // 2] == 0.0


def test_row_index_is_y():
    n, dx, w0 = 64, 1e-4, 5e-4
    center = (3 * dx, -5 * dx)  # on grid points: the peak is one sample
    f = lo.Field.gaussian(1064e-9, w0, n, dx, center=center)
    row, col = np.unravel_index(np.argmax(f.intensity), f.values.shape)
    assert (row, col) == (n // 2 - 5, n // 2 + 3)
    assert f.centroid == pytest.approx(center, abs=CENTROID_ATOL_W0 * w0)


# --- TEM00 closed forms
# --------------------------------------------------------------------------------


@pytest.mark.parametrize("n, step", GRIDS)
@pytest.mark.parametrize("power", [1.0, 2.5e-3, 7.0])
def test_gaussian_profile_and_power(n, step, power):
    w0 = 5e-3
    f = lo.Field.gaussian(355e-9, w0, n, step * w0, power=power)
    assert f.n == n and f.spacing == step * w0 and f.wavelength == 355e-9
    assert f.power == pytest.approx(power, rel=GAUSS_POWER_RTOL)
    expected = tem00(f.x, f.y, w0, power)
    significant = expected > 1e-20 * expected.max()
    np.testing.assert_allclose(
        f.intensity[significant], expected[significant], rtol=GAUSS_PROFILE_RTOL
    )
    phase = np.angle(f.values[significant])
    assert np.ptp(phase) <= 1e-12, "the waist field must have a flat phase"


@pytest.mark.parametrize("n, step", GRIDS)
@pytest.mark.parametrize("wavelength", [355e-9, 1064e-9])
def test_gaussian_beam_radius_is_waist(n, step, wavelength):
    w0 = 5e-3
    f = lo.Field.gaussian(wavelength, w0, n, step * w0)
    assert f.beam_radius == pytest.approx(w0, rel=RADIUS_RTOL)
    assert f.centroid == pytest.approx((0.0, 0.0), abs=CENTROID_ATOL_W0 * w0)


@pytest.mark.parametrize("center_w0", [(2.3, -1.7), (-0.37, 0.81), (0.0, 3.9)])
def test_offset_gaussian_centroid_and_radius(center_w0):
    # 16 samples per w0, window +-8 w0: the offset beam is still >= 4 w0 from every edge.
    n, w0 = 256, 1e-3
    center = (center_w0[0] * w0, center_w0[1] * w0)
    f = lo.Field.gaussian(532e-9, w0, n, w0 / 16, center=center, power=0.3)
    cx, cy = f.centroid
    assert cx == pytest.approx(center[0], abs=CENTROID_ATOL_W0 * w0)
    assert cy == pytest.approx(center[1], abs=CENTROID_ATOL_W0 * w0)
    assert f.beam_radius == pytest.approx(w0, rel=RADIUS_RTOL)
    assert f.power == pytest.approx(0.3, rel=GAUSS_POWER_RTOL)
    expected = tem00(f.x, f.y, w0, 0.3, center)
    significant = expected > 1e-20 * expected.max()
    np.testing.assert_allclose(
        f.intensity[significant], expected[significant], rtol=GAUSS_PROFILE_RTOL
    )


def test_elliptical_beam_radius_is_second_moment():
    # |U|^2 = exp(-2x^2/wx^2 - 2y^2/wy^2): sigma_x^2 = wx^2/4, so sqrt(2 (sigma_x^2 + sigma_y^2)) =
    # sqrt((wx^2 + wy^2) / 2). A radius taken from one axis or from the peak would fail. 12 samples
    # per wx, half-window 3.2 mm = 4.6 wy: sampling and truncation errors as for the TEM00 grids.
    n, dx, wx, wy = 256, 2.5e-5, 0.3e-3, 0.7e-3
    x = (np.arange(n) - n // 2) * dx
    values = np.exp(-(x[None, :] ** 2) / wx**2 - x[:, None] ** 2 / wy**2)
    f = lo.Field(values, dx, 1064e-9)
    assert f.beam_radius == pytest.approx(math.sqrt((wx**2 + wy**2) / 2), rel=RADIUS_RTOL)


def test_centroid_of_two_unequal_spots():
    # Two separated Gaussian spots of powers 1 and 3: the centroid is the power-weighted mean of the
    # centres.
    n, w0 = 256, 1e-3
    a = lo.Field.gaussian(1064e-9, w0, n, w0 / 16, center=(-2 * w0, 1 * w0), power=1.0)
    b = lo.Field.gaussian(1064e-9, w0, n, w0 / 16, center=(2 * w0, -1 * w0), power=3.0)
    # Field with the summed irradiance (amplitude sqrt(I_a + I_b)), so the spots add without
    # interference.
    f = lo.Field(np.sqrt(a.intensity + b.intensity), a.spacing, a.wavelength)
    cx, cy = f.centroid
    assert cx == pytest.approx((-2 * w0 + 3 * 2 * w0) / 4, abs=CENTROID_ATOL_W0 * w0)
    assert cy == pytest.approx((1 * w0 + 3 * -1 * w0) / 4, abs=CENTROID_ATOL_W0 * w0)
    assert f.power == pytest.approx(4.0, rel=GAUSS_POWER_RTOL)


# --- bad input
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("shape", [(8, 10), (10, 8), (64,), (9, 9), (6, 6), (2, 8, 8), (0, 0)])
def test_field_bad_shape(shape):
    with pytest.raises(ValueError, match="values"):
        lo.Field(np.ones(shape, complex), 1e-4, 355e-9)


@pytest.mark.parametrize("value", NOT_POSITIVE)
@pytest.mark.parametrize("name", ["spacing", "wavelength"])
def test_field_bad_sizes(name, value):
    args = dict(spacing=1e-4, wavelength=355e-9)
    args[name] = value
    with pytest.raises(ValueError, match=name):
        lo.Field(np.ones((8, 8), complex), args["spacing"], args["wavelength"])


@pytest.mark.parametrize("value", NOT_POSITIVE)
@pytest.mark.parametrize("name", ["wavelength", "waist_radius", "spacing"])
def test_gaussian_bad_sizes(name, value):
    args = dict(wavelength=355e-9, waist_radius=1e-3, n=64, spacing=1e-4)
    args[name] = value
    with pytest.raises(ValueError, match=name):
        lo.Field.gaussian(**args)


@pytest.mark.parametrize("value", [7, 6, 0, -8])
def test_gaussian_bad_n(value):
    with pytest.raises(ValueError, match=r"\bn\b"):
        lo.Field.gaussian(355e-9, 1e-3, value, 1e-4)


@pytest.mark.parametrize("value", [-1.0, math.nan, math.inf])
def test_gaussian_bad_power(value):
    with pytest.raises(ValueError, match="power"):
        lo.Field.gaussian(355e-9, 1e-3, 64, 1e-4, power=value)


@pytest.mark.parametrize("value", [(math.nan, 0.0), (0.0, math.inf)])
def test_gaussian_bad_center(value):
    with pytest.raises(ValueError, match="center"):
        lo.Field.gaussian(355e-9, 1e-3, 64, 1e-4, center=value)


# --------------------------------------------------------------------------------- hostile input
#: Neither a real number nor a length within the core's scales (1e-10 to 1e10 m).
HOSTILE_LENGTHS = [
    math.nan,
    math.inf,
    0.0,
    -0.0,
    5e-324,
    1e-300,
    1e300,
    2**40,
    2**63,
    10**400,
    True,
    "1",
    None,
]


@pytest.mark.parametrize(
    "values",
    [
        np.full((8, 8), "a"),
        np.full((8, 8), True),
        np.full((8, 8), None),
        np.full((8, 8), 10**400),
        [["1"] * 8] * 8,
        None,
        "values",
    ],
)
def test_field_refuses_values_that_are_not_numbers(values):
    with pytest.raises(ValueError, match="^values has dtype"):
        lo.Field(values, 1e-4, 355e-9)


def test_field_refuses_ragged_values_by_name():
    with pytest.raises(ValueError, match="^values is invalid"):
        lo.Field([[1.0] * 8] * 7 + [[1.0] * 3], 1e-4, 355e-9)


@pytest.mark.parametrize("amplitude", [1e200, 1e300, 1e17])
def test_field_refuses_values_whose_power_leaves_double_range(amplitude):
    """Σ|U|² spacing² must stay <= 1e30 W, the core's power bound: 64 samples of 1e17 on 1 cm carry
    6.4e31 W, larger amplitudes overflow to inf."""
    spacing = 1e-2
    with pytest.raises(ValueError, match=r"^values is invalid: its power"):
        lo.Field(np.full((8, 8), amplitude), spacing, 355e-9)


def test_field_takes_integer_values_as_complex():
    ints = np.arange(64, dtype=np.int64).reshape(8, 8)
    f = lo.Field(ints, 1e-4, 355e-9)
    assert f.values.dtype == np.complex128 and np.array_equal(f.values, ints.astype(complex))


@pytest.mark.parametrize("value", HOSTILE_LENGTHS)
@pytest.mark.parametrize("name", ["spacing", "wavelength"])
def test_field_refuses_lengths_outside_the_scales_by_name(name, value):
    args = dict(spacing=1e-4, wavelength=355e-9)
    args[name] = value
    with pytest.raises(ValueError, match=f"^{name} = "):
        lo.Field(np.ones((8, 8), complex), **args)


SMALL = lo.Field.gaussian(355e-9, 1e-3, 64, 1e-4)


@pytest.mark.parametrize(
    "value", [math.nan, math.inf, 1e300, 2**63, 10**400, True, "1", None, (1.0, 2.0)]
)
def test_propagate_refuses_distance_by_name(value):
    with pytest.raises(ValueError, match="^distance = "):
        lo.propagate(SMALL, value)


@pytest.mark.parametrize(
    "value", [math.nan, 0.0, -0.0, 5e-324, 1e-300, 1e300, 2**63, 10**400, True, "1"]
)
def test_propagate_refuses_output_spacing_by_name(value):
    with pytest.raises(ValueError, match="^output_spacing = "):
        lo.propagate(SMALL, 10.0, method="fresnel", output_spacing=value)


@pytest.mark.parametrize(
    "value", [2**31 - 1, 2**62, 2**63, 10**400, 65538, 63, 65, 1.0, 64.0, True, "AUTO", (64,)]
)
def test_propagate_refuses_grid_size_by_name(value):
    with pytest.raises(ValueError, match="^grid_size = "):
        lo.propagate(SMALL, 10.0, grid_size=value)


@pytest.mark.parametrize("value", [None, "", "Fresnel", b"fresnel", 0, True, ("fresnel",)])
def test_propagate_refuses_method_by_name(value):
    with pytest.raises(ValueError, match="^method = "):
        lo.propagate(SMALL, 10.0, method=value)


def test_propagate_refuses_a_non_field_by_name():
    with pytest.raises(ValueError, match="^field = "):
        lo.propagate(np.ones((8, 8)), 10.0)


@pytest.mark.parametrize(
    "value", [np.array(["fresnel", "auto"]), np.array(["fresnel"]), ["fresnel"]]
)
def test_propagate_refuses_a_method_that_is_not_a_string_by_name(value):
    with pytest.raises(ValueError, match="^method = "):
        lo.propagate(SMALL, 10.0, method=value)


def test_field_is_immutable_and_holds_a_read_only_copy():
    values = np.ones((8, 8), complex)
    f = lo.Field(values, 1e-4, 355e-9)
    values[0, 0] = 2.0  # the caller's array is not the field's
    assert f.values[0, 0] == 1.0
    for name, value in (("values", values), ("spacing", 2e-4), ("wavelength", 532e-9)):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(f, name, value)
    with pytest.raises(ValueError, match="read-only"):
        f.values[0, 0] = 1.0


@pytest.mark.parametrize(
    "make",
    [
        lambda: lo.Field.gaussian(355e-9, 1e-3, 64, 1e-4),
        lambda: lo.propagate(lo.Field.gaussian(355e-9, 1e-3, 64, 1e-4), 10.0),
    ],
    ids=["gaussian", "propagated"],
)
def test_fields_from_the_core_are_read_only(make):
    f = make()
    with pytest.raises(ValueError, match="read-only"):
        f.values[0, 0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        f.spacing = 1.0


def test_replace_makes_a_new_checked_field():
    f = lo.Field.gaussian(355e-9, 1e-3, 64, 1e-4)
    g = dataclasses.replace(f, spacing=2e-4)
    assert (g.spacing, g.wavelength, f.spacing) == (2e-4, 355e-9, 1e-4)
    assert not g.values.flags.writeable and np.array_equal(g.values, f.values)
    with pytest.raises(ValueError, match="spacing"):
        dataclasses.replace(f, spacing=-1.0)
