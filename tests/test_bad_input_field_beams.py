"""Invalid beam profiles, field beams and flat tops are rejected with a ValueError that names the
offending parameter, before any grid is allocated; extreme but valid indices and orders give finite
fields. The system's own parts are checked in test_bad_input.py."""

import math

import numpy as np
import pytest

import lidar_overlap as lo

NAN = math.nan
HUGE = [2**31, 2**63, 10**400, 1.7976931348623157e308, 1e300]
LG = dict(wavelength=355e-9, waist_radius=1e-3, l=1, p=1, n=64, spacing=2e-4)
PROFILES = {
    "annular_field": dict(
        wavelength=355e-9, outer_radius=1e-3, inner_radius=2e-4, n=64, spacing=5e-5
    ),
    "laguerre_gauss_field": LG,
    "super_gaussian_field": dict(wavelength=355e-9, radius=1e-3, order=4.0, n=64, spacing=1e-4),
}


def profile(fn, **changes):
    return getattr(lo, fn)(**{**PROFILES[fn], **changes})


@pytest.mark.parametrize("value", [2**31 - 1, 2**63, 10**400, 65538, 7, 0, True, 64.0, "64", None])
@pytest.mark.parametrize("fn", sorted(PROFILES))
def test_profile_n_refused_by_name(fn, value):
    with pytest.raises(ValueError, match="^n = "):
        profile(fn, n=value)


@pytest.mark.parametrize("fn", sorted(PROFILES))
def test_profile_n_beyond_the_memory_budget_refused_before_allocation(fn):
    previous = lo.max_memory()
    lo.set_max_memory(1 << 30)
    try:
        with pytest.raises(ValueError, match=r"^n = 16384 needs .* \(max_memory\)"):
            profile(fn, n=16384)
    finally:
        lo.set_max_memory(previous)


@pytest.mark.parametrize("value", HUGE + [5e-324, 1e-300, 0.0, NAN, "1e-4", None])
@pytest.mark.parametrize("fn", sorted(PROFILES))
def test_profile_spacing_refused_by_name(fn, value):
    with pytest.raises(ValueError, match="spacing = "):
        profile(fn, spacing=value)


@pytest.mark.parametrize(
    "value", [10**400, 1.7976931348623157e308, 1e300, 1e31, 0.0, -1.0, NAN, True]
)
@pytest.mark.parametrize("fn", sorted(PROFILES))
def test_profile_power_refused_by_name(fn, value):
    with pytest.raises(ValueError, match="^power = "):
        profile(fn, power=value)


@pytest.mark.parametrize("fn", sorted(PROFILES))
def test_profile_on_a_grid_far_coarser_than_the_beam_refused_naming_spacing(fn):
    """A 1 mm beam on 1e5 m samples: no power, or all of it in the centre sample."""
    with pytest.raises(ValueError, match="^(spacing|n \\* spacing) = "):
        profile(fn, spacing=1e5, **({"inner_radius": 0.0} if fn == "annular_field" else {}))


@pytest.mark.parametrize(
    "name, value", [("l", 101), ("l", -101), ("l", 2**63), ("l", 1.0), ("p", 101), ("p", 2**63)]
)
def test_laguerre_gauss_indices_bounded(name, value):
    with pytest.raises(ValueError, match=f"^{name} = "):
        profile("laguerre_gauss_field", **{name: value})


@pytest.mark.parametrize("l, p", [(100, 0), (-100, 0), (0, 100), (100, 100)])
def test_laguerre_gauss_extreme_indices_are_finite_with_their_radius(l, p):
    """w0 sqrt(2p + |l| + 1), within what 1024² samples resolve of p + 1 rings (measured 0.3 % at p
    = 100)."""
    radius = 1e-3 * math.sqrt(2 * p + abs(l) + 1)
    f = profile("laguerre_gauss_field", l=l, p=p, n=1024, spacing=9.6 * radius / 1024)
    assert np.all(np.isfinite(f.values)) and abs(f.power - 1.0) < 1e-12
    assert abs(f.beam_radius / radius - 1) < 0.005


@pytest.mark.parametrize("order", [1e300, 1.7976931348623157e308, 10**300])
def test_super_gaussian_of_huge_order_is_a_disc_whose_window_is_checked(order):
    disc = profile("super_gaussian_field", order=order)
    assert abs(disc.beam_radius / 1e-3 - 1) < 0.02  # a uniform disc's second-moment radius is R
    with pytest.raises(ValueError, match=r"^n \* spacing = "):
        profile("super_gaussian_field", order=order, n=16)


@pytest.mark.parametrize("scale", [0.0, 5e-324, 1e-150])
def test_field_beam_refuses_a_field_without_power_by_name(scale):
    """Fields below 1e-100 W: their G underflowed to 0 in the FO path (1e-165 W did)."""
    g = lo.Field.gaussian(355e-9, 1e-3, 64, 1e-4)
    with pytest.raises(ValueError, match="^field = .* its power is"):
        lo.FieldBeam(lo.Field(g.values * scale, g.spacing, g.wavelength))


def test_field_beam_refuses_a_single_sample_by_name():
    values = np.zeros((8, 8), complex)
    values[4, 4] = 1.0
    with pytest.raises(ValueError, match="^field = .* second-moment radius is 0 m"):
        lo.FieldBeam(lo.Field(values, 1e-4, 355e-9))


@pytest.mark.parametrize("value", [0.0, 5e-324, 1e-300, 1e-101, NAN])
def test_flat_top_refuses_power_by_name(value):
    with pytest.raises(ValueError, match="^power = "):
        lo.FlatTopBeam(355e-9, 1e-3, 1e-3, grid=64, max_iterations=2, power=value)
