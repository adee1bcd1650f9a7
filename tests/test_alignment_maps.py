"""Alignment maps of many systems through Dask: each map bit for bit the single call's, the same on
a two-worker cluster, in threads and in a plain loop; bad arguments refused by name."""

import numpy as np
import pytest

import lidar_overlap as lo

xr = pytest.importorskip("xarray")

SYSTEMS = [
    lo.paper_table1(),
    lo.paper_table1(defocus=1e-3),
    lo.paper_table1(obstruction_radius=0.02),
    lo.LidarSystem(
        beam=lo.GaussianBeam(355e-9, 1e-3, offset=(0.1, 0.0), tilt=(-2e-4, 0.0)),
        telescope=lo.paper_table1().telescope,
        detector=lo.paper_table1().detector,
    ),
]
RANGES = np.geomspace(60.0, 2000.0, 4)
AXES = dict(tilt_x=np.linspace(-1e-4, 1e-4, 3), defocus=np.array([-5e-4, 0.0, 5e-4]))


def maps(**kw):
    return lo.alignment_maps(SYSTEMS, RANGES, tolerance=1e-3, **AXES, **kw)


def test_each_map_is_the_single_call():
    ds = maps()
    assert ds.overlap.dims == ("system", "tilt_x", "defocus", "range")
    for i, system in enumerate(SYSTEMS):
        one = lo.alignment_map(system, RANGES, tolerance=1e-3, **AXES)
        assert np.array_equal(ds.overlap.isel(system=i).values, one.overlap.values)
        assert np.array_equal(ds.error_estimate.isel(system=i).values, one.error_estimate.values)
    assert list(ds.system_value_defocus.values) == [0.0, 1e-3, 0.0, 0.0]
    assert list(ds.system_value_tilt_x.values) == [0.0, 0.0, 0.0, -2e-4]


def test_a_cluster_threads_and_a_loop_give_the_same_bits(client, monkeypatch):
    here, there = maps(), maps(client=client)
    assert there.attrs["engine"] == "distributed" and here.attrs["engine"] in ("dask", "loop")
    xr.testing.assert_identical(here.drop_attrs(), there.drop_attrs())
    import lidar_overlap.analysis.engines as engines

    monkeypatch.setattr(engines, "engine", lambda client: "loop")
    xr.testing.assert_identical(maps().drop_attrs(), here.drop_attrs())


@pytest.mark.parametrize(
    "systems, kw, message",
    [
        ([], {}, "^systems is invalid"),
        (SYSTEMS[0], {}, "^systems is invalid"),
        ("table1", {}, "^systems is invalid"),
        ([SYSTEMS[0], None], {}, "^systems is invalid"),
        (SYSTEMS, {"tilt_z": np.zeros(2)}, "^tilt_z is invalid: expected the axes"),
        (SYSTEMS, {"client": "cluster"}, "^client = 'cluster' is invalid"),
        (SYSTEMS, {"threads": -1}, "^threads = -1 is invalid"),
    ],
)
def test_bad_arguments_are_refused_by_name(systems, kw, message):
    axes = {k: v for k, v in AXES.items() if "tilt_z" not in kw}
    with pytest.raises(ValueError, match=message):
        lo.alignment_maps(systems, RANGES, **axes, **kw)


def test_a_system_whose_map_is_invalid_names_the_axis():
    with pytest.raises(ValueError, match=r"^defocus"):
        lo.alignment_maps(SYSTEMS, RANGES, tilt_x=AXES["tilt_x"], defocus=np.array([-2.0, 0.0]))
