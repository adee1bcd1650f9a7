"""lo.fit: known parameters recovered from noisy synthetic curves within their stated uncertainties
(and the 1-sigma coverage over 100 noise draws), the Jacobian covariance against a bootstrap,
degeneracy warned, the near-range extrapolation band, robust loss against outliers, hostile inputs
and non-convergence."""

import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters

pytest.importorskip("scipy")

#: Model tolerance well below the noise (0.1 sigma and less); one thread: the curves are short, and
#: OpenMP over a dozen ranges costs more than it gains on a shared machine.
TOL, FAST = 1e-5, dict(method="rt", tolerance=1e-5, threads=1)
SIGMA = 0.01
#: The truth is computed 100x tighter than the fits' model.
TRUTH_TOL = 1e-7
TABLE1 = lo.paper_table1()
TRUE = {"beam.tilt[0]": 3e-4, "detector.defocus": 2e-3}
START = {
    "beam.tilt[0]": 2e-4,
    "detector.defocus": 1e-3,
}  # off 0: G is even in the tilt of a coaxial lidar
Z = np.geomspace(30.0, 2000.0, 12)
#: Binomial tolerance for the 1-sigma coverage over N_DRAWS draws: 0.683 ± 2.8 standard deviations
#: (0.047).
N_DRAWS, COVERAGE = 100, (0.55, 0.80)
BIAXIAL = lo.LidarSystem(
    beam=lo.GaussianBeam(
        wavelength=355e-9, waist_radius=1e-3, offset=(0.15, 0.0), tilt=(-1e-4, 0.0)
    ),
    telescope=TABLE1.telescope,
    detector=TABLE1.detector,
)


def _curve(system, values, z):
    return lo.overlap(parameters.replace(system, values), z, "rt", tolerance=TRUTH_TOL).overlap


def _noisy(g, rng, sigma=SIGMA):
    return g + rng.normal(0.0, sigma, g.size)


def test_coverage_of_the_stated_uncertainties_over_100_draws():
    g, start, rng = (
        _curve(TABLE1, TRUE, Z),
        parameters.replace(TABLE1, START),
        np.random.default_rng(1),
    )
    inside = np.zeros(len(TRUE))
    for _ in range(N_DRAWS):
        f = lo.fit(start, Z, _noisy(g, rng), sigma=SIGMA, free=list(TRUE), **FAST)
        inside += [abs(f.parameters[p] - v) <= f.uncertainties[p] for p, v in TRUE.items()]
    fraction = inside / N_DRAWS
    print(f"1-sigma coverage over {N_DRAWS} draws: {dict(zip(TRUE, fraction))}")
    assert np.all((COVERAGE[0] <= fraction) & (fraction <= COVERAGE[1])), fraction


@pytest.mark.parametrize(
    "system, truth, start, z",
    [
        (
            TABLE1,
            {"beam.tilt[1]": -2.5e-4, "detector.defocus": 3e-3},
            {"beam.tilt[1]": -1.5e-4, "detector.defocus": 1e-3},
            Z,
        ),
        (
            BIAXIAL,
            {"detector.offset[1]": 1e-4, "detector.defocus": 1.5e-3},
            {"detector.offset[1]": 0.5e-4, "detector.defocus": 0.5e-3},
            np.geomspace(80.0, 2000.0, 14),
        ),
    ],
)
def test_known_parameters_recovered_within_their_uncertainties(system, truth, start, z):
    """Two systems, three kinds of parameter; 3 sigma (a single draw; coverage is tested above)."""
    f = lo.fit(
        parameters.replace(system, start),
        z,
        _noisy(_curve(system, truth, z), np.random.default_rng(2)),
        sigma=SIGMA,
        free=list(truth),
        **FAST,
    )
    assert f.converged and f.degrees_of_freedom == z.size - 2
    for p, v in truth.items():
        assert (
            np.isfinite(f.uncertainties[p]) and abs(f.parameters[p] - v) <= 3 * f.uncertainties[p]
        ), (p, f.parameters[p], f.uncertainties[p])
    print(f"correlation {f.correlation[0, 1]:+.3f}, reduced chi-square {f.reduced_chi_square:.3f}")
    assert 0.2 < f.reduced_chi_square < 3.0 and not f.degenerate_pairs
    assert f.system == parameters.replace(system, f.parameters) and f.result.system == f.system


def test_unit_weights_scale_the_covariance_by_the_reduced_chi_square():
    g, start = _curve(TABLE1, TRUE, Z), parameters.replace(TABLE1, START)
    y = _noisy(g, np.random.default_rng(3))
    weighted = lo.fit(start, Z, y, sigma=SIGMA, free=list(TRUE), **FAST)
    unit = lo.fit(start, Z, y, free=list(TRUE), **FAST)
    assert unit.covariance_scaled and unit.sigma is None and not weighted.covariance_scaled
    np.testing.assert_allclose(
        unit.covariance, weighted.covariance * weighted.reduced_chi_square, rtol=1e-3
    )


def test_jacobian_covariance_against_a_bootstrap_of_the_residuals():
    """50 resamples of the residuals added to the fitted curve; standard errors within 25 %."""
    g, start, rng = (
        _curve(TABLE1, TRUE, Z),
        parameters.replace(TABLE1, START),
        np.random.default_rng(4),
    )
    f = lo.fit(start, Z, _noisy(g, rng), sigma=SIGMA, free=list(TRUE), **FAST)
    model, r = f.result.overlap, f.measured - f.result.overlap
    r = (r - r.mean()) * np.sqrt(Z.size / f.degrees_of_freedom)  # the residuals' deficit of dof
    draws = np.array(
        [
            list(
                lo.fit(
                    start, Z, model + rng.choice(r, Z.size), sigma=SIGMA, free=list(TRUE), **FAST
                ).parameters.values()
            )
            for _ in range(50)
        ]
    )
    ratio = draws.std(axis=0, ddof=1) / np.array(list(f.uncertainties.values()))
    print(f"bootstrap / Jacobian standard errors: {dict(zip(TRUE, ratio))}")
    assert np.all(np.abs(ratio - 1.0) <= 0.25), ratio


#: A beam tilted towards the field's edge, 5 cm off axis: at long range the offset only adds offset
#: / z to the tilt, so the two are degenerate there; near ranges tell them apart.
EDGE = {"beam.tilt[0]": 3.5e-4, "beam.offset[0]": 0.05}


@pytest.mark.parametrize(
    "z, degenerate",
    [(np.geomspace(2000.0, 3000.0, 10), True), (np.geomspace(40.0, 4000.0, 16), False)],
)
def test_degeneracy_of_tilt_and_offset_warned_at_long_range_only(z, degenerate):
    g = _curve(TABLE1, EDGE, z)
    start = parameters.replace(TABLE1, {"beam.tilt[0]": 3.3e-4, "beam.offset[0]": 0.04})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        f = lo.fit(
            start,
            z,
            _noisy(g, np.random.default_rng(5), 0.002),
            sigma=0.002,
            free=list(EDGE),
            **FAST,
        )
    said = [str(w.message) for w in caught if issubclass(w.category, lo.DegeneracyWarning)]
    print(f"correlation tilt/offset from {z[0]:g} m: {f.correlation[0, 1]:+.4f}")
    if degenerate:
        assert len(said) == 1 and "beam.tilt[0]" in said[0] and "beam.offset[0]" in said[0]
        assert [pair[:2] for pair in f.degenerate_pairs] == [("beam.tilt[0]", "beam.offset[0]")]
    else:
        assert not said and f.degenerate_pairs == ()


def test_tilt_and_detector_offset_along_one_axis_are_one_parameter_to_ray_tracing():
    """A detector offset dx moves the field of view as a beam tilt -dx / f does: the Jacobian is
    singular."""
    truth = {"beam.tilt[0]": -2e-4, "detector.offset[0]": 1e-4}
    g = _curve(TABLE1, truth, Z)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        f = lo.fit(
            parameters.replace(TABLE1, {"beam.tilt[0]": -1e-4, "detector.offset[0]": 0.5e-4}),
            Z,
            _noisy(g, np.random.default_rng(10)),
            sigma=SIGMA,
            free=list(truth),
            **FAST,
        )
    said = [str(w.message) for w in caught if issubclass(w.category, lo.DegeneracyWarning)]
    assert any("singular" in m for m in said) and any(
        "beam.tilt[0] and detector.offset[0]" in m for m in said
    )
    assert np.all(np.isinf(f.covariance)) and [p[:2] for p in f.degenerate_pairs] == [tuple(truth)]
    assert np.max(np.abs(f.residuals)) < 4.0  # the curve is still fitted


def test_partial_curve_from_150_m_extrapolated_band_covers_the_truth_at_50_m():
    """The Raman method measures G from 150 m only; the fit's band at 50 m (2 sigma) covers the true
    G."""
    z = np.geomspace(150.0, 2000.0, 12)
    f = lo.fit(
        parameters.replace(TABLE1, START),
        z,
        _noisy(_curve(TABLE1, TRUE, z), np.random.default_rng(6), 0.005),
        sigma=0.005,
        free=list(TRUE),
        **FAST,
    )
    near = np.array([50.0, 100.0])
    pred, true = f.predict(near), _curve(TABLE1, TRUE, near)
    print(f"G at 50 m: predicted {pred.overlap[0]:.5f} ± {pred.sigma[0]:.5f}, true {true[0]:.5f}")
    assert np.all(pred.sigma > 0) and np.all(np.abs(pred.overlap - true) <= 2 * pred.sigma), (
        pred,
        true,
    )


def test_robust_loss_resists_outliers_where_linear_does_not():
    g, start = _curve(TABLE1, TRUE, Z), parameters.replace(TABLE1, START)
    y = _noisy(g, np.random.default_rng(7))
    y[[6, 8]] += 0.3  # two outliers of 30 sigma near the curve's rise
    errors = {}
    with pytest.warns(lo.FitQualityWarning, match="far above 1"):  # the outliers, said
        f = lo.fit(start, Z, y, sigma=SIGMA, free=list(TRUE), loss="linear", **FAST)
    errors["linear"] = max(abs(f.parameters[p] - v) / f.uncertainties[p] for p, v in TRUE.items())
    for loss in ("soft_l1",):
        f = lo.fit(start, Z, y, sigma=SIGMA, free=list(TRUE), loss=loss, **FAST)
        errors[loss] = max(abs(f.parameters[p] - v) / f.uncertainties[p] for p, v in TRUE.items())
    print(f"largest |error| / sigma with outliers: {errors}")
    assert errors["soft_l1"] <= 3.0 < errors["linear"]


def test_non_convergence_raises_unless_allowed():
    y = _noisy(_curve(TABLE1, TRUE, Z), np.random.default_rng(8))
    with pytest.raises(RuntimeError, match="did not converge.*max_evaluations"):
        lo.fit(
            parameters.replace(TABLE1, START),
            Z,
            y,
            sigma=SIGMA,
            free=list(TRUE),
            max_evaluations=2,
            **FAST,
        )
    f = lo.fit(
        parameters.replace(TABLE1, START),
        Z,
        y,
        sigma=SIGMA,
        free=list(TRUE),
        max_evaluations=2,
        allow_unconverged=True,
        **FAST,
    )
    assert not f.converged and f.status == 0


def test_model_tolerance_above_the_noise_warns():
    y = _noisy(_curve(TABLE1, TRUE, Z), np.random.default_rng(9))
    with pytest.warns(RuntimeWarning, match="tolerance 0.01 exceeds 0.1 x the median sigma"):
        lo.fit(
            parameters.replace(TABLE1, START),
            Z,
            y,
            sigma=SIGMA,
            free=list(TRUE),
            method="rt",
            tolerance=1e-2,
            threads=1,
        )
    with pytest.warns(
        RuntimeWarning, match="exceeds 0.1 x the scatter of the residuals"
    ):  # sigma=None
        lo.fit(
            parameters.replace(TABLE1, START),
            Z,
            y,
            free=list(TRUE),
            method="rt",
            tolerance=1e-2,
            threads=1,
        )


def test_auto_is_planned_once_and_its_fourier_optics_choice_kept():
    """Table 1 at 1e-4 is Fourier optics for auto: every evaluation and Jacobian runs that plan (no
    batch)."""
    z = np.geomspace(60.0, 2000.0, 8)
    f = lo.fit(
        parameters.replace(TABLE1, START),
        z,
        _noisy(_curve(TABLE1, TRUE, z), np.random.default_rng(11)),
        sigma=SIGMA,
        free=list(TRUE),
        method="auto",
        tolerance=1e-4,
        threads=1,
    )
    assert f.plan.backend == "fo_radial" and f.result.method == "fo" and f.converged
    for p, v in TRUE.items():
        assert abs(f.parameters[p] - v) <= 3 * f.uncertainties[p], p


def test_without_scipy_the_error_names_the_extra(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "scipy", None)
    monkeypatch.setitem(sys.modules, "scipy.optimize", None)
    with pytest.raises(ImportError, match=r"pip install 'lidar-overlap\[fit\]'"):
        lo.fit(TABLE1, Z, np.full(Z.size, 0.5))


GOOD = dict(free=list(TRUE), **FAST)


@pytest.mark.parametrize(
    "change, match",
    [
        (dict(free=["beam.tilted"]), r"free: parameter 'beam.tilted' is invalid"),
        (dict(free=[]), r"free = \[\] is invalid"),
        (
            dict(bounds={"beam.tilt[0]": (3e-4, 1e-3)}),
            r"bounds\['beam.tilt\[0\]'\].*excludes the start",
        ),
        (dict(bounds={"beam.tilt[0]": (1e-3, -1e-3)}), r"expected low < high"),
        (
            dict(bounds={"beam.offset[0]": (-1, 1)}),
            r"bounds: 'beam.offset\[0\]' is not a free parameter",
        ),
        (dict(measured=np.ones(5)), r"measured has shape \(5,\): expected \(12,\)"),
        (
            dict(measured=np.where(np.arange(12) == 3, np.nan, 0.5)),
            r"measured\[3\] = nan is invalid",
        ),
        (
            dict(measured=np.where(np.arange(12) == 4, np.inf, 0.5)),
            r"measured\[4\] = inf is invalid",
        ),
        (dict(sigma=0.0), r"sigma\[0\] = 0.0 is invalid: expected finite values from 1e-100"),
        (dict(sigma=np.where(np.arange(12) == 2, np.nan, 0.01)), r"sigma\[2\] = nan is invalid"),
        (dict(sigma=-0.01), r"sigma\[0\] = -0.01 is invalid"),
        (dict(ranges=Z[::-1]), r"ranges must be strictly increasing"),
        (
            dict(ranges=Z[:1], measured=[0.1], free=["beam.tilt", "detector.defocus"]),
            r"measured has 1 points for 3 free parameters: expected more points",
        ),
        (dict(loss="l1"), r"loss = 'l1' is invalid"),
        # a truthy string is no consent to an unconverged result
        (dict(allow_unconverged="no"), r"^allow_unconverged = 'no' is invalid: expected True or"),
        (dict(allow_unconverged=1), r"^allow_unconverged = 1 is invalid"),
        (dict(method=lo.Turbulent(lo.Turbulence(1e-14), "rt")), r"Turbulent.*random draws"),
    ],
)
def test_hostile_inputs_refused_naming_the_argument(change, match):
    args = dict(
        system=parameters.replace(TABLE1, START),
        ranges=Z,
        measured=np.full(Z.size, 0.5),
        sigma=SIGMA,
        **GOOD,
    )
    args.update(change)
    with pytest.raises(ValueError, match=match):
        lo.fit(**args)
