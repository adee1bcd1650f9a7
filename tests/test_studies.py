"""Tolerance studies: the same members bit for bit on a cluster, in threads and in a plain loop,
whatever the chunking; percentiles and members as separate overlap calls give them; hostile input
refused by name."""

import math
import sys

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters

xr = pytest.importorskip("xarray")

SYSTEM = lo.paper_table1(obstruction_radius=0.02)
RANGES = np.geomspace(50.0, 2000.0, 8)
METHOD = lo.RT(tolerance=1e-4)
TOLERANCES = {
    "beam.tilt": ("normal", 0.0, 20e-6),
    "detector.defocus": ("normal", 0.0, 2e-4),
    "detector.offset[0]": ("uniform", -10e-6, 10e-6),
}


def study(**kw):
    args = dict(system=SYSTEM, distributions=TOLERANCES, n=24, ranges=RANGES, method=METHOD)
    args.update(kw)
    return lo.tolerance_study(
        args.pop("system"), args.pop("distributions"), args.pop("n"), args.pop("ranges"), **args
    )


def assert_same_study(a, b):
    """Every variable and coordinate bit for bit; attributes other than how it ran equal."""
    xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())
    ran = ("engine", "members_per_task")
    assert {k: v for k, v in a.attrs.items() if k not in ran} == {
        k: v for k, v in b.attrs.items() if k not in ran
    }


def hide_dask(monkeypatch):
    """``import dask`` raises ImportError from now on; xarray, which sees dask installed and imports
    dask.base itself, still finds that submodule loaded."""
    try:
        import dask.base  # noqa: F401
    except ImportError:
        return  # not installed: nothing to hide
    monkeypatch.setitem(sys.modules, "dask", None)


@pytest.fixture
def no_dask(monkeypatch):
    hide_dask(monkeypatch)


def test_cluster_threads_and_plain_loop_agree_bit_for_bit(client, monkeypatch):
    pytest.importorskip("dask")
    local = study()
    assert local.attrs["engine"] == "dask"
    remote = study(client=client, chunk=5)
    assert remote.attrs["engine"] == "distributed" and remote.attrs["members_per_task"] == 5
    hide_dask(monkeypatch)
    loop = study()
    assert loop.attrs["engine"] == "loop"
    assert_same_study(local, remote)
    assert_same_study(local, loop)
    assert local.overlap.shape == (24, RANGES.size) and local.value.shape == (24, 4)
    assert list(local.parameter.values) == [
        "beam.tilt[0]",
        "beam.tilt[1]",
        "detector.defocus",
        "detector.offset[0]",
    ]


def test_same_seed_same_result_whatever_the_chunks():
    a = study(seed=7)
    for chunk in (1, 5, 1000):
        assert_same_study(a, study(seed=7, chunk=chunk, threads=1 if chunk == 5 else 0))
    assert not np.array_equal(a.value.values, study(seed=8).value.values)
    assert a.attrs["n"] == 24 and a.attrs["seed"] == 7 and a.attrs["method"] == repr(METHOD)
    assert "detector.defocus: normal(0.0, 0.0002) offset" in a.attrs["distributions"]


def test_zero_spread_gives_the_system_itself():
    res = study(distributions={"detector.defocus": ("normal", 0.0, 0.0)}, n=5)
    g = lo.overlap(SYSTEM, RANGES, METHOD).overlap
    np.testing.assert_array_equal(res.overlap.values, np.broadcast_to(g, (5, RANGES.size)))
    np.testing.assert_array_equal(
        res.overlap_percentile.values, np.broadcast_to(g, (3, RANGES.size))
    )


def test_percentiles_and_members_are_those_of_separate_calls():
    sd = 1e-4
    res = study(
        distributions={"detector.defocus": ("normal", 1e-4, sd)},
        n=40,
        seed=3,
        percentiles=(0, 10, 50, 100),
    )
    drawn = parameters.get(SYSTEM, "detector.defocus") + np.random.default_rng(3).normal(
        1e-4, sd, 40
    )
    np.testing.assert_array_equal(
        res.value.values[:, 0], drawn
    )  # one Generator(seed), drawn up front
    np.testing.assert_array_equal(
        res.overlap_percentile.values, np.percentile(res.overlap.values, [0, 10, 50, 100], axis=0)
    )
    for i in (0, 17, 39):
        member = parameters.replace(SYSTEM, {"detector.defocus": float(drawn[i])})
        np.testing.assert_array_equal(
            res.overlap.values[i], lo.overlap(member, RANGES, METHOD).overlap
        )
    # defocus pushes full overlap outwards: the spread is real at near range and vanishes at far
    # range
    spread = res.overlap_percentile.values[-1] - res.overlap_percentile.values[0]
    assert spread[0] > 1e-3 and spread[-1] < 1e-3


def test_scipy_frozen_distributions_draw_offsets_from_the_same_generator():
    stats = pytest.importorskip("scipy.stats")
    res = study(distributions={"beam.tilt[1]": stats.norm(0.0, 20e-6)}, n=6, seed=5)
    np.testing.assert_array_equal(
        res.value.values[:, 0],
        stats.norm(0.0, 20e-6).rvs(size=6, random_state=np.random.default_rng(5)),
    )
    assert "scipy.stats.norm(0.0, 2e-05) offset" in res.attrs["distributions"]


def test_without_dask_a_loop_and_without_xarray_a_clear_message(no_dask, monkeypatch):
    assert study(n=3).attrs["engine"] == "loop"
    with pytest.raises(ValueError, match="client is given but dask.distributed is not installed"):
        monkeypatch.setitem(sys.modules, "distributed", None)
        study(n=3, client=object())
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(ImportError, match=r"pip install 'lidar-overlap\[io\]'"):
        study(n=3)


class _Draws:
    def __init__(self, values):
        self.values = values

    def rvs(self, size, random_state):
        return np.asarray(self.values, dtype=float)[:size]


@pytest.mark.parametrize(
    "kw, match",
    [
        (
            dict(distributions={"beam.bogus": ("normal", 0, 1e-6)}),
            r"distributions\['beam.bogus'\]: parameter",
        ),
        (
            dict(distributions={"detector.numerical_aperture": ("normal", 0, 0.01)}),
            "numerical_aperture is not set",
        ),
        (dict(distributions={}), "distributions = {} is invalid"),
        (dict(distributions=[("detector.defocus", ("normal", 0, 1))]), "distributions = "),
        (
            dict(distributions={"detector.defocus": ("normal", math.nan, 1e-4)}),
            r"distributions\['detector.defocus'\]",
        ),
        (dict(distributions={"detector.defocus": ("normal", 0.0, -1e-4)}), "expected sd >= 0"),
        (dict(distributions={"detector.defocus": ("uniform", 1e-4, 0.0)}), "expected low <= high"),
        (
            dict(distributions={"beam.tilt[0]": ("uniform", -1e308, 1e308)}),
            r"expected high - low within double range",
        ),
        (
            dict(distributions={"detector.defocus": ("gamma", 1.0, 2.0)}),
            r"distributions\['detector.defocus'\] = ",
        ),
        (
            dict(distributions={"detector.defocus": 1e-4}),
            r"distributions\['detector.defocus'\] = 0.0001 is invalid",
        ),
        (
            dict(
                distributions={
                    "beam.tilt": ("normal", 0, 1e-6),
                    "beam.tilt[1]": ("normal", 0, 1e-6),
                }
            ),
            "named twice",
        ),
        (
            dict(distributions={"detector.defocus": _Draws([0.0, 1e-4, math.nan, 0.0])}, n=4),
            r"member 2: detector.defocus = nan",
        ),
        (dict(distributions={"detector.defocus": _Draws([0.0])}, n=4), r"drew shape \(1,\)"),
        (
            dict(distributions={"detector.radius": _Draws([0.0, 0.0, 0.0, -1e-3])}, n=4),
            r"member 3: the draw detector.radius = -0.00055 .*invalid system",
        ),
        (
            dict(distributions={"telescope.obstruction_distance": _Draws([0.0, 60.0])}, n=2),
            r"member 1: ranges\[0\]",
        ),
        (dict(n=0), r"^n = 0 is invalid"),
        (dict(n=2**32), r"^n = 4294967296 is invalid: expected an integer from 1 to 10000000"),
        (dict(n=24.0), r"^n = 24.0 is invalid"),
        (dict(n=True), r"^n = True is invalid"),
        (dict(seed=-1), r"^seed = -1 is invalid"),
        (dict(chunk=0), r"^chunk = 0 is invalid"),
        (dict(threads=-1), r"^threads = -1 is invalid"),
        (dict(percentiles=(5, 101)), r"^percentiles = \(5, 101\) is invalid"),
        (dict(percentiles=(5, math.nan)), r"^percentiles = .* is invalid"),
        (dict(percentiles=()), r"^percentiles = \(\) is invalid"),
        (dict(percentiles=5), r"^percentiles = 5 is invalid"),
        (dict(percentiles="50"), r"^percentiles = '5' is invalid"),
        (dict(ranges=[]), r"^ranges has shape"),
        (dict(ranges=[100.0, math.nan]), r"^ranges\[1\] = nan"),
        (dict(method="bogus"), r"method = 'bogus'"),
        (dict(method=lo.Turbulent(lo.Turbulence(1e-14), "rt")), r"method = Turbulent"),
        (dict(system="table1"), r"^system = 'table1' is invalid"),
        (dict(client="tcp://localhost:8786"), r"^client = 'tcp://localhost:8786' is invalid"),
    ],
)
def test_hostile_inputs_are_refused_naming_the_argument(kw, match):
    with pytest.raises(ValueError, match=match):
        study(**kw)


def test_memory_is_checked_before_drawing():
    budget = lo.max_memory()
    lo.set_max_memory(2**20)
    try:
        with pytest.raises(
            ValueError, match=r"^n = 100000 needs .* lower n or the number of ranges"
        ):
            study(n=100_000)
    finally:
        lo.set_max_memory(budget)
