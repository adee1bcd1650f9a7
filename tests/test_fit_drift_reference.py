"""lo.fit_drift(..., reference=): the differential anchor. Days made by the model at a known linear
drift of the beam tilt plus a structure the model cannot shape (a bump), the reference made by the
model at a known covariate plus the same bump: the reference's covariate and the drift are recovered
within their stated uncertainties (pulls over seeds), the prediction at the reference's covariate is
the reference itself, the predictions equal the model's within their band, an offset at the
reference is recovered, lo.correct takes the fit; bad input is a clear error naming it."""

import warnings

import numpy as np
import pytest
from test_fit_drift import BASE, FAST, FREE, INTERVAL, SIGMA, SLOPE, START, TEMPERATURE, Z

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.model.instruments import chm15k

pytest.importorskip("scipy")

#: The reference's covariate (K): below the series' 290-310 K, an extrapolation of the drift line.
C_REF = 285.0
#: A bump of 0.03 at 400 m: structure the family cannot shape, the same in every curve.
BUMP = 0.03 * np.exp(-0.5 * ((Z - 400.0) / 60.0) ** 2)
SEEDS = (21, 22, 23)
INSIDE = (Z >= INTERVAL[0]) & (Z <= INTERVAL[1])


def _model(c, defocus=0.0):
    """The model's normalised curve at covariate ``c`` (K) plus the bump (defocus: an offset, m)."""
    tilt = BASE["beam.tilt[0]"] + SLOPE * (c - TEMPERATURE.mean())
    values = {**BASE, "beam.tilt[0]": tilt, "detector.defocus": BASE["detector.defocus"] + defocus}
    g = lo.overlap(parameters.replace(chm15k(), values), Z, "rt", tolerance=1e-6).overlap
    return g / g[INSIDE].mean() + BUMP


def _days(seed):
    rng = np.random.default_rng(seed)
    return np.array([_model(c) + rng.normal(0.0, SIGMA, Z.size) for c in TEMPERATURE])


def _fit(curves, reference, **options):
    options = {"normalize": INTERVAL, "free": FREE, "drifting": ["beam.tilt[0]"], **FAST, **options}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.DegeneracyWarning)
        return lo.fit_drift(START, Z, curves, TEMPERATURE, sigma=SIGMA, reference=reference,
                            **options)  # fmt: skip


def test_the_references_covariate_and_the_drift_are_recovered_within_their_uncertainty():
    pulls = []
    for seed in SEEDS:
        fit = _fit(_days(seed), _model(C_REF))
        c_ref, sd = fit.reference_covariate
        slope, slope_sd = fit.drift["beam.tilt[0]"]
        pulls += [(c_ref - C_REF) / sd, (slope - SLOPE) / slope_sd]
        # the free values, the slope and c_ref: every number the prediction needs
        assert fit.coefficients == len(FREE) + 2 == len(fit.parameters)
    pulls = np.array(pulls)
    assert np.all(np.abs(pulls) < 4.0), pulls
    # six pulls of a unit normal: their RMS is below 2 with probability 0.9998
    assert np.sqrt(np.mean(pulls**2)) < 2.0, pulls


def test_the_prediction_is_the_reference_at_its_covariate_and_the_model_elsewhere():
    reference = _model(C_REF)
    fit = _fit(_days(24), reference)
    c_ref = fit.reference_covariate[0]
    # at c_ref the differential model is the reference itself (normalised like the days), exactly;
    # c_ref (285 K) lies below the days' span, so the prediction says it extrapolates
    with pytest.warns(UserWarning, match="outside the fitted span"):
        at = fit.predict(Z, [c_ref])[0]
    assert at == pytest.approx(reference / reference[INSIDE].mean(), abs=1e-12)
    # at the days' covariates: the truth (model and bump) within 4 sigma of the band (+ the model's
    # tolerance); the unanchored fit, which the bump bends, misses it by several times more (RMS
    # error measured: 0.0050 against 0.00067)
    g, band = fit.predict(Z, TEMPERATURE, band=True)
    truth = np.array([_model(c) for c in TEMPERATURE])
    assert np.all(np.abs(g - truth) < 4.0 * band + 1e-3), np.abs(g - truth).max()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.FitQualityWarning)  # the bump: chi²/dof ~ 2.6
        plain = _fit(_days(24), None)
    rms = [np.sqrt(np.mean((p - truth) ** 2)) for p in (plain.predict(Z, TEMPERATURE), g)]
    assert rms[0] > 4.0 * rms[1], rms
    # the reference given at the fitted ranges is the stored one: the same prediction
    assert fit.predict(Z, TEMPERATURE, reference=reference) == pytest.approx(g, abs=1e-15)
    assert "reference on the drift line at" in fit.summary()


def test_an_offset_at_the_reference_is_recovered():
    # the reference's detector defocused by 0.3 mm beyond the drift line's state (a bench's focus)
    fit = _fit(_days(25), _model(C_REF, defocus=3e-4), reference_offsets=["detector.defocus"])
    offset, sd = (
        fit.parameters["detector.defocus@reference_offset"],
        fit.uncertainties["detector.defocus@reference_offset"],
    )
    assert abs(offset - 3e-4) < 4.0 * sd, (offset, sd)
    assert fit.reference_offsets == ("detector.defocus",) and fit.coefficients == len(FREE) + 3


def test_correction_with_a_referenced_drift_fit_follows_its_prediction():
    fit = _fit(_days(26), _model(C_REF))
    signal = np.full(Z.size, 2.0)
    corrected = lo.correct(Z, signal, fit, covariate=305.0)
    g = fit.predict(Z, [305.0])[0]
    use = ~corrected.mask
    # the correction's curve is the prediction on the far-range scale: signal / G ∝ 1 / prediction
    ratio = corrected.values[use] * g[use]
    assert ratio == pytest.approx(np.full(ratio.size, ratio[0]), rel=1e-9)


def _call(**changes):
    args = dict(curves=_days(27), reference=_model(C_REF))
    args.update(changes)
    return lambda: _fit(**args)


@pytest.mark.parametrize(
    "changes, name",
    [
        (dict(reference=np.ones(Z.size - 1)), "reference has 13 values"),
        (dict(reference=np.where(Z > 500, np.nan, 1.0)), r"reference\[5\]"),
        (dict(reference=np.where(Z > 500, np.inf, 1.0)), r"reference\[5\]"),
        (dict(reference=np.ones((2, Z.size))), "reference"),
        (dict(reference="factory"), "reference"),
        (dict(reference=np.zeros(Z.size)), "reference: normalize"),
        (dict(reference=-np.ones(Z.size)), "reference: normalize"),
        (dict(reference=np.full(Z.size, 1e-300)), "reference: .*overflow"),
        (dict(extinction_bias=True), "reference with extinction_bias"),
        (dict(search="global"), "search"),
        (dict(reference=None, reference_offsets=["detector.defocus"]), "reference_offsets"),
        (dict(reference_offsets=["detector.radius"]), "reference_offsets: detector.radius"),
        (dict(reference_offsets=["beam.nothing"]), "reference_offsets"),
        (dict(drifting={"beam.tilt[0]": "spline"}), "beam.tilt.0. as a spline with a reference"),
    ],
)
def test_bad_reference_is_a_clear_error_naming_it(changes, name):
    with pytest.raises(ValueError, match=name):
        _call(**changes)()


def test_predict_refuses_a_reference_it_cannot_use():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.FitQualityWarning)  # the bump, unanchored
        fit = _fit(_days(28), None)
    with pytest.raises(ValueError, match="no reference"):
        fit.predict(Z, [300.0], reference=np.ones(Z.size))
    anchored = _fit(_days(28), _model(C_REF))
    with pytest.raises(ValueError, match="reference has 3 values"):
        anchored.predict(Z, [300.0], reference=np.ones(3))
