"""Reading series of overlap curves (one row per curve: a date, covariates, one column per range):
a written file read back exactly, the CHM15k Payerne file, and hostile files refused naming the
line and column."""

import math
from pathlib import Path

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.io.overlap_curves import read_overlap_curve

DATA = Path(__file__).resolve().parent.parent / "examples" / "data"
PAYERNE = DATA / "chm15k_payerne_daily_overlap.csv"
HEADER = "date,temperature_K,quality,150,300.5,450"
ROWS = [
    "2014-01-02,291.25,2,0.125,0.5,0.875",
    "2014-01-03,nan,0,0.25,0.625,1",
    "2014-01-05T12:30,300,3,0.1,0.4,0.9",
]


def _write(tmp_path, lines, name="series.csv"):
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_a_written_series_reads_back_exactly(tmp_path):
    rng = np.random.default_rng(3)
    z = np.array([14.985, 29.97, 1000.0, 2997.0])
    g = rng.uniform(-0.01, 1.1, (5, z.size))
    t = rng.uniform(270.0, 310.0, 5)
    dates = np.arange("2013-03-01", "2013-03-06", dtype="datetime64[D]")
    lines = ["date,internal_temperature_K," + ",".join(repr(float(v)) for v in z)]
    lines += [
        f"{d},{float(t[i])!r}," + ",".join(repr(float(v)) for v in g[i])
        for i, d in enumerate(dates)
    ]
    path = _write(tmp_path, ["# a comment line", *lines])
    s = lo.read_overlap_series(path)
    expected = lo.OverlapSeries(z, g, dates, {"internal_temperature_K": t}, str(path))
    assert s == expected
    assert np.array_equal(s.curves, g) and np.array_equal(s.ranges, z)  # repr round-trips floats
    assert s.dates.dtype == np.dtype("datetime64[s]") and len(s) == 5


def test_covariates_may_be_nan_and_dates_carry_a_time(tmp_path):
    s = lo.read_overlap_series(_write(tmp_path, [HEADER, *ROWS]))
    assert list(s.covariates) == ["temperature_K", "quality"]
    assert math.isnan(s.covariates["temperature_K"][1])
    assert s.dates[2] == np.datetime64("2014-01-05T12:30:00")
    assert s.ranges.tolist() == [150.0, 300.5, 450.0]


def test_select_within_and_the_dataset(tmp_path):
    s = lo.read_overlap_series(_write(tmp_path, [HEADER, *ROWS]))
    good = s.select(s.covariates["quality"] >= 1)
    assert len(good) == 2 and good.curves[:, 0].tolist() == [0.125, 0.1]
    assert good.covariates["temperature_K"].tolist() == [291.25, 300.0]
    near = s.within(100.0, 400.0)
    assert near.ranges.tolist() == [150.0, 300.5] and near.curves.shape == (3, 2)
    ds = s.to_dataset()
    assert ds.overlap.dims == ("date", "range") and np.array_equal(ds.overlap.values, s.curves)
    assert np.array_equal(ds.quality.values, s.covariates["quality"])
    with pytest.raises(ValueError, match="mask"):
        s.select([True, False])
    with pytest.raises(ValueError, match="no curve"):
        s.select(np.zeros(3, dtype=bool))
    with pytest.raises(ValueError, match="no range"):
        s.within(500.0, 600.0)


def test_the_value_cannot_be_changed(tmp_path):
    s = lo.read_overlap_series(_write(tmp_path, [HEADER, *ROWS]))
    with pytest.raises(ValueError):
        s.curves[0, 0] = 2.0
    with pytest.raises(ValueError):
        s.covariates["quality"][0] = 1.0
    with pytest.raises(TypeError):
        s.covariates["new"] = np.zeros(3)  # type: ignore[index]


def test_the_payerne_series_and_its_factory_curve():
    s = lo.read_overlap_series(PAYERNE)
    assert s.curves.shape == (153, 200) and list(s.covariates) == [
        "internal_temperature_K",
        "quality",
        "candidates",
    ]
    assert s.dates[0] == np.datetime64("2013-03-16") and s.dates[-1] == np.datetime64("2014-09-25")
    assert np.diff(s.ranges) == pytest.approx(np.full(199, 14.985), abs=1e-9)
    assert int((s.covariates["quality"] >= 1).sum()) == 142
    factory = read_overlap_curve(DATA / "chm15k_payerne_factory_overlap.csv")
    assert np.array_equal(factory.ranges, s.ranges)
    # beyond about 1 km the retrieval leaves every day at the factory curve (the data's README)
    far = s.ranges > 1200.0
    assert np.max(np.abs(s.curves[:, far] - factory.overlap[far])) < 1e-5


@pytest.mark.parametrize(
    "lines, match",
    [
        ([], "no header"),
        ([HEADER], "no data"),
        (["day,t,150,300"], "line 1, column 1: 'day'"),
        ([HEADER, "2014-01-02,291,2,0.1,0.5"], "line 2: 5 values, expected 6"),
        ([HEADER, "2014-01-02,291,2,0.1,0.5,0.8,0.9"], "line 2: 7 values"),
        ([HEADER, "2014-01-02,291,2,0,1,0,5,0,9"], "decimal comma"),
        (["date;t;150;300", "2014-01-02;291;0,1;0,5"], "column 1"),
        (["date,t,300,150", "2014-01-02,291,0.1,0.5"], "column 4: range 150 m does not follow"),
        (["date,t,150,150", "2014-01-02,291,0.1,0.5"], "no duplicates"),
        (["date,t,150,-3", "2014-01-02,291,0.1,0.5"], "range '-3'"),
        (["date,t,150,inf", "2014-01-02,291,0.1,0.5"], "range 'inf'"),
        (["date,t,150,300", "2014-01-02,291,0.1,nan"], r"line 2, column 4 \(300\).*finite"),
        (["date,t,150,300", "2014-01-02,291,0.1,٠.٥"], r"line 2, column 4 \(300\)"),
        (["date,t,150,300", "2014-01-02,２９１,0.1,0.5"], r"line 2, column 2 \(t\)"),
        (["date,t,150,300", "2014-01-02,2_91,0.1,0.5"], r"column 2 \(t\)"),
        (["date,t,150,300", "02.01.2014,291,0.1,0.5"], "line 2, column 1 \\(date\\)"),
        (["date,t,150,300", "2014-02-30,291,0.1,0.5"], "not a calendar date"),
        (
            ["date,t,150,300", "2014-01-02,291,0.1,0.5", "2014-01-01,291,0.1,0.5"],
            "line 3.*strictly increasing",
        ),
        (
            ["date,t,150,300", "2014-01-02,291,0.1,0.5", "2014-01-02,291,0.1,0.5"],
            "line 3.*strictly increasing",
        ),
        (["date,150,t", "2014-01-02,0.1,291"], "covariates come before the ranges"),
        (["date,t,t,150", "2014-01-02,1,2,0.1"], "column 3: 't'"),
        (["date,température,150", "2014-01-02,1,0.1"], "column 2"),
        (["date,t", "2014-01-02,1"], "no range columns"),
    ],
)
def test_hostile_files_are_refused_naming_line_and_column(tmp_path, lines, match):
    with pytest.raises(ValueError, match=match):
        lo.read_overlap_series(_write(tmp_path, lines))


def test_a_file_that_is_not_utf8_or_not_a_file_is_refused(tmp_path):
    bad = tmp_path / "latin1.csv"
    bad.write_bytes("date,t,150\n2014-01-02,1,0.1\n# é\n".encode("latin-1"))
    with pytest.raises(ValueError, match="not UTF-8"):
        lo.read_overlap_series(bad)
    with pytest.raises(ValueError, match="not a regular file"):
        lo.read_overlap_series(tmp_path)


def test_the_constructor_refuses_what_the_reader_refuses():
    z, g = [150.0, 300.0], [[0.1, 0.5], [0.2, 0.6]]
    dates = np.array(["2014-01-01", "2014-01-02"], dtype="datetime64[D]")
    with pytest.raises(ValueError, match="dates"):
        lo.OverlapSeries(z, g, dates[::-1])
    with pytest.raises(ValueError, match="dates"):
        lo.OverlapSeries(z, g, np.array([1.0, 2.0]))
    with pytest.raises(ValueError, match="curves has shape"):
        lo.OverlapSeries(z, [[0.1, 0.5, 0.7]], dates[:1])
    with pytest.raises(ValueError, match="one per curve"):
        lo.OverlapSeries(z, g, dates, {"t": [1.0]})
    with pytest.raises(ValueError, match="covariates key"):
        lo.OverlapSeries(z, g, dates, {"a b": [1.0, 2.0]})
    with pytest.raises(ValueError, match="curves"):
        lo.OverlapSeries(z, [[0.1, math.nan], [0.2, 0.6]], dates)
