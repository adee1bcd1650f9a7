"""lo.fit_drift: a series with a known linear drift of the beam tilt against a covariate gives the
slope back within its stated uncertainty (pulls over seeds); drifting="auto" picks the drifting
parameter and not the fixed one, and a series without drift gets none; the prediction at a curve's
covariate is that curve's fit, its band grows away from the data; lo.correct takes the drift fit
with the day's covariate; bad input is a clear error naming it."""

import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.model.instruments import chm15k

pytest.importorskip("scipy")

FAST = dict(method="rt", tolerance=1e-4, threads=1)
Z = np.arange(10, 80, 5) * 14.985  # 150-1124 m, 14 gates
INTERVAL = (800.0, 1120.0)
TEMPERATURE = np.linspace(290.0, 310.0, 8)  # K
SIGMA = 0.004
FREE = ["beam.tilt[0]", "detector.defocus"]
BASE = {"beam.tilt[0]": 2e-5, "detector.defocus": 0.0}
#: The drift: -2 µrad/K (the tilt moves by 40 µrad over the series, a tenth of the field of view).
SLOPE = -2e-6
START = parameters.replace(chm15k(), {"beam.tilt[0]": 0.0, "detector.defocus": 1e-4})
SEEDS = (11, 12, 13)


def _series(seed, slope=SLOPE, normalize=True):
    rng = np.random.default_rng(seed)
    mean = TEMPERATURE.mean()
    rows = []
    for t in TEMPERATURE:
        tilt = BASE["beam.tilt[0]"] + slope * (t - mean)
        system = parameters.replace(chm15k(), {**BASE, "beam.tilt[0]": tilt})
        g = lo.overlap(system, Z, "rt", tolerance=1e-6).overlap
        if normalize:
            g = g / g[(Z >= INTERVAL[0]) & (Z <= INTERVAL[1])].mean()
        rows.append(g + rng.normal(0.0, SIGMA, Z.size))
    return np.array(rows)


def _drift(curves, drifting=("beam.tilt[0]",), **options):
    options = {"normalize": INTERVAL, "free": FREE, **FAST, **options}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.DegeneracyWarning)
        return lo.fit_drift(
            START, Z, curves, TEMPERATURE, sigma=SIGMA, drifting=list(drifting)
            if not isinstance(drifting, str) else drifting, **options,
        )  # fmt: skip


def test_the_drift_is_recovered_within_its_stated_uncertainty():
    pulls = []
    for seed in SEEDS:
        fit = _drift(_series(seed))
        slope, sd = fit.drift["beam.tilt[0]"]
        pulls.append((slope - SLOPE) / sd)
        # the intercept is the value at the covariate's mean
        assert fit.covariate_reference == pytest.approx(TEMPERATURE.mean())
        a = fit.parameters["beam.tilt[0]"]
        assert abs(a - BASE["beam.tilt[0]"]) < 4.0 * fit.uncertainties["beam.tilt[0]"]
    pulls = np.array(pulls)
    assert np.all(np.abs(pulls) < 4.0), pulls
    # three pulls of a unit normal: their RMS is below 2.5 with probability 0.9995
    assert np.sqrt(np.mean(pulls**2)) < 2.5, pulls


def test_auto_picks_the_drifting_parameter_and_a_series_without_drift_gets_none():
    """The tilt's drift is ~ 100 sigma: every seed picks it. A spurious drift is taken when its
    chi-square drop exceeds ln(n) + 2 (~ 6.7 here: p ~ 0.01 per candidate and round), so "most
    draws": at least 2 of the 3 seeds exactly right, with drift and without. Rate measured: 3 of 3
    in both (the tilt alone drifting; no drift in the series without one)."""
    picked = [_drift(_series(seed), drifting="auto") for seed in SEEDS]
    assert all("beam.tilt[0]" in f.drifting for f in picked), [f.choices for f in picked]
    assert sum(f.drifting == ("beam.tilt[0]",) for f in picked) >= 2, [f.choices for f in picked]
    still = [_drift(_series(seed, slope=0.0), drifting="auto") for seed in SEEDS]
    assert sum(f.drifting == () for f in still) >= 2, [f.choices for f in still]
    assert "no parameter drifts" in next(f for f in still if not f.drifting).summary()


def test_free_auto_chooses_the_family_on_the_median_curve_and_then_the_drift():
    # The model ladder on the median curve (its global searches cut to 4 generations of 6 and one
    # polished minimum: ~9 CPU s, the ladder's six families) chooses the free paths; the tilt is
    # among them (the family that moves the beam's axis), and the drift fit then finds its drift.
    fit = _drift(_series(11), drifting="auto", free="auto", generations=4, population=6, minima=1)
    assert fit.choices[0].startswith("free='auto': family '")
    assert "beam.tilt[0]" in fit.free and fit.drifting == ("beam.tilt[0]",), fit.choices
    slope, sd = fit.drift["beam.tilt[0]"]
    assert abs(slope - SLOPE) < 4.0 * sd
    assert fit.reduced_chi_square < 1.0 + 4.0 * np.sqrt(2.0 / fit.degrees_of_freedom)


def test_prediction_at_a_curves_covariate_is_that_curves_fit_and_its_band_grows_outside():
    fit = _drift(_series(14))
    at = fit.predict(Z, TEMPERATURE[[0, 6]])
    assert at.shape == (2, Z.size)
    for row, i in zip(at, (0, 6)):
        assert row == pytest.approx(fit.curves[i].fitted, abs=1e-9)
    with pytest.warns(UserWarning, match="covariate = 340 K lies outside the fitted span"):
        g, band = fit.predict(Z, [300.0, 340.0], band=True)
    near = Z < 600.0  # where the tilt matters
    assert np.all(band[1][near] > 2.0 * band[0][near])  # 2 spans out: the slope's share grows
    # the relative curve's normaliser is the data's: its mean over the interval is 1
    inside = (Z >= INTERVAL[0]) & (Z <= INTERVAL[1])
    assert g[:, inside].mean(axis=1) == pytest.approx(1.0, abs=1e-12)
    assert "µrad/K" in fit.summary()


def test_absolute_series_and_correction_at_the_days_covariate():
    fit = _drift(_series(15, normalize=False), normalize=None)
    assert abs(fit.drift["beam.tilt[0]"][0] - SLOPE) < 4.0 * fit.drift["beam.tilt[0]"][1]
    signal = np.full(Z.size, 2.0)
    corrected = lo.correct(Z, signal, fit, covariate=305.0)
    g = fit.predict(Z, [305.0])[0]
    use = ~corrected.mask
    assert corrected.values[use] == pytest.approx(signal[use] / g[use], rel=1e-12)
    with pytest.raises(ValueError, match="covariate is missing"):
        lo.correct(Z, signal, fit)
    with pytest.raises(ValueError, match="covariate"):
        lo.correct(Z, signal, fit.curves[0], covariate=305.0)


def _call(**changes):
    args = dict(system=START, ranges=Z, curves=_series(16), covariate=TEMPERATURE, sigma=SIGMA,
                free=FREE, drifting=["beam.tilt[0]"], normalize=INTERVAL)  # fmt: skip
    args.update(changes)
    return lambda: lo.fit_drift(
        args.pop("system"), args.pop("ranges"), args.pop("curves"), args.pop("covariate"), **args,
        **FAST,
    )  # fmt: skip


@pytest.mark.parametrize(
    "changes, name",
    [
        (dict(curves=[np.ones(Z.size), np.ones(Z.size - 1)]), "curves"),
        (dict(curves=_series(16)[:, :-1]), "curves has shape"),
        (dict(curves=_series(16)[:1], covariate=TEMPERATURE[:1]), "at least two"),
        (dict(covariate=np.where(TEMPERATURE > 300, np.nan, TEMPERATURE)), r"covariate\[4\]"),
        (dict(covariate=np.where(TEMPERATURE > 300, np.inf, TEMPERATURE)), r"covariate\[4\]"),
        (dict(covariate=TEMPERATURE[:-1]), "covariate has 7 values"),
        (dict(covariate=np.full(8, 300.0)), "covariate is constant"),
        (dict(covariate=np.repeat([-1e308, 1e308], 4)), "covariate spans"),
        (dict(covariate=TEMPERATURE * 1e-110), "covariate spans 2e-109: expected a spread from"),
        (dict(covariate=TEMPERATURE * 1e300), "covariate spans .*: expected a spread from"),
        (dict(drifting=["detector.radius"]), "drifting"),
        (dict(free=["beam.nothing"]), "free"),
        # a path the system does not have: its beam has no second component, its detector no NA
        (dict(free=["beam.components[1].weight"]), r"free: beam.components\[1\].weight does not"),
        (dict(free=FREE + ["detector.numerical_aperture"]), "free: detector.numerical_aperture"),
        (dict(curves=list(_series(16)[:, :5]) + [np.ones(4)] * 6), "curves"),
        (dict(sigma=None), "sigma"),
        (dict(sigma=np.nan), "sigma"),
        (dict(sigma=np.ones((3, 3))), "sigma"),
        (dict(normalize=[INTERVAL] * 8), "normalize"),
        (dict(curves=_series(16) * 1e300), "curves"),
        (dict(ranges=Z[::-1]), "ranges"),
        (dict(covariate_unit=3), "covariate_unit"),
    ],
)
def test_bad_input_is_a_clear_error_naming_it(changes, name):
    with pytest.raises(ValueError, match=name):
        _call(**changes)()


def test_the_slopes_uncertainty_follows_the_covariates_unit_over_its_whole_range():
    # The same series with the covariate in units 1e-12 to 1e10 times kelvin (seconds over years
    # put the slope column 1e9 above the others in SI units): the slope and its uncertainty scale
    # as 1 / unit, neither infinite (the covariance is taken in the solver's natural units).
    curves = _series(11)
    reference = _drift(curves).drift["beam.tilt[0]"]
    for unit in (1e-12, 1e8, 1e10):
        fit = _call(curves=curves, covariate=(TEMPERATURE - 300.0) * unit)()
        slope, sd = fit.drift["beam.tilt[0]"]
        assert slope * unit == pytest.approx(reference[0], rel=1e-6)
        assert sd * unit == pytest.approx(reference[1], rel=1e-6), unit


def test_prediction_refuses_bad_covariates():
    fit = _drift(_series(17))
    with pytest.raises(ValueError, match=r"covariate\[1\]"):
        fit.predict(Z, [300.0, np.nan])


def test_the_drift_parameters_names_have_one_home_and_keep_their_old_spellings():
    from lidar_overlap.analysis.fitting import drift_basis, drift_names, drift_reference

    # importable where they were defined before (drift_basis, drift_reference): the same objects
    assert drift_basis.SLOPE is drift_names.SLOPE and drift_basis.knot_name is drift_names.knot_name
    assert drift_reference.REFERENCE is drift_names.REFERENCE
    assert drift_reference.OFFSET is drift_names.OFFSET
    # the spellings a result's parameters are indexed by (docs/series.md)
    spelled = (drift_names.SLOPE, drift_names.REFERENCE, drift_names.OFFSET)
    assert spelled == ("@slope", "covariate@reference", "@reference_offset")
    assert drift_names.knot_name("beam.tilt[0]", 2) == "beam.tilt[0]@knot[2]"
