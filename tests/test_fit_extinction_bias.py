"""lo.fit(..., normalize=(z_low, z_high), extinction_bias=True): relative data carrying the two-way
transmission error exp(-2 da (z - z_ref)) of their retrieval give back da and the system the data
without the trend give; da's uncertainty is that of the joint least-squares problem (an independent
finite-difference Jacobian and pseudo-inverse here) and its pulls scatter as N(0, 1); with da = 0
the fitted da is consistent with 0 and the information criterion rarely asks for it; the global
search's batched profile equals a grid search over da; the ladder counts da in every family's k;
the command line's --extinction-bias; bad input is a clear error."""

import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.analysis.fitting.families import Family
from lidar_overlap.analysis.fitting.ladder import BIC_TIE, fit_ladder
from lidar_overlap.analysis.fitting.normalization import EXTINCTION_BIAS_BOUND, normalization
from lidar_overlap.analysis.fitting.problem import fit_problem
from lidar_overlap.cli import main

pytest.importorskip("scipy")

FAST = dict(method="rt", tolerance=1e-6, threads=1)
TABLE1 = lo.paper_table1()
TRUE = {"beam.tilt[0]": 3e-4, "detector.defocus": 2e-3}
START = {"beam.tilt[0]": 2e-4, "detector.defocus": 1e-3}
SCALES = {"beam.tilt[0]": 4.5e-4, "detector.defocus": 6e-3}
Z = np.geomspace(60.0, 3000.0, 24)
INTERVAL = (1000.0, 3000.0)
INSIDE = (Z >= INTERVAL[0]) & (Z <= INTERVAL[1])
Z_REF = Z[INSIDE].mean()
#: The retrieval's extinction error of the synthetic data (1/m): 0.03 /km, two-way 0.17 over 3 km.
DA = 3e-5
SIGMA = 0.005
#: Noise-free data: the fit stops at the truth to the optimiser's precision, far below this
#: fraction of the parameters' natural scales (and of the bias bound for da).
SAME = 1e-3
#: The stated uncertainty of da agrees with the independent joint covariance to this fraction (the
#: finite-difference Jacobians differ at 1e-4; the rest is the 1e-6 model tolerance).
UNCERTAINTY_AGREE = 0.03
#: Sum of N_DRAWS squared pulls ~ chi²(N_DRAWS): its two-sided 99.8 % interval for 10 draws.
N_DRAWS, PULL_CHI2 = 10, (1.48, 29.6)
#: With da = 0, BIC asks for the trend (a gain above ln n + BIC_TIE in chi², p ~ 0.02 a draw) in
#: at most this many of N_DRAWS draws (binomial: P(>= 3) ~ 1e-3).
MOST_FALSE_TRENDS = 2
#: The profiled cost and δα agree with a parabola-refined grid search to this fraction (the cost is
#: quadratic in da to 1e-4 of it over a grid step of 1e-8 /m; the profile stops at 1e-12 /m).
GRID_AGREE = 1e-8


def _truth(tol=1e-8):
    return lo.overlap(parameters.replace(TABLE1, TRUE), Z, "rt", tolerance=tol).overlap


def _trend(da):
    return np.exp(-2.0 * da * (Z - Z_REF))


def _start():
    return parameters.replace(TABLE1, START)


def _fit(y, sigma=SIGMA, **kw):
    return lo.fit(_start(), Z, y, sigma=sigma, free=list(TRUE), normalize=INTERVAL, **FAST, **kw)


@pytest.mark.filterwarnings("ignore:fit. the model's tolerance")  # noise-free data
def test_noise_free_trended_data_give_back_da_and_the_system_of_the_untrended_data():
    g = _truth()
    with_bias = _fit(0.9 * g * _trend(DA), sigma=None, extinction_bias=True)
    plain = _fit(g, sigma=None)
    assert isinstance(with_bias, lo.RelativeFitResult)
    assert abs(with_bias.extinction_bias - DA) < SAME * EXTINCTION_BIAS_BOUND
    assert with_bias.extinction_bias_reference == pytest.approx(Z_REF)
    for path, scale in SCALES.items():
        assert abs(with_bias.parameters[path] - TRUE[path]) < SAME * scale
        assert abs(with_bias.parameters[path] - plain.parameters[path]) < SAME * scale
    # one degree of freedom more taken than without the trend
    assert with_bias.degrees_of_freedom == plain.degrees_of_freedom - 1
    # the prediction carries the trend: it reproduces the fitted curve at the measured ranges
    assert with_bias.predict(Z).overlap == pytest.approx(with_bias.fitted, abs=1e-9)
    assert plain.extinction_bias is None and "extinction bias" in with_bias.summary()


def _normalised(g, da):
    v = g * _trend(da)
    return v / v[INSIDE].mean()


def test_da_uncertainty_is_that_of_the_joint_problem():
    """Independent: central differences of the normalised model in (tilt, defocus, da) from
    lo.overlap, and the covariance (Jᵀ C⁺ J)⁻¹ with C⁺ numpy's pseudo-inverse of the normalised
    data's covariance A diag(σ²) Aᵀ."""
    rng = np.random.default_rng(3)
    y = _truth() * _trend(DA) + rng.normal(0.0, SIGMA, Z.size)
    f = _fit(y, extinction_bias=True)
    best = parameters.replace(TABLE1, f.parameters)
    columns = []
    for path, h in (("beam.tilt[0]", 1e-6), ("detector.defocus", 2e-5)):
        shifted = [
            lo.overlap(
                parameters.replace(best, {path: f.parameters[path] + s}), Z, "rt", tolerance=1e-9
            ).overlap
            for s in (h, -h)
        ]
        columns.append(
            (
                _normalised(shifted[0], f.extinction_bias)
                - _normalised(shifted[1], f.extinction_bias)
            )
            / (2 * h)
        )
    g = lo.overlap(best, Z, "rt", tolerance=1e-9).overlap
    h = 1e-7
    columns.append(
        (_normalised(g, f.extinction_bias + h) - _normalised(g, f.extinction_bias - h)) / (2 * h)
    )
    j = np.array(columns).T
    mean = y[INSIDE].mean()
    e = INSIDE / INSIDE.sum()
    a = (np.eye(Z.size) - np.outer(y / mean, e)) / mean
    c_plus = np.linalg.pinv(a @ np.diag(np.full(Z.size, SIGMA**2)) @ a.T, rcond=1e-10)
    cov = np.linalg.inv(j.T @ c_plus @ j)
    assert f.extinction_bias_uncertainty == pytest.approx(
        math.sqrt(cov[2, 2]), rel=UNCERTAINTY_AGREE
    )
    for i, path in enumerate(TRUE):
        assert f.uncertainties[path] == pytest.approx(math.sqrt(cov[i, i]), rel=UNCERTAINTY_AGREE)


def test_da_pulls_scatter_as_a_unit_normal_and_the_system_is_recovered():
    g = _truth()
    pulls = []
    for seed in range(N_DRAWS):
        y = g * _trend(DA) + np.random.default_rng(seed).normal(0.0, SIGMA, Z.size)
        f = _fit(y, extinction_bias=True)
        pulls.append((f.extinction_bias - DA) / f.extinction_bias_uncertainty)
        for path in TRUE:
            assert abs(f.parameters[path] - TRUE[path]) < 5 * f.uncertainties[path]
    assert PULL_CHI2[0] < np.sum(np.square(pulls)) < PULL_CHI2[1]


def test_without_a_trend_da_is_consistent_with_zero_and_rarely_chosen():
    g = _truth()
    chosen, pulls = 0, []
    for seed in range(N_DRAWS):  # the draws of the trended test: its pulls less the trend's effect
        y = g + np.random.default_rng(seed).normal(0.0, SIGMA, Z.size)
        plain, with_bias = _fit(y), _fit(y, extinction_bias=True)
        pulls.append(with_bias.extinction_bias / with_bias.extinction_bias_uncertainty)
        n = plain.degrees_of_freedom + len(TRUE)  # independent points
        bic_plain = plain.chi_square + len(TRUE) * math.log(n)
        bic_bias = with_bias.chi_square + (len(TRUE) + 1) * math.log(n)
        chosen += bic_bias < bic_plain - BIC_TIE
        assert (
            with_bias.chi_square <= plain.chi_square + 1e-6
        )  # one more parameter never fits worse
    assert PULL_CHI2[0] < np.sum(np.square(pulls)) < PULL_CHI2[1]
    assert chosen <= MOST_FALSE_TRENDS


@pytest.mark.filterwarnings("ignore::lidar_overlap.FitQualityWarning")  # the rest is misfit
def test_a_trend_beyond_the_bound_rests_on_it_and_says_so():
    y = _truth() * _trend(3 * EXTINCTION_BIAS_BOUND)
    with pytest.warns(RuntimeWarning, match="rests on its bound"):
        f = _fit(y, allow_unconverged=True, extinction_bias=True)
    assert f.extinction_bias == pytest.approx(EXTINCTION_BIAS_BOUND, rel=1e-9)


@pytest.mark.parametrize("value", ["yes", 1, 1.0, np.nan, np.inf, None, [True]])
def test_extinction_bias_must_be_a_bool(value):
    with pytest.raises(ValueError, match="extinction_bias = .* expected True or False"):
        _fit(_truth(), extinction_bias=value)


@pytest.mark.parametrize("normalize", [None, "far"])
def test_extinction_bias_needs_an_interval(normalize):
    with pytest.raises(ValueError, match=r"extinction_bias=True needs normalize = \(z_low"):
        lo.fit(_start(), Z, _truth(), sigma=SIGMA, free=list(TRUE), normalize=normalize,
               extinction_bias=True, **FAST)  # fmt: skip


def test_false_and_numpy_bools_are_accepted():
    y = _truth() + np.random.default_rng(7).normal(0.0, SIGMA, Z.size)
    assert _fit(y, extinction_bias=np.bool_(False)).extinction_bias is None
    assert _fit(y, extinction_bias=np.bool_(True)).extinction_bias is not None


def test_nan_or_inf_data_are_refused_with_the_bias_too():
    for bad in (np.nan, np.inf):
        y = _truth().copy()
        y[5] = bad
        with pytest.raises(ValueError, match=r"measured\[5\]"):
            _fit(y, extinction_bias=True)


def test_profiled_cost_of_many_curves_is_the_least_over_a_grid_of_da():
    """The global search's batched cost: each curve's profiled cost and δα equal the least plain
    cost of the curve times exp(-2 da (z - z_ref)) over a grid of da, refined by the parabola
    through the grid's three lowest points."""
    rng = np.random.default_rng(11)
    y = _truth() * _trend(DA) + rng.normal(0.0, SIGMA, Z.size)
    sigma = np.full(Z.size, SIGMA)
    trended = normalization(INTERVAL, Z, y, sigma, extinction_bias=True)
    plain = normalization(INTERVAL, Z, y, sigma)
    curves = np.array(
        [
            lo.overlap(
                parameters.replace(TABLE1, {"beam.tilt[0]": t}), Z, "rt", tolerance=1e-8
            ).overlap
            for t in (2.5e-4, 3e-4, 3.5e-4)
        ]
    )
    step = 1e-8
    grid = np.arange(-EXTINCTION_BIAS_BOUND, EXTINCTION_BIAS_BOUND + step / 2, step)
    least, where = [], []
    for g in curves:
        cost = plain.whitened_cost(g[None, :] * np.exp(-2 * grid[:, None] * (Z - Z_REF)))
        i = int(np.argmin(cost))
        if i in (0, grid.size - 1):  # on the bound (a curve far from the data may need more)
            least.append(cost[i])
            where.append(grid[i])
            continue
        left, mid, right = cost[i - 1 : i + 2]
        curvature = (left - 2 * mid + right) / 2  # per step²
        shift = (left - right) / (4 * curvature)  # the parabola's vertex, in steps
        least.append(mid - curvature * shift**2)
        where.append(grid[i] + shift * step)
    assert trended.whitened_cost(curves) == pytest.approx(least, rel=GRID_AGREE)
    assert trended.bias(curves) == pytest.approx(where, abs=GRID_AGREE * EXTINCTION_BIAS_BOUND)


@pytest.mark.filterwarnings("ignore:fit. the model's tolerance")  # noise-free data
def test_command_line_extinction_bias(tmp_path, capsys, fit_inputs):
    scenario, data = fit_inputs(Z.tolist(), (_truth() * _trend(DA)).tolist())
    args = ["fit", str(scenario), str(data), "--free", *TRUE, "--out", str(tmp_path / "out")]
    assert main(args + ["--normalize", *map(str, INTERVAL), "--extinction-bias"]) == 0
    assert "retrieval extinction bias" in capsys.readouterr().out
    rows = (tmp_path / "out" / "table1_fit.csv").read_text().splitlines()
    row = next(r for r in rows if r.startswith("extinction_bias,"))
    assert abs(float(row.split(",")[1]) - DA) < SAME * EXTINCTION_BIAS_BOUND
    assert row.split(",")[3] == "1/m"
    assert main(args + ["--extinction-bias"]) == 1  # needs --normalize: a clear error
    assert "needs normalize" in capsys.readouterr().err


def test_ladder_carries_the_bias_in_every_family_and_counts_it():
    tilt = Family("tilt", ("beam.tilt[0]",), "pointing")
    tilt_focus = Family("tilt + focus", tuple(TRUE), "pointing, focus")
    y = _truth() * _trend(DA) + np.random.default_rng(5).normal(0.0, SIGMA, Z.size)
    problem = fit_problem(
        _start(), Z, y, SIGMA, free="auto",
        bounds={"beam.tilt[0]": (-1e-3, 1e-3), "detector.defocus": (-0.01, 0.02)}, method="rt",
        tolerance=1e-6, threads=1, normalize=INTERVAL, extinction_bias=True, seed=0,
    )  # fmt: skip
    r = fit_ladder(problem, families=(tilt, tilt_focus))
    assert r.chosen_family is tilt_focus
    for s in r.scores:
        assert s.k == len(s.family.paths) + 1
        n = s.fit.degrees_of_freedom + s.k  # independent points: n - 1 of the normalised data
        assert n == Z.size - 1
        assert s.bic == pytest.approx(s.fit.chi_square + s.k * math.log(n), rel=1e-12)
    assert abs(r.chosen.extinction_bias - DA) < 3 * r.chosen.extinction_bias_uncertainty
    assert "not the instrument" in str(r)


def test_profile_of_hostile_curves():
    """Curves the search may propose: zero or NaN over the interval cost inf (δα 0), a curve of
    1e300 is a shape like any other, and a pure exponential trend is taken out exactly."""
    z = np.linspace(100.0, 3000.0, 20)
    norm = normalization((1000.0, 3000.0), z, np.ones(20), np.full(20, 0.01), True)
    curves = np.array([np.zeros(20), np.full(20, np.nan), np.full(20, 1e300), np.exp(1e-4 * z)])
    with np.errstate(all="raise"):  # nothing escapes as a floating-point warning
        bias, cost = norm.bias(curves), norm.whitened_cost(curves)
    assert np.all(np.isfinite(bias)) and bias[:2].tolist() == [0.0, 0.0]
    assert cost[:2].tolist() == [np.inf, np.inf]
    assert bias[2] == pytest.approx(0.0, abs=1e-12) and cost[2] < 1e-12
    assert bias[3] == pytest.approx(5e-5, rel=1e-9) and cost[3] < 1e-12
