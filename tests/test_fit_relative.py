"""lo.fit(..., normalize=...): relative data (normalised to their mean over an interval, or to 1 in
the far range) give the parameters an absolute fit of absolute data gives; the covariance of the
normalised problem covers the truth at its stated rate; bad intervals are clear errors; the command
line's --normalize."""

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.analysis.fitting.normalization import normalization
from lidar_overlap.cli import main

pytest.importorskip("scipy")

FAST = dict(method="rt", tolerance=1e-6, threads=1)
TABLE1 = lo.paper_table1()
TRUE = {"beam.tilt[0]": 3e-4, "detector.defocus": 2e-3}
START = {"beam.tilt[0]": 2e-4, "detector.defocus": 1e-3}
Z = np.geomspace(60.0, 3000.0, 20)
INTERVAL = (1000.0, 3000.0)
#: Noise-free data: both fits stop at the truth to the optimiser's precision, far below this
#: fraction of the parameters' natural scales (tilt 4.5e-4 rad, defocus 6 mm).
SAME = 1e-3
SIGMA = 0.01
#: 1-sigma coverage over N_DRAWS draws: 0.683 +- 2.9 binomial standard deviations (0.066).
N_DRAWS, COVERAGE = 50, (0.49, 0.88)


def _truth(z=Z, tol=1e-8):
    return lo.overlap(parameters.replace(TABLE1, TRUE), z, "rt", tolerance=tol).overlap


def _start():
    return parameters.replace(TABLE1, START)


@pytest.mark.filterwarnings("ignore:fit. the model's tolerance")  # noise-free data
@pytest.mark.parametrize("normalize", [INTERVAL, "far"])
def test_relative_fit_of_relative_data_equals_absolute_fit_of_absolute_data(normalize):
    g = _truth()
    absolute = lo.fit(_start(), Z, g, free=list(TRUE), **FAST)
    if normalize == "far":
        far = _truth(np.array([100.0 * Z[-1]]))[0]
        relative_data = g / far  # normalised to 1 in the far range
    else:
        inside = (Z >= INTERVAL[0]) & (Z <= INTERVAL[1])
        relative_data = 0.83 * g / g[inside].mean()  # any scale: only the shape counts
    relative = lo.fit(_start(), Z, relative_data, free=list(TRUE), normalize=normalize, **FAST)
    assert isinstance(relative, lo.RelativeFitResult)
    for path, scale in (("beam.tilt[0]", 4.5e-4), ("detector.defocus", 6e-3)):
        assert abs(relative.parameters[path] - absolute.parameters[path]) < SAME * scale
        assert abs(relative.parameters[path] - TRUE[path]) < SAME * scale
    assert relative.chi_square < 1e-6
    assert relative.fitted == pytest.approx(relative.measured, abs=1e-5)


def test_interval_normalisation_loses_one_degree_of_freedom_and_predicts_on_its_scale():
    rng = np.random.default_rng(3)
    y = _truth() + rng.normal(0.0, SIGMA, Z.size)
    f = lo.fit(_start(), Z, y, SIGMA, free=list(TRUE), normalize=INTERVAL, **FAST)
    assert f.degrees_of_freedom == Z.size - 1 - len(TRUE)
    inside = (Z >= INTERVAL[0]) & (Z <= INTERVAL[1])
    assert f.measured[inside].mean() == pytest.approx(1.0, abs=1e-12)
    assert f.fitted[inside].mean() == pytest.approx(1.0, abs=1e-12)
    pred = f.predict(Z)
    assert pred.overlap == pytest.approx(f.fitted, abs=1e-6)
    assert np.all(np.isfinite(pred.sigma)) and np.all(pred.sigma >= 0)
    assert f.absolute(Z).overlap == pytest.approx(f.fitted * f.model_scale, abs=1e-6)


def test_normalised_covariance_covers_the_truth_at_the_1_sigma_rate():
    rng = np.random.default_rng(11)
    g = _truth()
    inside_tilt = 0
    for _ in range(N_DRAWS):
        y = (g + rng.normal(0.0, SIGMA, Z.size)) * 1.1
        f = lo.fit(_start(), Z, y, SIGMA * 1.1, free=list(TRUE), normalize=INTERVAL, **FAST)
        inside_tilt += (
            abs(f.parameters["beam.tilt[0]"] - TRUE["beam.tilt[0]"])
            < (f.uncertainties["beam.tilt[0]"])
        )
    assert COVERAGE[0] <= inside_tilt / N_DRAWS <= COVERAGE[1]


@pytest.mark.parametrize(
    "normalize, message",
    [
        ((10.0, 65.0), r"holds 1 measured points \(the data span \[60, 3000\] m\)"),
        ((2000.0, 1000.0), "expected z_low < z_high"),
        ((2000.0, 2100.0), "holds 0 measured points"),
        ((4000.0, 5000.0), "holds 0 measured points"),
        ("near", "expected None, 'far' or"),
        ((1.0, 2.0, 3.0), "expected None, 'far' or"),
    ],
)
def test_bad_normalisation_is_a_clear_error(normalize, message):
    with pytest.raises(ValueError, match=message):
        lo.fit(_start(), Z, _truth(), free=list(TRUE), normalize=normalize, **FAST)


def test_an_interval_reaching_past_the_data_selects_the_points_within_it():
    # the last point at 2499.2 m: (1500, 2500) holds the points of (1500, 2499.2), and the fit is
    # the same fit
    z = np.geomspace(60.0, 2499.2, 20)
    y = 0.9 * _truth(z)
    w = np.full(z.size, SIGMA)
    wide, exact = normalization((1500.0, 2500.0), z, y, w), normalization((1500.0, 2499.2), z, y, w)
    assert wide.inside.sum() >= 2 and np.array_equal(wide.inside, exact.inside)
    assert np.array_equal(wide.whitening, exact.whitening)
    f = lo.fit(_start(), z, y, SIGMA, free=list(TRUE), normalize=(1500.0, 2500.0), **FAST)
    g = lo.fit(_start(), z, y, SIGMA, free=list(TRUE), normalize=(1500.0, 2499.2), **FAST)
    assert f.parameters == g.parameters and f.chi_square == g.chi_square


@pytest.mark.parametrize("scale", [1e-200, 1e-300])
def test_data_too_small_for_their_weights_are_refused_naming_measured(scale):
    # unit weights on data of 1e-300: sigma / mean overflows double precision (it reached the
    # eigendecomposition as a LinAlgError)
    y = scale * _truth()
    mean = float(y[(Z >= INTERVAL[0]) & (Z <= INTERVAL[1])].mean())
    with pytest.raises(lo.ParameterError, match=rf"^measured: .* is {mean:g} and sigma reaches 1:"):
        lo.fit(_start(), Z, y, free=list(TRUE), normalize=INTERVAL, **FAST)


def test_fewer_points_than_parameters_is_a_clear_error():
    z = Z[-3:]
    with pytest.raises(ValueError, match="points for 2 free parameters"):
        lo.fit(_start(), z, _truth(z), free=list(TRUE), normalize=(z[0], z[-1]), **FAST)


def test_command_line_normalize(tmp_path, capsys, fit_inputs):
    scenario, data = fit_inputs(Z.tolist(), (0.9 * _truth()).tolist())
    args = ["fit", str(scenario), str(data), "--free", *TRUE, "--out", str(tmp_path / "out")]
    assert main(args + ["--normalize", "1000", "3000"]) == 0
    printed = capsys.readouterr().out
    assert "relative data" in printed and "1000-3000 m" in printed
    assert "# normalize" in (tmp_path / "out" / "table1_fit.csv").read_text()


def test_command_line_normalize_with_fourier_optics_and_its_default_tolerance(
    tmp_path, capsys, fit_inputs
):
    # the relative fit's tolerance left to the library on the FO path (it printed "internal
    # error": the tolerance was None)
    z = np.geomspace(300.0, 1200.0, 5)
    scenario, data = fit_inputs(z.tolist(), (0.9 * _truth(z)).tolist())
    args = ["fit", str(scenario), str(data), "--free", "beam.tilt[0]", "--out", str(tmp_path)]
    assert main(args + ["--normalize", "500", "1000", "--method", "fo"]) == 0
    printed = capsys.readouterr().out
    assert "fit (fo" in printed and "500-1000 m" in printed


def test_interval_whitening_is_the_pseudo_inverse_square_root_and_is_reused_read_only():
    rng = np.random.default_rng(3)
    z = np.linspace(100.0, 1000.0, 30)
    y = 0.9 + 0.1 * rng.random(z.size)
    w = 0.01 + 0.01 * rng.random(z.size)
    first = normalization((500.0, 1000.0), z, y, w)
    # W^T W = C^+, C the covariance of the data divided by their own mean (normalization.py)
    inside = first.inside
    a = (np.eye(z.size) - np.outer(first.data, inside / inside.sum())) / first.data_scale
    cov = (a * w**2) @ a.T
    white = first.whitening
    assert white.shape == (z.size - 1, z.size)
    np.testing.assert_allclose(
        white.T @ white, np.linalg.pinv(cov, rcond=1e-10, hermitian=True), rtol=1e-8, atol=1e-6
    )
    # the same data again reuse it (the ladder sets up one curve's fit many times); it cannot be
    # changed through one fit's normalisation, and other errors give another
    assert normalization((500.0, 1000.0), z, y.copy(), w.copy()).whitening is white
    with pytest.raises(ValueError):
        white[0, 0] = 1.0
    other = w.copy()
    other[0] *= 2.0
    assert normalization((500.0, 1000.0), z, y, other).whitening is not white
