"""OverlapResult: contents, the derived ranges checked against their definitions on the returned
curve, the cases where they do not exist (NaN), threshold validation, and the matplotlib plot."""

import dataclasses

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import lidar_overlap as lo  # noqa: E402

THIN = dict(
    waist_radius=1e-9, divergence=1e-12, width_law="linear"
)  # a geometric pencil beam (M^2 < 1 needs the linear law)
RANGES = np.geomspace(1.0, 1e4, 300)


@pytest.fixture(scope="module")
def results():
    tilted = lo.paper_table1()
    tilted = dataclasses.replace(
        tilted, beam=dataclasses.replace(tilted.beam, offset=(0.1, 0.0), tilt=(-0.4e-3, 0.0))
    )
    return {
        "table1": lo.overlap(lo.paper_table1(), RANGES),
        "obstructed": lo.overlap(lo.paper_table1(obstruction_radius=0.04), RANGES),
        "defocused": lo.overlap(lo.paper_table1(defocus=8e-3), RANGES),
        "biaxial": lo.overlap(tilted, RANGES),
    }


@pytest.fixture(scope="module")
def dark():
    """A curve that is zero everywhere: thin on-axis beam, ranges before the obstruction onset (45.1
    m)."""
    return lo.overlap(lo.paper_table1(obstruction_radius=0.02, **THIN), np.linspace(1.0, 40.0, 50))


def _index(res, z):
    hits = np.flatnonzero(res.ranges == z)
    assert hits.size == 1, f"{z} is not a grid range"
    return int(hits[0])


def test_contents():
    system = lo.paper_table1()
    z = [5.0, 50.0, 500.0]
    res = lo.overlap(system, z, tolerance=1e-6)
    assert isinstance(res, lo.OverlapResult)
    assert res.method == "rt"
    assert res.system is system
    assert res.tolerance == 1e-6
    np.testing.assert_array_equal(res.ranges, z)
    assert res.overlap.shape == res.error_estimate.shape == (3,)
    assert np.all((res.overlap >= 0) & (res.overlap <= 1))
    assert np.all(res.error_estimate >= 0)


@pytest.mark.parametrize("case", ["table1", "obstructed", "defocused", "biaxial"])
@pytest.mark.parametrize("threshold", [0.5, 0.9, 0.99, 0.999])
def test_full_overlap_range_definition(results, case, threshold):
    res = results[case]
    z = res.full_overlap_range(threshold)
    i = _index(res, z)
    level = threshold * res.overlap.max()
    assert res.overlap[i] >= level
    assert np.all(res.overlap[:i] < level)


def test_full_overlap_range_default_and_obstructed(results):
    res = results["table1"]
    assert res.full_overlap_range() == res.full_overlap_range(0.99)
    # relative to the maximum: an obstructed system whose G never reaches 0.99 still has one
    blocked = results["obstructed"]
    assert blocked.overlap.max() < 0.99
    assert np.isfinite(blocked.full_overlap_range())
    # and a higher threshold never gives a shorter range
    values = [res.full_overlap_range(t) for t in (0.1, 0.5, 0.9, 0.99, 0.999)]
    assert values == sorted(values)


def test_full_overlap_range_threshold_one_is_first_maximum(results):
    res = results["defocused"]
    z = res.full_overlap_range(1.0)
    assert z == res.ranges[np.argmax(res.overlap)]


@pytest.mark.parametrize("case", ["table1", "obstructed", "defocused", "biaxial"])
@pytest.mark.parametrize("threshold", [1e-6, 1e-3, 0.1, 0.5])
def test_first_signal_range_definition(results, case, threshold):
    res = results[case]
    z = res.first_signal_range(threshold)
    i = _index(res, z)
    assert res.overlap[i] >= threshold
    assert np.all(res.overlap[:i] < threshold)


def test_first_signal_range_is_absolute(results):
    # 0.8 is reached by the clear system but never by one that loses (40/75)^2 = 28 % to the
    # obstruction
    assert np.isfinite(results["table1"].first_signal_range(0.8))
    assert np.isnan(results["obstructed"].first_signal_range(0.8))
    assert results["table1"].first_signal_range() == results["table1"].first_signal_range(1e-3)


def test_nan_when_there_is_no_signal(dark):
    assert np.all(dark.overlap == 0.0)
    assert np.isnan(dark.full_overlap_range())
    assert np.isnan(dark.full_overlap_range(0.5))
    assert np.isnan(dark.first_signal_range())
    assert np.isnan(dark.first_signal_range(1e-9))


@pytest.mark.parametrize("threshold", [0.0, -0.5, 1.5, float("nan")])
def test_bad_thresholds(results, threshold):
    res = results["table1"]
    with pytest.raises(ValueError, match="threshold"):
        res.full_overlap_range(threshold)
    with pytest.raises(ValueError, match="threshold"):
        res.first_signal_range(threshold)


def test_first_signal_threshold_one_is_rejected(results):
    with pytest.raises(ValueError, match="threshold"):
        results["table1"].first_signal_range(1.0)


def _vertical_lines(ax):
    xs = []
    for line in ax.get_lines():
        x = np.asarray(line.get_xdata(), dtype=float)
        if x.size == 2 and x[0] == x[1]:
            xs.append(float(x[0]))
    return xs


def test_plot_returns_axes_with_the_curve(results):
    res = results["obstructed"]
    ax = res.plot()
    try:
        assert isinstance(ax, matplotlib.axes.Axes)
        curves = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == res.ranges.size]
        assert len(curves) == 1
        np.testing.assert_array_equal(curves[0].get_xdata(), res.ranges)
        np.testing.assert_array_equal(curves[0].get_ydata(), res.overlap)
        assert ax.get_xscale() == "log"
        marks = _vertical_lines(ax)
        assert any(x == pytest.approx(res.full_overlap_range(), rel=1e-12) for x in marks)
        assert any(x == pytest.approx(res.first_signal_range(), rel=1e-12) for x in marks)
    finally:
        plt.close(ax.figure)


def test_plot_onto_given_axes(results):
    fig, ax = plt.subplots()
    try:
        out_a = results["table1"].plot(ax=ax)
        out_b = results["obstructed"].plot(ax=ax)
        assert out_a is ax and out_b is ax
        ys = [
            np.asarray(ln.get_ydata())
            for ln in ax.get_lines()
            if len(ln.get_ydata()) == RANGES.size
        ]
        assert any(np.array_equal(y, results["table1"].overlap) for y in ys)
        assert any(np.array_equal(y, results["obstructed"].overlap) for y in ys)
    finally:
        plt.close(fig)


def test_plot_without_signal_draws_no_marks(dark):
    ax = dark.plot()
    try:
        assert _vertical_lines(ax) == []
        np.testing.assert_array_equal(ax.get_lines()[0].get_ydata(), dark.overlap)
    finally:
        plt.close(ax.figure)


# --------------------------------------------------------------------------------- equality and
# error kinds
def test_equal_results_compare_equal_and_differing_ones_do_not(results):
    res = results["table1"]
    again = lo.overlap(res.system, res.ranges, "rt", tolerance=res.tolerance)
    assert res == again and not (res != again)
    assert res != dataclasses.replace(res, overlap=np.nextafter(res.overlap, 0.0))
    assert res != dataclasses.replace(res, error_kind="nominal")
    assert res != dataclasses.replace(res, system=lo.paper_table1(defocus=1e-3))
    assert (res == "rt") is False
    with pytest.raises(TypeError):
        hash(res)


def test_results_with_nan_tolerance_equal_themselves_and_allclose_compares_curves():
    z = np.geomspace(50.0, 2000.0, 6)
    fo, rt = (
        lo.overlap(lo.paper_table1(), z, "fo"),
        lo.overlap(lo.paper_table1(), z, "rt", tolerance=1e-6),
    )
    assert np.isnan(fo.tolerance) and fo == lo.overlap(lo.paper_table1(), z, "fo")
    gap = float(np.max(np.abs(fo.overlap - rt.overlap)))
    assert fo != rt and fo.allclose(rt, atol=gap) and not fo.allclose(rt, atol=0.5 * gap)
    assert not fo.allclose(lo.overlap(lo.paper_table1(), z[:-1], "fo"), atol=1.0)  # other ranges


@pytest.mark.parametrize(
    "other, atol, message",
    [
        ("rt", 0.0, "^other = 'rt' is invalid"),
        (None, -1.0, "^atol = -1.0 is invalid"),
        (None, float("nan"), "^atol = nan is invalid"),
    ],
)
def test_allclose_refuses_bad_arguments_by_name(results, other, atol, message):
    res = results["table1"]
    with pytest.raises(ValueError, match=message):
        res.allclose(res if other is None else other, atol=atol)


def test_error_kind_is_checked_and_survives_files(results, tmp_path):
    res = results["table1"]
    assert res.error_kind == "bound"
    with pytest.raises(ValueError, match="^error_kind = 'exact' is invalid"):
        dataclasses.replace(res, error_kind="exact")
    fo = lo.overlap(res.system, res.ranges, "fo")
    fo.to_csv(tmp_path / "fo.csv")
    assert lo.OverlapResult.from_csv(tmp_path / "fo.csv") == fo
