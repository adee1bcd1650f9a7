"""A fit says what it found: statistics that are not finite numbers are an error, a converged fit
whose residuals say the minimum is local or the model inadequate warns FitQualityWarning, a
zero-residual fit without sigma warns, and parameter paths are compared in their plain form."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.analysis.fitting import verdict as fit_verdict

pytest.importorskip("scipy")

FAST = dict(method="rt", tolerance=1e-5, threads=1)
TABLE1 = lo.paper_table1()
Z = np.geomspace(30.0, 2000.0, 24)
TRUE = {"beam.tilt[0]": 3e-4, "detector.defocus": 2e-3}
START = {"beam.tilt[0]": 2e-4, "detector.defocus": 1e-3}
SIGMA = 0.01


def _truth():
    return lo.overlap(parameters.replace(TABLE1, TRUE), Z, "rt", tolerance=1e-8).overlap


def _quiet_fit(*args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("error", fit_verdict.FitQualityWarning)
        return lo.fit(*args, **kwargs)


def test_a_good_fit_with_sigma_is_not_warned_and_its_statistics_are_finite():
    y = _truth() + np.random.default_rng(3).normal(0.0, SIGMA, Z.size)
    f = _quiet_fit(parameters.replace(TABLE1, START), Z, y, sigma=SIGMA, free=list(TRUE), **FAST)
    assert f.converged
    stats = [f.chi_square, f.reduced_chi_square, *f.uncertainties.values()]
    assert all(math.isfinite(v) for v in stats) and np.all(np.isfinite(f.correlation))


def test_chi_square_far_above_one_warns_that_the_minimum_may_be_local():
    # sigma ten times smaller than the noise: chi²/dof ~ 100
    y = _truth() + np.random.default_rng(4).normal(0.0, SIGMA, Z.size)
    with pytest.warns(lo.FitQualityWarning, match="far above 1"):
        lo.fit(parameters.replace(TABLE1, START), Z, y, sigma=SIGMA / 10, free=list(TRUE), **FAST)


def test_structured_residuals_warn_without_sigma():
    # the wrong model: a curve that the free parameters cannot make (a smooth bump added)
    z = np.geomspace(30.0, 2000.0, 80)
    g = lo.overlap(parameters.replace(TABLE1, TRUE), z, "rt", tolerance=1e-8).overlap
    y = np.clip(g + 0.05 * np.sin(np.linspace(0.0, 5.0 * np.pi, z.size)), 0.0, 1.0)
    with pytest.warns(lo.FitQualityWarning, match="structured"):
        lo.fit(parameters.replace(TABLE1, START), z, y, free=list(TRUE), **FAST)


def test_a_zero_residual_fit_without_sigma_warns_and_its_correlation_is_a_number():
    y = lo.overlap(parameters.replace(TABLE1, START), Z, **FAST).overlap
    with pytest.warns(lo.FitQualityWarning, match="exactly"):
        f = lo.fit(parameters.replace(TABLE1, START), Z, y, free=list(TRUE), **FAST)
    assert np.all(np.isfinite(f.correlation))
    assert all(v == 0.0 for v in f.uncertainties.values())


@pytest.mark.parametrize("sigma", [1e-300, 1e300, 1e-101])
def test_sigma_out_of_double_range_is_refused_by_name(sigma):
    with pytest.raises(ValueError, match=r"sigma\[0\]"):
        lo.fit(TABLE1, Z, _truth(), sigma=sigma, free=["detector.defocus"], **FAST)


def test_measured_values_far_from_g_are_refused_by_name():
    with pytest.raises(ValueError, match=r"measured\[\d+\]"):
        lo.fit(TABLE1, Z, _truth() * 1e300, free=["detector.defocus"], **FAST)


@pytest.mark.parametrize(
    "measured",
    [lambda g: g + 0j, lambda g: [str(v) for v in g], lambda g: g > 0.5],
)
def test_measured_takes_real_numbers_only(measured):
    with pytest.raises(ValueError, match="measured"):
        lo.fit(TABLE1, Z, measured(_truth()), free=["detector.defocus"], **FAST)


@pytest.mark.parametrize("sigma", [True, "0.01", 0.01 + 0j])
def test_sigma_takes_real_numbers_only(sigma):
    with pytest.raises(ValueError, match="sigma"):
        lo.fit(TABLE1, Z, _truth(), sigma=sigma, free=["detector.defocus"], **FAST)


def test_telecover_fit_refuses_sigma_beyond_double_range():
    mask = lo.ApertureMask.sectors(4)
    dev = np.zeros((4, Z.size))
    with pytest.raises(ValueError, match="sigma"):
        lo.fit_telecover(TABLE1, Z[5:], dev[:, 5:], 1e300, free=["beam.tilt"], sectors=mask)


def test_no_degrees_of_freedom_is_refused():
    z = Z[:2]
    with pytest.raises(ValueError, match="more points than parameters"):
        lo.fit(TABLE1, z, _truth()[:2], sigma=SIGMA, free=list(TRUE), **FAST)


@pytest.mark.parametrize(
    "free",
    [
        ["beam.tilt[0]", "beam.tilt[00]"],
        ["beam.tilt[0]", "beam.tilt"],
        ["detector.defocus", "detector.defocus"],
    ],
)
def test_one_scalar_named_twice_is_refused(free):
    with pytest.raises(ValueError, match="named twice"):
        lo.fit(TABLE1, Z, _truth(), free=free, **FAST)


@pytest.mark.parametrize("path", ["beam.tilt[0]\n", "beam.tilt[\u0660]", "detector.defocus\n"])
def test_paths_with_a_newline_or_non_ascii_digits_are_refused(path):
    with pytest.raises(ValueError, match="free"):
        lo.fit(TABLE1, Z, _truth(), free=[path], **FAST)


def test_free_none_is_a_clear_error():
    with pytest.raises(ValueError, match="free = None is invalid"):
        lo.fit(TABLE1, Z, _truth(), free=None, **FAST)


def test_canonical_paths():
    assert parameters.canonical("beam.tilt[00]") == "beam.tilt[0]"
    assert parameters.canonical("telescope.aberrations.zernike[011]") == (
        "telescope.aberrations.zernike[11]"
    )
    assert parameters.expand(["beam.tilt"]) == ["beam.tilt[0]", "beam.tilt[1]"]


def test_the_runs_test_tells_noise_from_structure():
    rng = np.random.default_rng(0)
    assert abs(fit_verdict.runs_z(rng.normal(size=400))) < fit_verdict.RUNS_Z
    assert fit_verdict.runs_z(np.sin(np.linspace(0, 4 * np.pi, 400))) < -fit_verdict.RUNS_Z
    assert fit_verdict.runs_z(np.ones(5)) is None


def test_a_zero_residual_fit_of_a_degenerate_parameter_is_warned_not_nan():
    # G is even in the tilt of a coaxial lidar: at tilt 0 the Jacobian is singular
    y = lo.overlap(TABLE1, Z, **FAST).overlap
    with pytest.warns((lo.FitQualityWarning, lo.DegeneracyWarning)):
        f = lo.fit(TABLE1, Z, y, free=["detector.defocus", "beam.tilt[0]"], **FAST)
    assert not any(math.isnan(v) for v in f.uncertainties.values())
    assert not np.isnan(f.covariance).any() and not np.isnan(f.correlation).any()


@pytest.mark.parametrize("where", ["residuals", "jac"])
def test_values_not_finite_at_the_start_are_refused_in_the_fit_s_words(where):
    """The driver's guard (the fit's input checks keep real data from reaching it): scipy's own
    refusal names no parameter; no extra evaluation is made to check."""
    from scipy import optimize

    calls = []

    def residuals(x):
        calls.append(x)
        return np.array([np.inf if where == "residuals" else 1.0, x[0]])

    def jac(x):
        return np.array([[np.nan if where == "jac" else 0.0], [1.0]])

    with pytest.raises(ValueError, match="not finite at the start: sigma is too small"):
        fit_verdict.least_squares(optimize, residuals, np.array([0.5]), jac=jac)
    assert len(calls) == 1
    fine = fit_verdict.least_squares(
        optimize, lambda x: x - 2.0, np.array([0.0]), jac=lambda x: [[1]]
    )
    assert fine.x[0] == pytest.approx(2.0)
