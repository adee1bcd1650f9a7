"""lo.fit_drift with a spline drift (drifting={path: "spline"}): a quadratic drift of the beam tilt
is fitted better by the spline than by a line (the chi-square drop exceeds the BIC's penalty for
the spline's extra coefficients) and the spline's drift curve meets the truth within its stated
uncertainty at the knots; a linear truth gives a spline that is linear within its uncertainty;
``drift`` is the mean slope over the span; prediction, systems and correction follow the spline,
which continues linearly outside the span (with a warning, as a line's); bad input is a clear error
naming it."""

import math
import warnings

import numpy as np
import pytest
from test_fit_drift import BASE, FAST, FREE, INTERVAL, SIGMA, SLOPE, START, TEMPERATURE, Z

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.model.instruments import chm15k

pytest.importorskip("scipy")

TILT = BASE["beam.tilt[0]"]  # rad, at the covariate's mean; SLOPE: rad/K
#: rad/K²: the tilt bends by 20 µrad at the span's ends (its departure from the chord at the
#: interior knots, 18 µrad, is ~ 20 sigma of the spline's fitted departures)
CURVATURE = 2e-7
SPLINE = {"beam.tilt[0]": "spline"}
#: |pull| bound for a single Gaussian quantity (p ~ 6e-5 two-sided).
PULL = 4.0
#: chi-square with 2 degrees of freedom exceeded with p = 0.001.
CHI2_2_P001 = 13.8


def _tilt(t, curvature):
    d = np.asarray(t, dtype=float) - TEMPERATURE.mean()
    return TILT + SLOPE * d + curvature * d**2


def _series(seed, curvature=CURVATURE, normalize=True):
    rng = np.random.default_rng(seed)
    rows = []
    for t in TEMPERATURE:
        system = parameters.replace(
            chm15k(), {"beam.tilt[0]": float(_tilt(t, curvature)), "detector.defocus": 0.0}
        )
        g = lo.overlap(system, Z, "rt", tolerance=1e-6).overlap
        if normalize:
            g = g / g[(Z >= INTERVAL[0]) & (Z <= INTERVAL[1])].mean()
        rows.append(g + rng.normal(0.0, SIGMA, Z.size))
    return np.array(rows)


def _drift(curves, drifting=SPLINE, normalize=INTERVAL, covariate=TEMPERATURE, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the straight line's poor fit of a bent drift
        return lo.fit_drift(
            START, Z, curves, covariate, sigma=SIGMA, free=FREE, drifting=drifting,
            normalize=normalize, **{**FAST, **options},
        )  # fmt: skip


@pytest.mark.parametrize("seed", [21, 22])
def test_a_quadratic_drift_is_fitted_better_by_a_spline_that_meets_the_truth_at_its_knots(seed):
    y = _series(seed)
    line = _drift(y, drifting=["beam.tilt[0]"])
    spline = _drift(y)
    assert spline.splines == ("beam.tilt[0]",) and spline.knots.size == 4
    # knots at the covariate's quantiles 0, 1/3, 2/3, 1
    assert spline.knots == pytest.approx(np.quantile(TEMPERATURE, [0, 1 / 3, 2 / 3, 1]))
    extra = len(spline.parameters) - len(line.parameters)
    assert extra == 2  # 4 knots: 2 coefficients beyond the line's
    n = spline.degrees_of_freedom + len(spline.parameters)
    assert line.chi_square - spline.chi_square > extra * math.log(n)
    value, sd = spline.drift_curve("beam.tilt[0]", spline.knots)
    pulls = (value - _tilt(spline.knots, CURVATURE)) / sd
    assert np.all(np.abs(pulls) < PULL), pulls
    # the mean slope over the span is the parabola's chord: SLOPE (the curvature is symmetric)
    slope, slope_sd = spline.drift["beam.tilt[0]"]
    assert abs(slope - SLOPE) < PULL * slope_sd


def test_a_linear_drift_gives_a_spline_that_is_linear_within_its_uncertainty():
    spline = _drift(_series(23, curvature=0.0))
    names = ["beam.tilt[0]@knot[1]", "beam.tilt[0]@knot[2]"]
    at = [list(spline.parameters).index(k) for k in names]
    g = np.array([spline.parameters[k] for k in names])
    # the departures from the chord are jointly zero: chi-square with 2 degrees of freedom
    assert g @ np.linalg.solve(spline.covariance[np.ix_(at, at)], g) < CHI2_2_P001
    slope, sd = spline.drift["beam.tilt[0]"]
    assert abs(slope - SLOPE) < PULL * sd
    assert "mean over the span" in spline.summary() and "µrad" in spline.summary()


def test_drift_is_the_mean_slope_and_the_spline_continues_linearly_outside_its_span():
    fit = _drift(_series(24))
    low, high = TEMPERATURE.min(), TEMPERATURE.max()
    value, _ = fit.drift_curve("beam.tilt[0]", [low, high])
    slope, sd = fit.drift["beam.tilt[0]"]
    assert slope == pytest.approx((value[1] - value[0]) / (high - low), rel=1e-10)
    # its uncertainty, from the covariance through the maps at the span's ends
    d = (fit.matrix(high) - fit.matrix(low))[FREE.index("beam.tilt[0]")] / (high - low)
    assert sd == pytest.approx(math.sqrt(d @ fit.covariance @ d), rel=1e-10)
    # the value at the reference covariate is the path's parameter
    at_ref, at_ref_sd = fit.drift_curve("beam.tilt[0]", fit.covariate_reference)
    assert at_ref[0] == pytest.approx(fit.parameters["beam.tilt[0]"], rel=1e-12)
    assert at_ref_sd[0] == pytest.approx(fit.uncertainties["beam.tilt[0]"], rel=1e-10)
    # a path that does not drift is constant
    still, _ = fit.drift_curve("detector.defocus", [low, high])
    assert still == pytest.approx(fit.parameters["detector.defocus"], rel=1e-12)
    # beyond the span: a straight line with the end's slope (natural spline: no curvature there)
    with pytest.warns(UserWarning, match=r"covariate = 320 K lies outside the fitted span \[290"):
        out, out_sd = fit.drift_curve("beam.tilt[0]", [high - 1e-3, high, high + 10, high + 20])
    end_slope = (out[1] - out[0]) / 1e-3
    assert (out[2] - out[1]) / 10 == pytest.approx(end_slope, rel=1e-4)
    assert out[3] - out[2] == pytest.approx(out[2] - out[1], rel=1e-10)
    assert out_sd[3] > out_sd[2] > out_sd[1]


def test_prediction_system_and_correction_follow_the_spline():
    fit = _drift(_series(25, normalize=False), normalize=None)
    at = fit.predict(Z, TEMPERATURE[[1, 5]])
    for row, i in zip(at, (1, 5)):  # absolute: each curve's fit is its system's G
        assert row == pytest.approx(fit.curves[i].predict(Z).overlap, abs=1e-9)
    t = 297.0
    tilt, _ = fit.drift_curve("beam.tilt[0]", t)
    assert parameters.get(fit.system_at(t), "beam.tilt[0]") == pytest.approx(tilt[0], rel=1e-12)
    signal = np.full(Z.size, 2.0)
    corrected = lo.correct(Z, signal, fit, covariate=t)
    g = fit.predict(Z, [t])[0]
    use = ~corrected.mask
    assert corrected.values[use] == pytest.approx(signal[use] / g[use], rel=1e-12)
    with pytest.warns(UserWarning, match="covariate = 280 K lies outside"):
        lo.correct(Z, signal, fit, covariate=280.0)
    with pytest.warns(UserWarning, match="covariate = 315 K lies outside"):
        fit.predict(Z, [300.0, 315.0])


def test_a_linear_drift_warns_outside_its_span_too():
    fit = _drift(_series(26, curvature=0.0), drifting=["beam.tilt[0]"])
    assert fit.splines == () and fit.knots.size == 0
    with pytest.warns(UserWarning, match=r"covariate = 340 K .* span \[290, 310\] K"):
        fit.predict(Z, [340.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # inside the span: no warning
        fit.predict(Z, [290.0, 310.0])


def _call(**changes):
    args = dict(curves=_series(27), covariate=TEMPERATURE, drifting=SPLINE)
    args.update(changes)
    return lambda: lo.fit_drift(
        START, Z, args.pop("curves"), args.pop("covariate"), sigma=SIGMA, free=FREE,
        normalize=INTERVAL, **args, **FAST,
    )  # fmt: skip


REPEATED = np.array([290.0] * 6 + [300.0, 310.0])


@pytest.mark.parametrize(
    "changes, message",
    [
        (dict(spline_knots=0), "spline_knots = 0 is invalid: expected an integer >= 3"),
        (dict(spline_knots=1), "spline_knots = 1 is invalid"),
        (dict(spline_knots=2), "spline_knots = 2 is invalid"),
        (dict(spline_knots=-4), "spline_knots = -4 is invalid"),
        (dict(spline_knots=math.nan), "spline_knots = nan is invalid: expected an integer"),
        (dict(spline_knots=4.0), "spline_knots = 4.0 is invalid: expected an integer"),
        (dict(spline_knots=True), "spline_knots = True is invalid"),
        (dict(spline_knots="4"), "spline_knots = '4' is invalid"),
        (dict(spline_knots=2**32), "spline_knots = 4294967296 is invalid: .* 8 distinct values"),
        (dict(spline_knots=9), "spline_knots = 9 is invalid: .* 8 distinct values"),
        (dict(covariate=REPEATED), "spline_knots = 4 is invalid: .* 3 distinct values"),
        (dict(covariate=REPEATED, spline_knots=3), "spline_knots = 3 is invalid: .* coincide"),
        # a list of paths is never a spline: its knots are still checked
        (dict(drifting=["beam.tilt[0]"], spline_knots=1), "spline_knots = 1"),
        (dict(drifting={"beam.tilt[0]": "cubic"}), r"drifting\['beam.tilt\[0\]'\] = 'cubic'"),
        (dict(drifting={"beam.tilt[0]": None}), r"drifting\['beam.tilt\[0\]'\] = None"),
        (dict(drifting={"beam.tilt[0]": 3}), r"drifting\['beam.tilt\[0\]'\] = 3"),
        (dict(drifting={3: "spline"}), "drifting key 3"),
        (dict(drifting={"beam.nothing": "spline"}), "drifting"),
        (dict(drifting={"detector.radius": "spline"}), "drifting: detector.radius is not free"),
        (dict(drifting={"beam.tilt": "linear", "beam.tilt[0]": "spline"}), "drifting names"),
    ],
)
def test_bad_input_is_a_clear_error_naming_it(changes, message):
    with pytest.raises(ValueError, match=message):
        _call(**changes)()


def test_drift_curve_refuses_bad_paths_and_covariates():
    fit = _drift(_series(28))
    with pytest.raises(ValueError, match="path = 'detector.radius' is invalid: expected a free"):
        fit.drift_curve("detector.radius", 300.0)
    with pytest.raises(ValueError, match=r"covariate\[1\] = nan"):
        fit.drift_curve("beam.tilt[0]", [300.0, math.nan])
    with pytest.raises(ValueError, match=r"covariate\[0\] = inf"):
        fit.drift_curve("beam.tilt[0]", math.inf)


def test_the_result_refuses_splines_and_knots_that_do_not_fit_its_parameters():
    import dataclasses

    fit = _drift(_series(29))
    with pytest.raises(ValueError, match="knots"):
        dataclasses.replace(fit, knots=fit.knots[::-1])
    with pytest.raises(ValueError, match="knots"):
        dataclasses.replace(fit, knots=np.empty(0))
    with pytest.raises(ValueError, match="splines"):
        dataclasses.replace(fit, splines=("detector.defocus",))
    with pytest.raises(ValueError, match="parameters"):  # one knot more: two departures short
        dataclasses.replace(fit, knots=np.linspace(290.0, 310.0, 6))


def test_the_spline_does_not_depend_on_the_covariates_offset_or_scale():
    # the covariate in another unit and origin (mK from 1e9 mK): the same curves, the same
    # chi-square, the slope and its uncertainty in the new unit
    y = _series(30)
    fit = _drift(y)
    moved = _drift(y, covariate=1e3 * TEMPERATURE + 1e9)
    assert moved.knots == pytest.approx(1e3 * fit.knots + 1e9, rel=1e-15)
    assert moved.chi_square == pytest.approx(fit.chi_square, rel=1e-9)
    slope, sd = fit.drift["beam.tilt[0]"]
    assert moved.drift["beam.tilt[0]"] == pytest.approx((1e-3 * slope, 1e-3 * sd), rel=1e-6)
    for name in ("beam.tilt[0]@knot[1]", "beam.tilt[0]@knot[2]"):  # departures: in rad, unmoved
        assert moved.parameters[name] == pytest.approx(fit.parameters[name], rel=1e-6)
