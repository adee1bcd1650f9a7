"""The empirical per-gate temperature model (Hervo et al. 2016): an exact log-linear law recovered
to rounding, the fit against numpy's own least squares, and bad input refused by name."""

import math

import numpy as np
import pytest

import lidar_overlap as lo

Z = np.linspace(100.0, 1000.0, 13)
REFERENCE = 1.0 - np.exp(-Z / 250.0)
#: Rounding of ln, exp and a 13-gate least squares in double precision.
ROUNDING = 1e-12


def _law(t, intercept, slope, center):
    """G(z, t) = G_ref(z) exp(a(z) + b(z) (t - center)), one row per temperature."""
    return REFERENCE * np.exp(intercept + np.outer(np.asarray(t) - center, slope))


def test_an_exact_log_linear_law_is_recovered_to_rounding():
    intercept = 0.02 * np.sin(Z / 200.0)
    slope = 4e-3 * np.exp(-Z / 300.0)  # 1/K: +0.05 in G over 10 K near 350 m, as measured
    t = np.array([275.0, 281.5, 290.0, 296.0, 304.5])
    g = _law(t, intercept, slope, t.mean())
    model = lo.empirical_drift(Z, g, t, REFERENCE)
    assert model.center == pytest.approx(t.mean(), rel=1e-15)
    np.testing.assert_allclose(model.intercept, intercept, rtol=0, atol=ROUNDING)
    np.testing.assert_allclose(model.slope, slope, rtol=0, atol=ROUNDING)
    assert np.all(model.slope_sigma < ROUNDING) and np.all(model.residual_rms < ROUNDING)
    np.testing.assert_allclose(model.predict(Z, t), g, rtol=ROUNDING, atol=0)
    assert model.coefficients == 2 * Z.size and model.n_curves == 5
    assert model.covariate_range == (275.0, 304.5)
    # a new temperature: the law itself (the straight line in ln G extrapolates exactly)
    np.testing.assert_allclose(
        model.predict(Z[3:7], [320.0]), _law([320.0], intercept, slope, t.mean())[:, 3:7], 1e-12
    )


def test_noisy_curves_match_numpys_least_squares_and_its_uncertainties():
    rng = np.random.default_rng(7)
    t = rng.uniform(275.0, 305.0, 40)
    g = _law(t, 0.0, 3e-3 * np.ones(Z.size), 290.0) * np.exp(rng.normal(0.0, 0.01, (40, Z.size)))
    model = lo.empirical_drift(Z, g, t, REFERENCE)
    y = np.log(g / REFERENCE)
    for j in (0, 6, 12):
        (b, a), cov = np.polyfit(t - t.mean(), y[:, j], 1, cov=True)
        assert model.slope[j] == pytest.approx(b, rel=1e-10)
        assert model.intercept[j] == pytest.approx(a, rel=1e-9, abs=1e-14)
        assert model.slope_sigma[j] == pytest.approx(math.sqrt(cov[0, 0]), rel=1e-9)
        assert model.intercept_sigma[j] == pytest.approx(math.sqrt(cov[1, 1]), rel=1e-9)
    pulls = (model.slope - 3e-3) / model.slope_sigma
    assert np.all(np.abs(pulls) < 4.0)  # 13 gates, 4 sigma: fails by chance with p ~ 1e-3


def test_predict_refuses_ranges_between_gates_and_bad_covariates():
    t = np.array([280.0, 290.0, 300.0])
    model = lo.empirical_drift(Z, _law(t, 0.0, 1e-3 * np.ones(Z.size), 290.0), t, REFERENCE)
    assert model.predict([Z[2]], 290.0).shape == (1, 1)
    with pytest.raises(ValueError, match=r"ranges\[1\] = 160.*not interpolated"):
        model.predict([Z[0], 160.0], [290.0])
    with pytest.raises(ValueError, match=r"ranges\[0\] = 2000"):
        model.predict([2000.0], [290.0])
    for bad in (math.nan, math.inf, "300"):
        with pytest.raises(ValueError, match="covariate"):
            model.predict(Z, [bad])


@pytest.mark.parametrize(
    "change, match",
    [
        (dict(covariate=[280.0, math.nan, 300.0]), r"covariate\[1\] = nan"),
        (dict(covariate=[280.0, 290.0]), "covariate has 2 values for 3 curves"),
        (dict(covariate=[290.0, 290.0, 290.0]), "all values are equal"),
        (dict(curves=np.ones((1, Z.size))), "1 curve"),
        (dict(curves=np.ones(Z.size)), "curves has shape"),
        (dict(curves=np.ones((3, Z.size - 1))), "curves has shape"),
        (dict(reference=np.ones(Z.size - 1)), "reference has 12 values for 13 ranges"),
        (dict(reference=np.r_[0.0, np.ones(Z.size - 1)]), r"reference\[0\] = 0.0 \(range 100 m\)"),
        (
            dict(curves=np.r_[np.ones((2, Z.size)), [np.r_[np.ones(5), -0.01, np.ones(7)]]]),
            r"curves\[2, 5\] = -0.01 \(range 475 m\)",
        ),
        (dict(ranges=Z[::-1]), "strictly increasing"),
        (dict(covariate=[280.0, 1e300, -1e300]), "covariate"),
    ],
)
def test_bad_input_is_refused_by_name(change, match):
    arguments = dict(
        ranges=Z, curves=np.ones((3, Z.size)), covariate=[280.0, 290.0, 300.0], reference=REFERENCE
    )
    arguments.update(change)
    with pytest.raises(ValueError, match=match):
        lo.empirical_drift(**arguments)


def test_a_prediction_that_overflows_is_refused_naming_the_covariate():
    z = np.array([100.0, 200.0, 300.0])
    t = np.array([270.0, 280.0, 290.0, 300.0])
    curves = np.exp(0.01 * np.outer(t - 285.0, [1.0, 2.0, 3.0])) * 0.5
    model = lo.empirical_drift(z, curves, t, np.full(3, 0.5))
    assert np.all(np.isfinite(model.predict(z, [250.0, 320.0])))
    with pytest.raises(
        lo.ParameterError, match=r"^covariate\[1\] = 1e\+300 is invalid: .*270 to 300"
    ):
        model.predict(z, [280.0, 1e300])
