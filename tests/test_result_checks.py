"""OverlapResult checks itself on construction (no NaN or out-of-range G can pass as a result;
round-off within the stated error is clipped into [0, 1]), and full_overlap_range warns when the
curve is still rising at the end of the ranges, by the rule its docstring states, checked here on
curves of known shape."""

import math
import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.forward.result import FAR_SLOPE, ROUND_OFF

Z = np.array([10.0, 20.0, 50.0, 100.0])


def _result(
    overlap,
    error=(0.0, 0.0, 0.0, 0.0),
    tolerance=1e-4,
    ranges=Z,
    method="rt",
    cls=lo.OverlapResult,
    **extra,
):
    return cls(
        ranges=ranges,
        overlap=overlap,
        method=method,
        error_estimate=error,
        system=None,
        tolerance=tolerance,
        **extra,
    )


@pytest.fixture
def no_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        yield


# ------------------------------------------------------------------------------------------
# construction
@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, 1.5, -0.2])
def test_a_value_outside_0_1_is_refused_naming_range_value_and_method(bad):
    with pytest.raises(ValueError) as info:
        _result([0.1, 0.5, bad, 0.9], method="fo")
    message = str(info.value)
    assert message.startswith(f"overlap[2] = {bad!r} at range 50.0 m (method 'fo') is invalid")
    assert "within [0, 1]" in message


def test_the_subclass_is_checked_too():
    with pytest.raises(ValueError, match=r"overlap\[0\] = nan"):
        _result([math.nan, 0.5, 0.8, 0.9], cls=lo.TurbulentOverlapResult)


@pytest.mark.parametrize(
    "error, tolerance",
    [
        ((0.0,) * 4, 1e-4),
        ((1e-3,) * 4, 1e-4),
        ((math.nan,) * 4, math.nan),
        ((1e-20,) * 4, 1e-20),
        ((1e300,) * 4, 1e300),  # a stated error widens nothing: round-off only
    ],
)
def test_round_off_is_clipped_and_beyond_it_refused_whatever_the_stated_error(error, tolerance):
    allowed = ROUND_OFF
    inside = _result([-0.5 * allowed, 0.5, 0.9, 1.0 + 0.5 * allowed], error, tolerance)
    assert inside.overlap.tolist() == [0.0, 0.5, 0.9, 1.0]
    for value in (-2.0 * allowed, 1.0 + 2.0 * allowed):
        with pytest.raises(ValueError, match=r"overlap\[3\]"):
            _result([0.1, 0.5, 0.9, value], error, tolerance)


def test_valid_values_are_kept_exactly():
    values = np.array([0.0, 0.123456789012345678, 0.999999999999, 1.0])
    res = _result(values)
    assert np.array_equal(res.overlap, values) and res.overlap.dtype == np.float64


@pytest.mark.parametrize(
    "change, words",
    [
        (dict(ranges=[10.0, 20.0, 50.0]), "overlap has 4 values for 3 ranges"),
        (dict(error=(0.0, 0.0)), "error_estimate has 2 values for 4 ranges"),
        (dict(ranges=np.array([]), overlap=[], error=[]), "ranges is empty"),
        (dict(overlap=[[0.1, 0.5, 0.9, 1.0]]), "overlap is invalid: expected a 1-D array"),
        (dict(overlap="0.5"), "overlap is invalid: expected a 1-D array"),
        (
            dict(ranges=[10.0, 20.0, 20.0, 100.0]),
            "strictly increasing: ranges[2] = 20.0 follows 20.0",
        ),
        (dict(ranges=[0.0, 20.0, 50.0, 100.0]), "ranges[0] = 0.0 is invalid"),
        (dict(ranges=[10.0, 20.0, 50.0, math.inf]), "ranges[3] = inf is invalid"),
        (dict(error=(0.0, -1e-6, 0.0, 0.0)), "error_estimate[1] = -1e-06 is invalid"),
        (dict(error=(0.0, 0.0, math.inf, 0.0)), "error_estimate[2] = inf is invalid"),
        (dict(tolerance=math.inf), "tolerance = inf is invalid"),
        (dict(tolerance=-1e-4), "tolerance = -0.0001 is invalid"),
        (dict(tolerance="1e-4"), "tolerance = '1e-4' is invalid"),
        (dict(method=None), "method = None is invalid"),
        (dict(method=""), "method = '' is invalid"),
    ],
)
def test_malformed_contents_are_refused(change, words):
    arguments = dict(overlap=[0.1, 0.5, 0.9, 1.0])
    arguments.update(change)
    with pytest.raises(ValueError) as info:
        _result(**arguments)
    assert words in str(info.value)


def test_missing_estimates_and_tolerance_are_allowed():
    res = _result([0.1, 0.5, 0.9, 1.0], error=(math.nan,) * 4, tolerance=math.nan)
    assert np.all(np.isnan(res.error_estimate)) and math.isnan(res.tolerance)


# ------------------------------------------------------------------------------ full_overlap_range
# warning
def _algebraic(limit, gap_at_last, z):
    """G(z) = limit (1 - a / z), a curve approaching its limit as 1/z (the slowest the rule
    assumes), with its relative gap at the last range given."""
    a = gap_at_last * z[-1]
    return limit * (1.0 - a / z)


Z_FAR = np.geomspace(50.0, 2000.0, 120)


def test_a_curve_still_rising_warns_and_says_what_to_do():
    g = 0.32 * Z_FAR / Z_FAR[-1]  # max 0.32, at the last range, rising steeply
    res = _result(g, error=np.zeros(Z_FAR.size), ranges=Z_FAR)
    with pytest.warns(RuntimeWarning, match="still rising at the end of the ranges") as caught:
        z = res.full_overlap_range()
    assert "extend the ranges" in str(caught[0].message) and "1000 m to 2000 m" in str(
        caught[0].message
    )
    assert z == res.ranges[np.argmax(g >= 0.99 * g.max())]  # still returned, by its definition


def test_the_threshold_of_the_rule():
    # the secant from z_last/2 to z_last of limit (1 - a/z) rises by limit a / z_last over log10(2)
    # decades
    slope_per_gap = 1.0 / math.log10(2.0)
    at_threshold = (
        FAR_SLOPE / slope_per_gap
    )  # the relative gap at which the slope is 1 % per decade
    below = _result(
        _algebraic(0.8, 0.9 * at_threshold, Z_FAR), error=np.zeros(Z_FAR.size), ranges=Z_FAR
    )
    above = _result(
        _algebraic(0.8, 1.1 * at_threshold, Z_FAR), error=np.zeros(Z_FAR.size), ranges=Z_FAR
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        below.full_overlap_range()
    with pytest.warns(RuntimeWarning, match="still rising"):
        above.full_overlap_range()
    # the docstring's bound: a curve that does not warn ends within 0.43 % of its limit
    assert (0.8 - below.overlap.max()) / 0.8 < 0.0043


def test_converged_peaked_and_dark_curves_do_not_warn(no_warnings):
    table1 = lo.overlap(lo.paper_table1(), np.geomspace(5.0, 1000.0, 200))
    assert table1.full_overlap_range() == pytest.approx(207.9, abs=0.5)
    defocused = lo.overlap(lo.paper_table1(defocus=8e-3), np.geomspace(5.0, 1e4, 200))
    assert np.argmax(defocused.overlap) < defocused.ranges.size - 1  # peaks, then falls
    assert np.isfinite(defocused.full_overlap_range())
    dark = _result([0.0, 0.0, 0.0, 0.0])
    assert math.isnan(dark.full_overlap_range())


def test_noise_within_the_error_estimates_does_not_warn():
    z = np.linspace(900.0, 1000.0, 20)  # a short grid: the secant spans 0.046 decade
    g = 0.99 + 5e-4 * (-1.0) ** np.arange(
        1, z.size + 1
    )  # ends 1e-3 above its start: 2 % per decade
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _result(g, error=np.full(z.size, 5e-4), ranges=z).full_overlap_range() == z[0]
    with pytest.warns(RuntimeWarning, match="still rising"):  # the same rise, stated as exact
        _result(g, error=np.zeros(z.size), ranges=z).full_overlap_range()


def test_reaches_far_range_says_whether_full_overlap_range_warns():
    rising = _result(0.32 * Z_FAR / Z_FAR[-1], error=np.zeros(Z_FAR.size), ranges=Z_FAR)
    settled = _result(_algebraic(0.8, 1e-4, Z_FAR), error=np.zeros(Z_FAR.size), ranges=Z_FAR)
    assert not rising.reaches_far_range() and settled.reaches_far_range()
    assert not _result([0.7], error=[0.0], ranges=[300.0]).reaches_far_range()
    assert _result([0.0, 0.0, 0.0, 0.0]).reaches_far_range()  # nothing rises


def test_a_single_range_warns():
    res = _result([0.7], error=[0.0], ranges=[300.0])
    with pytest.warns(RuntimeWarning, match="one range"):
        assert res.full_overlap_range() == 300.0


@pytest.mark.parametrize("threshold", [0.0, 1.0, -1e-3, 2.0, math.nan, True, "0.5"])
def test_first_signal_threshold_must_be_inside_0_1(threshold):
    res = _result([0.1, 0.5, 0.9, 1.0])
    with pytest.raises(ValueError, match="threshold"):
        res.first_signal_range(threshold)
