"""Turbulence realisations through Dask: bit for bit lo.overlap's turbulent result on the FO and RT
paths, on a two-worker cluster, in threads and in a plain loop, whatever the chunking; the
statistics those of NumPy on the samples; the core's first_realization and hostile input refused by
name."""

import dataclasses
import importlib
import math
import sys
import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core

xr = pytest.importorskip("xarray")

SYSTEM = lo.paper_table1()
RANGES = np.geomspace(100.0, 3000.0, 5)
TURBULENCE = lo.Turbulence(1e-14)
METHODS = {
    # FO on the beam's path (its grid too coarse for the return path's); RT on both paths (the
    # default): the correlated and the uncorrelated draws split as the whole run's
    "fo": lo.Turbulent(
        TURBULENCE, lo.FO(beam_grid=64), realizations=7, seed=11, screens=3, paths="transmit"
    ),
    "rt": lo.Turbulent(TURBULENCE, lo.RT(tolerance=1e-4), realizations=40, seed=3),
}
STATISTICS = {
    "overlap": "realizations",
    "mean": "overlap",
    "standard_error": "error_estimate",
    "std": "std",
    "low": "low",
    "high": "high",
}
RAN = ("engine", "realizations_per_task")


def study(path="fo", **kw):
    system, ranges, method = (
        kw.pop("system", SYSTEM),
        kw.pop("ranges", RANGES),
        kw.pop("method", METHODS[path]),
    )
    return lo.turbulent_realizations(system, ranges, method, **kw)


def same_bits(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def assert_same(a, b):
    """Every variable and coordinate bit for bit; attributes other than how it ran equal."""
    for name in list(a.data_vars) + list(a.coords):
        assert same_bits(a[name].values, b[name].values), name
    xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())
    assert {k: v for k, v in a.attrs.items() if k not in RAN} == {
        k: v for k, v in b.attrs.items() if k not in RAN
    }


def assert_is_overlap(ds, res):
    for name, field in STATISTICS.items():
        assert same_bits(ds[name].values, getattr(res, field)), name
    assert same_bits(ds.range.values, res.ranges)


def hide_dask(monkeypatch):
    """``import dask`` raises ImportError from now on (xarray keeps the submodules it loaded)."""
    try:
        importlib.import_module("dask.base")
    except ImportError:
        return
    monkeypatch.setitem(sys.modules, "dask", None)


@pytest.fixture(scope="module")
def single():
    """lo.overlap's result on each path: the reference."""
    return {path: lo.overlap(SYSTEM, RANGES, method) for path, method in METHODS.items()}


@pytest.mark.parametrize("path", ["fo", "rt"])
@pytest.mark.parametrize("chunk, threads", [(None, 0), (1, 0), (3, 1), (4, 0), (1000, 0)])
def test_bit_for_bit_lo_overlap_whatever_the_chunks(single, path, chunk, threads):
    ds = study(path, chunk=chunk, threads=threads)
    assert_is_overlap(ds, single[path])
    k = METHODS[path].realizations
    if chunk is not None:
        assert ds.attrs["realizations_per_task"] == chunk
    assert ds.overlap.dims == ("realization", "range") and list(ds.realization.values) == list(
        range(k)
    )
    assert (
        ds.attrs["model"] == path
        and ds.attrs["seed"] == METHODS[path].seed
        and ds.attrs["realizations"] == k
    )
    assert ds.attrs["method"] == repr(METHODS[path]) and ds.attrs["error_kind"] == "standard_error"


@pytest.mark.parametrize("path", ["fo", "rt"])
def test_a_cluster_threads_and_a_loop_give_the_same_bits(client, monkeypatch, single, path):
    pytest.importorskip("dask")
    here = study(path)
    assert here.attrs["engine"] == "dask"
    there = study(path, client=client)
    small = study(path, client=client, chunk=3)  # parts that start and end inside pairs of screens
    assert (
        there.attrs["engine"] == small.attrs["engine"] == "distributed"
        and small.attrs["realizations_per_task"] == 3
    )
    hide_dask(monkeypatch)
    loop, loop_chunks = study(path), study(path, chunk=2, threads=1)
    assert loop.attrs["engine"] == loop_chunks.attrs["engine"] == "loop"
    assert loop.attrs["realizations_per_task"] == METHODS[path].realizations
    for other in (there, small, loop, loop_chunks):
        assert_same(here, other)
    assert_is_overlap(there, single[path])


@pytest.mark.parametrize("path", ["fo", "rt"])
def test_statistics_are_numpy_on_the_samples(path):
    ds = study(path, chunk=2)
    g = ds.overlap.values
    k = g.shape[0]
    np.testing.assert_array_equal(ds["mean"].values, g.mean(axis=0))
    np.testing.assert_array_equal(ds["std"].values, g.std(axis=0, ddof=1))
    np.testing.assert_allclose(
        ds.standard_error.values, g.std(axis=0, ddof=1) / math.sqrt(k), rtol=1e-15, atol=0
    )
    np.testing.assert_array_equal(
        np.stack([ds.low.values, ds.high.values]), np.percentile(g, [5, 95], axis=0)
    )
    assert (ds.low.attrs["percentile"], ds.high.attrs["percentile"]) == (5.0, 95.0)
    # The 5th percentile of 7 samples lies below their mean; where the samples agree to round-off
    # (the first ranges, before turbulence spreads them) their summed mean may fall ulps below them.
    mean = ds["mean"].values
    assert np.all(ds["std"].values[2:] > 0)
    assert np.all(ds.low.values <= mean + 8 * np.finfo(float).eps * np.abs(mean))
    assert ds.range.attrs["units"] == "m" and all(ds[v].attrs["units"] == "1" for v in STATISTICS)


def test_without_turbulence_every_draw_is_the_plain_curve():
    calm = lo.Turbulent(lo.Turbulence(0.0), lo.RT(tolerance=1e-4), realizations=3)
    ds = study(method=calm, chunk=1)
    plain = lo.overlap(SYSTEM, RANGES, lo.RT(tolerance=1e-4)).overlap
    assert same_bits(ds.overlap.values, np.tile(plain, (3, 1))) and same_bits(
        ds["std"].values, np.zeros(RANGES.size)
    )
    assert_is_overlap(ds, lo.overlap(SYSTEM, RANGES, calm))
    assert ds.attrs["engine"] == "loop"


def test_rt_warnings_are_lo_overlaps_once():
    """RT's convergence warning counts every draw, as lo.overlap's, however the draws were split."""
    short = lo.Turbulent(
        TURBULENCE,
        lo.RT(tolerance=1e-9, max_segments=1),
        realizations=6,
        seed=1,
        paths="transmit",  # one warning, not also the return path's regime
    )
    with warnings.catch_warnings(record=True) as single:
        warnings.simplefilter("always")
        res = lo.overlap(SYSTEM, RANGES, short)
    with warnings.catch_warnings(record=True) as split:
        warnings.simplefilter("always")
        ds = study(method=short, chunk=4)
    assert [str(w.message) for w in split] == [str(w.message) for w in single] and len(single) == 1
    assert "of 30 ranges" in str(single[0].message) and split[0].filename == __file__
    assert_is_overlap(ds, res)


def test_a_draw_the_model_cannot_trace_fails_as_in_lo_overlap(client):
    tilted = dataclasses.replace(
        SYSTEM, beam=dataclasses.replace(SYSTEM.beam, tilt=(1.0, 0.0), offset=(0.01, 0.0))
    )
    method = lo.Turbulent(TURBULENCE, "rt", realizations=4)
    with pytest.raises(ValueError) as single:
        lo.overlap(tilted, [1e10], method)
    # from this process, from threads and from a cluster's workers: every task fails, the first in
    # order is said
    for kw in ({}, {"chunk": 1}, {"chunk": 1, "client": client}):
        with pytest.raises(ValueError) as split:
            study(system=tilted, ranges=[1e10], method=method, **kw)
        assert str(split.value) == str(single.value) and str(split.value).startswith(
            "ranges[0] = 10000000000.0 m"
        )


def test_the_core_refuses_a_first_realization_beyond_the_run_by_name():
    options = dict(realizations=3, screens=1, beam_grid=32, threads=1)
    args = (SYSTEM._native, [1000.0], TURBULENCE._native)
    for first in (999_998, 10**6, 2**64 - 1):
        with pytest.raises(
            ValueError,
            match=r"^first_realization = .* is invalid: expected an index from 0 to 999997 "
            r"\(first_realization \+ realizations <= 1000000\)",
        ):
            _core.overlap_fo_turbulent(
                *args, _core.TurbulenceOptions(first_realization=first, **options)
            )
    with pytest.raises(TypeError):
        _core.TurbulenceOptions(first_realization=-1)
    last = _core.overlap_fo_turbulent(
        *args, _core.TurbulenceOptions(first_realization=999_997, **options)
    )
    assert np.asarray(last.overlap).shape == (3, 1)


def test_without_dask_a_loop_and_without_xarray_a_clear_message(monkeypatch):
    hide_dask(monkeypatch)
    assert study(chunk=4).attrs["engine"] == "loop"
    monkeypatch.setitem(sys.modules, "distributed", None)
    with pytest.raises(ValueError, match=r"client is given but dask.distributed is not installed"):
        study(client=object())
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(
        ImportError, match=r"turbulent_realizations .* pip install 'lidar-overlap\[io\]'"
    ):
        study()


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(chunk=0), r"^chunk = 0 is invalid: expected an integer from 1 to 1000000$"),
        (dict(chunk=-1), r"^chunk = -1 is invalid: expected an integer from 1 to 1000000$"),
        (
            dict(chunk=2**64),
            r"^chunk = 18446744073709551616 is invalid: expected an integer from 1 to 1000000$",
        ),
        (dict(chunk=math.nan), r"^chunk = nan is invalid: expected an integer"),
        (dict(chunk=2.0), r"^chunk = 2.0 is invalid"),
        (dict(chunk=True), r"^chunk = True is invalid"),
        (dict(chunk="2"), r"^chunk = '2' is invalid"),
        (dict(threads=-1), r"^threads = -1 is invalid"),
        (dict(threads=2**64), r"^threads = 18446744073709551616 is invalid"),
        (
            dict(client="tcp://localhost:8786"),
            r"^client = 'tcp://localhost:8786' is invalid: expected a "
            r"dask.distributed.Client or None",
        ),
        (dict(client=42), r"^client = 42 is invalid"),
        (dict(method="rt"), r"^method = 'rt' is invalid: expected a lidar_overlap.Turbulent"),
        (dict(method=lo.RT()), r"^method = RT\(.* is invalid: expected a lidar_overlap.Turbulent"),
        (dict(system="table1"), r"^system = 'table1' is invalid: expected a LidarSystem"),
        (dict(ranges=[]), r"^ranges has shape"),
        (dict(ranges=[100.0, math.nan]), r"^ranges\[1\] = nan"),
        (
            dict(method=lo.Turbulent(TURBULENCE, "fo", realizations=2 * 10**6)),
            r"^realizations = 2000000 is invalid: expected a count from 1 to 1000000",
        ),
        (
            dict(
                method=lo.Turbulent(TURBULENCE, "rt", realizations=10**6),
                ranges=np.arange(1.0, 100001.0),
            ),
            r"^realizations = 1000000 needs .* \(max_memory\)",
        ),
    ],
)
def test_hostile_inputs_are_refused_naming_the_argument(kw, match):
    with pytest.raises(ValueError, match=match):
        study(**kw)
