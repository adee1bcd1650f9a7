"""Results are values: read-only arrays, checked on construction up to a fixed round-off (not the
stated error), pickled through the constructor, and written and read back exactly or not at all."""

from __future__ import annotations

import dataclasses
import os
import pickle

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.forward.result import ROUND_OFF

Z = np.array([150.0, 400.0, 1200.0, 3000.0])


def _result(**changes) -> lo.OverlapResult:
    fields = dict(
        ranges=Z,
        overlap=[0.1, 0.5, 0.9, 1.0],
        method="rt",
        error_estimate=[1e-6] * 4,
        system=lo.paper_table1(),
        tolerance=1e-4,
    )
    return lo.OverlapResult(**{**fields, **changes})


# --------------------------------------------------------------------------- construction
@pytest.mark.parametrize(
    "error, tolerance",
    [([1e300], float("nan")), ([float("nan")], 1e300), ([0.5], 0.5)],
)
def test_a_large_stated_error_does_not_widen_what_is_clipped(error, tolerance):
    with pytest.raises(ValueError, match=r"overlap\[0\] = 42.0"):
        lo.OverlapResult([100.0], [42.0], "rt", error, None, tolerance)
    with pytest.raises(ValueError, match=r"overlap\[0\] = -7.0"):
        lo.OverlapResult([100.0], [-7.0], "rt", error, None, tolerance)


def test_round_off_is_clipped_and_more_is_refused():
    r = _result(overlap=[-0.5 * ROUND_OFF, 0.5, 0.9, 1.0 + 0.5 * ROUND_OFF])
    assert r.overlap[0] == 0.0 and r.overlap[-1] == 1.0
    with pytest.raises(ValueError, match="overlap"):
        _result(overlap=[-3 * ROUND_OFF, 0.5, 0.9, 1.0])


def test_arrays_are_read_only_copies():
    mine = np.array([0.1, 0.5, 0.9, 1.0])
    r = _result(overlap=mine)
    mine[0] = 0.7  # the caller's array stays the caller's
    assert r.overlap[0] == 0.1 and mine.flags.writeable
    for name in ("ranges", "overlap", "error_estimate"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(r, name)[0] = 3.0


@pytest.mark.parametrize(
    "name, value",
    [
        ("overlap", [0.1j, 0.5, 0.9, 1.0]),
        ("overlap", ["0.1", "0.5", "0.9", "1.0"]),
        ("overlap", [True, False, True, True]),
        ("ranges", np.array([150, 400, 1200, 3000], dtype=complex)),
        ("error_estimate", [None] * 4),
    ],
)
def test_arrays_take_real_numbers_only(name, value):
    with pytest.raises(ValueError, match=name):
        _result(**{name: value})


def test_a_result_changed_behind_its_back_is_not_written(tmp_path):
    r = _result()
    forged = r.overlap.copy()
    forged[1] = 3.0
    object.__setattr__(r, "overlap", forged)
    with pytest.raises(ValueError, match="overlap"):
        r.to_csv(tmp_path / "r.csv")
    assert not (tmp_path / "r.csv").exists()


# --------------------------------------------------------------------------- pickling
def test_pickles_round_trip_and_are_checked_again():
    r = _result()
    assert pickle.loads(pickle.dumps(r)) == r
    forged = pickle.dumps(r).replace(
        np.array([0.1, 0.5, 0.9, 1.0]).tobytes(), np.array([0.1, 0.5, 0.9, 7.0]).tobytes()
    )
    with pytest.raises(ValueError, match="overlap"):
        pickle.loads(forged)


def test_turbulent_results_pickle_and_check_their_draws():
    samples = np.array([[0.2, 0.6, 0.9, 1.0], [0.4, 0.8, 0.9, 1.0]])
    t = lo.TurbulentOverlapResult(
        Z,
        samples.mean(axis=0),
        "fo",
        samples.std(axis=0) / 2,
        None,
        float("nan"),
        "standard_error",
        realizations=samples,
        std=samples.std(axis=0),
        low=samples.min(axis=0),
        high=samples.max(axis=0),
    )
    assert pickle.loads(pickle.dumps(t)) == t
    assert not t.realizations.flags.writeable
    with pytest.raises(ValueError, match="realizations"):
        dataclasses.replace(t, realizations=samples * 7.0)
    with pytest.raises(ValueError, match="std"):
        dataclasses.replace(t, std=-t.std - 1.0)


def test_masked_systems_and_masks_pickle():
    mask = lo.ApertureMask.quadrants() if hasattr(lo.ApertureMask, "quadrants") else None
    if mask is None:
        mask = lo.ApertureMask.sectors(4)
    system = lo.paper_table1()
    masked = dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, mask=mask))
    assert pickle.loads(pickle.dumps(mask)) == mask
    assert pickle.loads(pickle.dumps(masked)) == masked


# --------------------------------------------------------------------------- files
def test_csv_round_trip_is_exact(tmp_path):
    r = _result()
    r.to_csv(tmp_path / "r.csv", {"station": "Granada", "shots": 3000, "gain": 1.5})
    back = lo.OverlapResult.from_csv(tmp_path / "r.csv")
    assert back == r


@pytest.mark.parametrize(
    "attrs, key",
    [
        ({"method": "fo"}, "method"),
        ({"tolerance": 0.5}, "tolerance"),
        ({"beam_wavelength_m": 532e-9}, "beam_wavelength_m"),
        ({"system": "x"}, "system"),
        ({"format": "x"}, "format"),
        ({"bad key": 1}, "bad key"),
        ({"note": "two\nlines"}, "note"),
        ({"note": "42"}, "note"),
        ({"flag": True}, "flag"),
        ({"gain": float("nan")}, "gain"),
    ],
)
def test_callers_attrs_cannot_replace_or_garble_the_header(tmp_path, attrs, key):
    with pytest.raises(ValueError, match="attrs"):
        _result().to_csv(tmp_path / "r.csv", attrs)
    assert not (tmp_path / "r.csv").exists()


def test_header_lines_count_only_before_the_data(tmp_path):
    path = tmp_path / "r.csv"
    _result().to_csv(path)
    text = path.read_text()
    for tail in ("# method: fo\n", "# tolerance: 0.5\n", "# note\n"):
        path.write_text(text.replace("# rows: 4\n", tail + "# rows: 4\n"))
        with pytest.raises(ValueError, match="before the columns"):
            lo.OverlapResult.from_csv(path)
    path.write_text(text.replace("# method: rt\n", "# method: rt\n# method: fo\n"))
    with pytest.raises(ValueError, match="twice"):
        lo.OverlapResult.from_csv(path)


def test_a_large_tolerance_in_a_file_does_not_hide_a_bad_g(tmp_path):
    path = tmp_path / "r.csv"
    lo.OverlapResult(Z, [0.1, 0.5, 0.9, 1.0], "rt", [0.0] * 4, None, 0.0).to_csv(path)
    text = path.read_text().replace("# tolerance: 0.0", "# tolerance: 1e300")
    path.write_text(text.replace("\n400.0,0.5,", "\n400.0,-7.0,"))
    with pytest.raises(ValueError, match=r"overlap\[1\] = -7.0"):
        lo.OverlapResult.from_csv(path)


@pytest.mark.parametrize(
    "edit",
    [
        lambda t: t.replace("telescope_diameter_m: ", "telescope_diameter_m: x"),
        lambda t: "\n".join(line for line in t.split("\n") if "detector_radius_m" not in line),
        lambda t: t.replace("beam_type: gaussian", "beam_type: banana"),
        lambda t: t.replace("beam_wavelength_m: ", "beam_wavelength_m: -"),
    ],
)
def test_a_corrupt_system_header_is_an_error_not_a_missing_system(tmp_path, edit):
    path = tmp_path / "r.csv"
    _result().to_csv(path)
    path.write_text(edit(path.read_text()))
    with pytest.raises(ValueError, match="r.csv"):
        lo.OverlapResult.from_csv(path)


def test_a_result_without_a_system_reads_back_without_one(tmp_path):
    path = tmp_path / "r.csv"
    _result(system=None).to_csv(path)
    assert lo.OverlapResult.from_csv(path).system is None


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs")
def test_readers_refuse_a_fifo_instead_of_waiting(tmp_path):
    fifo = tmp_path / "fifo.csv"
    os.mkfifo(fifo)
    with pytest.raises(ValueError, match="not a regular file"):
        lo.OverlapResult.from_csv(fifo)
    pytest.importorskip("xarray")
    with pytest.raises(ValueError, match="not a regular file"):
        lo.OverlapResult.from_netcdf(fifo)


def test_from_netcdf_says_what_is_wrong_in_its_own_words(tmp_path):
    pytest.importorskip("xarray")
    text = tmp_path / "text.nc"
    text.write_text("range_m,overlap\n1,0.5\n")
    with pytest.raises(ValueError, match="text.nc: not a readable NetCDF file"):
        lo.OverlapResult.from_netcdf(text)
    good = tmp_path / "good.nc"
    _result().to_netcdf(good)
    truncated = tmp_path / "truncated.nc"
    truncated.write_bytes(good.read_bytes()[: good.stat().st_size // 2])
    with pytest.raises(ValueError, match="truncated.nc"):
        lo.OverlapResult.from_netcdf(truncated)
    assert lo.OverlapResult.from_netcdf(good) == _result()
    with pytest.raises(ValueError, match="attrs"):
        _result().to_netcdf(tmp_path / "x.nc", {"history": "none"})


@pytest.mark.parametrize("method", ["banana", "auto", "", None, 3])
def test_a_result_names_the_model_it_came_from(method):
    with pytest.raises(ValueError, match=r"^method = .* expected the model"):
        _result(method=method)


def test_a_result_within_the_obstruction_distance_is_refused():
    system = lo.paper_table1(obstruction_radius=0.02)  # obstruction at 0.7 m (Table 1's spider)
    d = system.telescope.obstruction_distance
    assert d > 0
    with pytest.raises(ValueError, match="obstruction"):
        _result(ranges=[0.5 * d, 400.0, 1200.0, 3000.0], system=system)
    with pytest.raises(ValueError, match="system = 'x' is invalid"):
        _result(system="x")


def test_a_two_way_amplification_is_nan_only_where_no_light_comes_back():
    z = np.array([100.0, 200.0])
    rows = np.array([[0.0, 0.4], [0.0, 0.6]])
    fields = dict(
        ranges=z,
        overlap=rows.mean(axis=0),
        method="fo",
        error_estimate=[0.0, 0.1],
        system=None,
        tolerance=float("nan"),
        error_kind="standard_error",
        realizations=rows,
        paths="both",
        uncorrelated=rows,
    )
    dark = lo.TurbulentOverlapResult(**fields, amplification=[float("nan"), 1.0])
    assert np.isnan(dark.amplification[0])
    with pytest.raises(ValueError, match=r"amplification\[1\] = nan at range 200.0 m"):
        dataclasses.replace(dark, amplification=[float("nan"), float("nan")])
