"""lo.fit_series: one warm-started local fit per curve of a series. A synthetic series with a known
tilt per curve recovered within the stated uncertainties; a cluster, dask's threads and a plain
loop give the same bits; bad input refused by name before any fit runs."""

import math
import warnings

import numpy as np
import pytest
from test_studies import hide_dask

import lidar_overlap as lo
from lidar_overlap import parameters

pytest.importorskip("scipy")
pytest.importorskip("xarray")

Z = np.linspace(100.0, 1500.0, 30)
START = lo.instruments.chm15k(beam_offset=0.1, beam_tilt=-5e-5)
#: The series' true tilts (rad) and temperatures (K): the tilt falls by 1 urad/K, as on the
#: Payerne unit.
TEMPERATURE = np.array([281.0, 286.0, 290.0, 293.0, 297.0, 302.0])
TILT = -5e-5 - 1e-6 * (TEMPERATURE - 290.0)
SIGMA = 0.003
DATES = np.arange("2014-03-01", "2014-03-07", dtype="datetime64[D]")


def _series(seed=0, normalize=None):
    rng = np.random.default_rng(seed)
    truth = [parameters.replace(START, {"beam.tilt[0]": t}) for t in TILT]
    g = np.array([lo.overlap(s, Z, "rt", tolerance=1e-7).overlap for s in truth])
    g = g + rng.normal(0.0, SIGMA, g.shape)
    return g if normalize is None else 0.9 * g


def _fit(curves, **options):
    settings = dict(
        coords={"date": DATES, "internal_temperature_K": TEMPERATURE},
        sigma=SIGMA,
        free=["beam.tilt[0]"],
        method="rt",
        tolerance=1e-4,
    )
    settings.update(options)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.FitQualityWarning)
        return lo.fit_series(START, Z, curves, **settings)


def test_known_tilts_are_recovered_within_their_uncertainties():
    ds = _fit(_series(seed=1))
    assert ds.value.dims == ("date", "parameter") and list(ds.parameter.values) == ["beam.tilt[0]"]
    assert ds.unit.values.tolist() == ["rad"]
    assert np.array_equal(ds.internal_temperature_K.values, TEMPERATURE)
    assert np.array_equal(ds.date.values, DATES.astype("datetime64[ns]"))
    assert bool(ds.converged.all())
    pulls = (ds.value.values[:, 0] - TILT) / ds.uncertainty.values[:, 0]
    assert np.all(np.abs(pulls) < 4.0), pulls  # 6 curves at 4 sigma: by chance p ~ 4e-4
    # the noise is the stated sigma: chi-square of 29 degrees of freedom in its 0.1 %-99.9 % band
    assert np.all((ds.reduced_chi_square > 0.38) & (ds.reduced_chi_square < 2.0))
    assert np.allclose(ds.noise, SIGMA, rtol=1e-12)
    assert np.all(ds.rms < 1.5 * SIGMA)
    # the slope of the tilt against temperature: -1 urad/K within the fit's spread
    slope = np.polyfit(TEMPERATURE, ds.value.values[:, 0], 1)[0]
    assert slope == pytest.approx(-1e-6, abs=0.2e-6)


def test_a_cluster_dask_threads_and_a_loop_give_the_same_bits(client, monkeypatch):
    pytest.importorskip("dask")
    g = _series(seed=2, normalize=True)
    options = dict(normalize=(1000.0, 1500.0), chunk=2)
    here = _fit(g, **options)
    remote = _fit(g, client=client, **options)
    hide_dask(monkeypatch)
    loop = _fit(g, **options)
    assert (here.attrs["engine"], remote.attrs["engine"], loop.attrs["engine"]) == (
        "dask",
        "distributed",
        "loop",
    )
    for other in (remote, loop):
        for name in ("value", "uncertainty", "rms", "reduced_chi_square", "evaluations"):
            assert np.array_equal(here[name].values, other[name].values), name
        assert here.drop_attrs().identical(other.drop_attrs())
    pulls = (here.value.values[:, 0] - TILT) / here.uncertainty.values[:, 0]
    assert np.all(np.abs(pulls) < 4.0), pulls


def test_the_retrievals_extinction_bias_is_recovered_per_curve_with_its_uncertainty():
    """Relative curves whose retrieval assumed an extinction off by δα = 3e-5 /m (a factor
    exp(-2 δα z) before the normalisation, 8 % over the curve): each curve's δα in the dataset,
    within 4 of its stated sigmas, in 1/m; without extinction_bias the dataset has no such
    variable."""
    bias = 3e-5
    interval = (1000.0, 1500.0)
    inside = (Z >= interval[0]) & (Z <= interval[1])
    rng = np.random.default_rng(5)
    rows = []
    for tilt in TILT:
        g = lo.overlap(parameters.replace(START, {"beam.tilt[0]": tilt}), Z, "rt", tolerance=1e-7)
        biased = g.overlap * np.exp(-2.0 * bias * Z)
        rows.append(biased / biased[inside].mean() + rng.normal(0.0, SIGMA, Z.size))
    ds = _fit(np.array(rows), normalize=interval, extinction_bias=True)
    assert ds.extinction_bias.attrs["units"] == "1/m"
    pulls = (ds.extinction_bias.values - bias) / ds.extinction_bias_uncertainty.values
    assert np.all(np.abs(pulls) < 4.0), pulls
    assert np.all(ds.extinction_bias_uncertainty.values < bias / 3)  # resolved on each curve
    assert "extinction_bias" not in _fit(np.array(rows)[:2], coords=None, normalize=interval)


def test_without_coords_the_series_is_numbered():
    ds = _fit(_series()[:2], coords=None)
    assert ds.value.dims == ("curve", "parameter") and ds.curve.values.tolist() == [0, 1]


@pytest.mark.parametrize(
    "change, match",
    [
        (
            dict(coords={"date": DATES, "t": np.r_[TEMPERATURE[:5], math.nan]}),
            r"coords\['t'\]\[5\] = nan is invalid",
        ),
        (dict(coords={"date": DATES[:5]}), r"coords\['date'\] has shape \(5,\)"),
        (
            dict(coords={"date": np.r_[DATES[:5], np.datetime64("NaT")]}),
            r"coords\['date'\]\[5\] = NaT is invalid",
        ),
        (dict(coords=[1, 2]), "coords"),
        (dict(curves=np.ones(Z.size)), "one curve alone: lo.fit"),
        (dict(curves=np.ones((6, Z.size - 1))), r"curves has shape \(6, 29\)"),
        (dict(curves=np.full((6, Z.size), math.nan)), r"curves\[0, 0\] = nan"),
        (dict(sigma=np.ones(3)), r"sigma has shape \(3,\)"),
        (dict(sigma=0.0), r"sigma\[0, 0\] = 0.0"),
        (dict(sigma=-1e-300), "sigma"),
        (dict(free="auto"), "free = 'auto'"),
        (dict(free=["beam.nothing"]), "beam.nothing"),
        (dict(threads=2), "threads is set by fit_series"),
        (dict(search="global"), "search is set by fit_series"),
        (dict(chunk=0), "chunk"),
        (dict(chunk=2**70), "chunk"),
        (dict(client="localhost"), "client"),
        (dict(normalize=(5000.0, 6000.0)), "normalize"),
    ],
)
def test_bad_input_is_refused_by_name(change, match):
    arguments = dict(curves=np.ones((6, Z.size)) * 0.5)
    arguments.update(change)
    with pytest.raises(ValueError, match=match):
        _fit(**arguments)


def test_plot_series_draws_each_parameter_against_time_and_a_covariate():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from lidar_overlap.views.plotting import plot_series

    ds = _fit(_series(seed=1))
    (by_date,) = plot_series(ds)
    assert by_date.get_ylabel() == "beam.tilt[0] (µrad)" and by_date.get_xlabel() == "date"
    (by_t,) = plot_series(ds, against="internal_temperature_K")
    y, dy = ds.value.values[:, 0] * 1e6, ds.uncertainty.values[:, 0] * 1e6
    slope = np.polyfit(TEMPERATURE, y, 1, w=1 / dy)[0]
    assert by_t.get_legend().get_texts()[0].get_text() == f"slope {slope:.3g} µrad/K"
    with pytest.raises(ValueError, match="against = 'nothing'"):
        plot_series(ds, against="nothing")
    plt.close("all")


def test_the_warm_start_is_the_previous_fit_of_the_chunk_and_each_chunk_starts_cold():
    """chunk=1: every curve from the given system, as lo.fit alone; one chunk: the second curve
    from the first one's fitted system. Both bit for bit those independent calls."""
    g = _series(seed=3)[:2]
    options = dict(free=["beam.tilt[0]"], method="rt", tolerance=1e-4, threads=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.FitQualityWarning)
        first = lo.fit(START, Z, g[0], SIGMA, **options)
        cold = lo.fit(START, Z, g[1], SIGMA, **options)
        warm = lo.fit(parameters.replace(START, first.parameters), Z, g[1], SIGMA, **options)
    one_each = _fit(g, coords=None, chunk=1).value.values[:, 0]
    together = _fit(g, coords=None, chunk=2).value.values[:, 0]
    assert one_each.tolist() == [first.parameters["beam.tilt[0]"], cold.parameters["beam.tilt[0]"]]
    assert together.tolist() == [first.parameters["beam.tilt[0]"], warm.parameters["beam.tilt[0]"]]
