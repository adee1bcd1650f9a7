"""The range-resolved noise estimate (lidar_overlap.io.noise_profile) against synthetic curves of a
known heteroscedastic noise sigma(r) = a (r / r0)^p, its exact invariances, and hostile input."""

import dataclasses
import math

import numpy as np
import pytest

from lidar_overlap.io.noise_profile import NoiseProfile, noise_profile
from lidar_overlap.io.overlap_curves import far_range_noise

#: A far interval as the PollyXT's (7.5 m bins, 500-3000 m: 334 points, 4 windows of 83).
Z = np.arange(500.0, 3000.0, 7.5)
INTERVAL = (500.0, 3000.0)
R0, LEVEL = 1500.0, 0.01
SEEDS = range(20)
#: Over 400 seeds (4 windows), for p = 0, 1, 1.5 and 2: the exponent p + 0.006 to 0.037 ± 0.16
#: (largest deviation 0.48), sigma(R0) / LEVEL 0.967 to 0.986 ± 0.07 (largest deviation 0.22): each
#: window's MAD estimate scatters by 14 %. Each draw must fall within 3.7 (exponent) and 3.8 (level)
#: of those standard deviations, the mean of 20 draws within 0.13 and 0.06 of the truth (3.6
#: standard errors, less the level's bias of up to 0.033).
EXPONENT_EACH, LEVEL_EACH = 0.6, 0.27
EXPONENT_MEAN, LEVEL_MEAN = 0.13, 0.06


def curve(exponent: float, seed: int, z: np.ndarray = Z) -> np.ndarray:
    """A flat far range with the last approach to 1 and noise LEVEL (z / R0)^exponent."""
    rng = np.random.default_rng(seed)
    sigma = LEVEL * (z / R0) ** exponent
    return 1.0 - 0.05 * np.exp(-z / 800.0) + sigma * rng.normal(0.0, 1.0, z.size)


@pytest.mark.parametrize("exponent", [0.0, 1.0, 1.5, 2.0])
def test_a_known_power_law_is_recovered_over_seeds(exponent):
    exponents, levels = [], []
    for seed in SEEDS:
        p = noise_profile(Z, curve(exponent, seed), INTERVAL)
        exponents.append(p.exponent)
        levels.append(float(p(R0)) / LEVEL)
    assert np.all(np.abs(np.array(exponents) - exponent) < EXPONENT_EACH), exponents
    assert np.all(np.abs(np.array(levels) - 1.0) < LEVEL_EACH), levels
    assert abs(np.mean(exponents) - exponent) < EXPONENT_MEAN
    assert abs(np.mean(levels) - 1.0) < LEVEL_MEAN


def test_the_profile_is_the_power_law_through_its_windows():
    p = noise_profile(Z, curve(1.5, 3), INTERVAL, windows=5)
    assert p.window_ranges.size == p.window_sigmas.size == 5
    assert np.all(np.diff(p.window_ranges) > 0)
    assert INTERVAL[0] < p.window_ranges[0] and p.window_ranges[-1] < INTERVAL[1]
    # windows of 67 and 66 points: nearly equal weights, so nearly the plain line through them
    x, y = np.log(p.window_ranges), np.log(p.window_sigmas)
    slope, intercept = np.polyfit(x, y, 1)
    assert p.exponent == pytest.approx(slope, rel=0.02)
    assert float(p(p.reference_range)) == pytest.approx(
        math.exp(intercept) * p.reference_range**slope, rel=0.02
    )
    assert p.reference_range == pytest.approx(math.exp(np.mean(x)), rel=0.01)
    assert p.single == far_range_noise(Z, curve(1.5, 3), INTERVAL)
    z = np.array([100.0, 700.0, 2000.0, 5000.0])
    assert p(z) == pytest.approx(p.amplitude * (z / p.reference_range) ** p.exponent, rel=1e-12)
    held = p(z, below="hold")
    assert held[0] == pytest.approx(float(p(INTERVAL[0])), rel=1e-12)
    assert held[1:] == pytest.approx(p(z[1:]), rel=1e-12)
    assert p(np.array([[700.0], [2000.0]])).shape == (2, 1)


def test_the_power_law_is_the_count_weighted_least_squares_line():
    """The fit against the normal equations of least squares on ln sigma against ln r, each
    window weighted by its points (windows of 84, 84, 83 and 83 points here), to 1e-12."""
    p = noise_profile(Z, curve(1.5, 7), INTERVAL)
    counts = [part.size for part in np.array_split(np.arange(Z.size), 4)]  # all within INTERVAL
    assert len(set(counts)) == 2
    x, y, w = np.log(p.window_ranges), np.log(p.window_sigmas), np.array(counts, dtype=float)
    x_ref = np.sum(w * x) / np.sum(w)
    slope = np.sum(w * (x - x_ref) * (y - np.sum(w * y) / np.sum(w))) / np.sum(w * (x - x_ref) ** 2)
    assert p.exponent == pytest.approx(slope, rel=1e-12)
    assert p.reference_range == pytest.approx(math.exp(x_ref), rel=1e-12)
    assert p.amplitude == pytest.approx(math.exp(np.sum(w * y) / np.sum(w)), rel=1e-12)


def test_scaled_curves_scale_the_profile_exactly():
    g = curve(1.5, 5)
    p = noise_profile(Z, g, INTERVAL)
    for factor in (2.0**-990, 2.0**990):  # 1e-298, 1e298: tiny and huge overlaps
        q = noise_profile(Z, g * factor, INTERVAL)
        assert q.exponent == pytest.approx(p.exponent, rel=1e-9)
        assert q.amplitude == pytest.approx(p.amplitude * factor, rel=1e-9)
    far = 2.0**900  # ranges near 1e271 m: the exponent and the shape do not depend on the unit
    q = noise_profile(Z * far, g, (INTERVAL[0] * far, INTERVAL[1] * far))
    assert q.exponent == pytest.approx(p.exponent, rel=1e-9)
    assert q.reference_range == pytest.approx(p.reference_range * far, rel=1e-9)
    assert q(1600.0 * far) == pytest.approx(p(1600.0), rel=1e-9)


@pytest.mark.parametrize(
    "change, message",
    [
        (dict(overlap_nan=True), r"^overlap\[3\] = nan is invalid"),
        (dict(overlap=np.ones(Z.size)), "no scatter"),
        (dict(interval=(3000.0, 500.0)), "expected low < high"),
        (dict(interval=(0.0, 3000.0)), r"^interval = \(0, 3000\) m is invalid: expected z_low > 0"),
        (dict(interval=(500.0, 560.0)), "holds 9 points"),
        (dict(windows=1), r"^windows = 1 is invalid: expected an integer from 2"),
        (dict(windows=0), r"^windows = 0 is invalid"),
        (dict(windows=True), r"^windows = True is invalid"),
        (dict(windows=2.5), r"^windows = 2.5 is invalid"),
        (dict(windows="4"), r"^windows = '4' is invalid"),
        (dict(windows=2**32), r"^windows = 4294967296 is invalid"),
        (dict(windows=34), r"^windows = 34 is invalid .* 9 per window; .*at most 33 windows"),
        (dict(ranges=Z[::-1].copy()), r"^ranges must be strictly increasing"),
    ],
)
def test_bad_input_is_refused_naming_the_parameter(change, message):
    g = curve(1.5, 1)
    if change.pop("overlap_nan", False):
        g[3] = math.nan
    args = dict(ranges=Z, overlap=g, interval=INTERVAL, windows=4) | change
    with pytest.raises(ValueError, match=message):
        noise_profile(**args)


def test_a_window_without_scatter_is_named():
    g = curve(1.5, 2)
    g[Z < 1100.0] = 1.0  # clipped at the start of the interval: the first of 4 windows is constant
    with pytest.raises(
        ValueError, match=r"^windows = 4: window 0 \(500 to 1122.5 m\) has no scatter"
    ):
        noise_profile(Z, g, INTERVAL)
    assert noise_profile(Z, g, (1100.0, 3000.0)).exponent > 0  # the measured part is usable


@pytest.mark.parametrize(
    "ranges, below, message",
    [
        ([100.0, math.nan], "extrapolate", r"^ranges\[1\] = nan is invalid: expected finite"),
        ([math.inf], "extrapolate", r"^ranges\[0\] = inf is invalid"),
        ([0.0], "hold", r"^ranges\[0\] = 0.0 is invalid: .* > 0 m"),
        ([-1.0], "extrapolate", r"^ranges\[0\] = -1.0 is invalid"),
        (["700"], "extrapolate", "^ranges"),
        ([700.0], "clamp", r"^below = 'clamp' is invalid"),
    ],
)
def test_evaluation_refuses_bad_ranges_and_modes(ranges, below, message):
    p = noise_profile(Z, curve(1.5, 1), INTERVAL)
    with pytest.raises(ValueError, match=message):
        p(ranges, below=below)


def test_a_profile_is_a_checked_value():
    p = noise_profile(Z, curve(1.5, 1), INTERVAL)
    assert p == noise_profile(Z, curve(1.5, 1), INTERVAL) and p != noise_profile(
        Z, curve(1.5, 2), INTERVAL
    )
    with pytest.raises(ValueError, match="read-only"):
        p.window_sigmas[0] = 1.0
    for field, value, message in [
        ("amplitude", 0.0, "^amplitude = 0.0 is invalid"),
        ("exponent", math.nan, "^exponent = nan is invalid"),
        ("reference_range", 1e400, "^reference_range = inf is invalid"),
        ("interval", (3.0, 1.0), r"^interval = \(3.0, 1.0\) is invalid"),
        ("window_sigmas", [0.1], "^window_sigmas"),
        ("window_ranges", [1.0, math.inf, 2.0, 3.0], r"^window_ranges\[1\] = inf"),
        ("single", -1.0, "^single = -1.0 is invalid"),
    ]:
        with pytest.raises(ValueError, match=message):
            dataclasses.replace(p, **{field: value})
    assert isinstance(p, NoiseProfile)
