"""OverlapResult files: CSV and NetCDF round trips are exact (ranges, G, error estimates, method,
tolerance), the files carry units and the system description, a Gaussian system is rebuilt from the
attributes, a missing xarray gives an ImportError saying what to install; a file appears only once
complete (a full disk leaves nothing, or the previous file), and files with NaN or out-of-range
values are refused."""

import dataclasses
import errno
import math
import os
import stat
import sys

import numpy as np
import pytest

import lidar_overlap as lo

pytest.importorskip("xarray")
RANGES = np.geomspace(5.0, 1000.0, 50)


def _biaxial():
    system = lo.paper_table1(
        obstruction_radius=0.02, defocus=3e-3, divergence=0.2e-3, width_law="linear"
    )
    beam = dataclasses.replace(system.beam, offset=(0.1, -0.01), tilt=(-0.3e-3, 1e-5))
    detector = dataclasses.replace(system.detector, numerical_aperture=0.22, offset=(1e-5, 0.0))
    return dataclasses.replace(system, beam=beam, detector=detector)


@pytest.fixture(scope="module")
def results():
    # The aberrated ray fan stops ~2e-4 short of convergence here: a 1e-4 tolerance would warn.
    return {
        "rt": lo.overlap(lo.paper_table1(), RANGES, method="rt"),
        "fo": lo.overlap(lo.paper_table1(obstruction_radius=0.02), RANGES[20::4], method="fo"),
        "biaxial": lo.overlap(_biaxial(), RANGES, method="rt", tolerance=1e-6),
        "aberrated": lo.overlap(_aberrated(), RANGES[20::8], method="rt", tolerance=1e-3),
    }


def _aberrated():
    aberrations = lo.Aberrations(zernike={6: 0.2e-6, 11: 0.3e-6}, w222=0.1e-6, field_radius=0.45e-3)
    base = lo.paper_table1()
    return dataclasses.replace(
        base, telescope=dataclasses.replace(base.telescope, aberrations=aberrations)
    )


def _assert_same(read, original, system_too=True):
    assert np.array_equal(read.ranges, original.ranges)
    assert np.array_equal(read.overlap, original.overlap)
    assert np.array_equal(read.error_estimate, original.error_estimate, equal_nan=True)
    assert read.method == original.method
    assert read.tolerance == original.tolerance or (
        math.isnan(read.tolerance) and math.isnan(original.tolerance)
    )
    if system_too:
        assert read.system == original.system


@pytest.mark.parametrize("key", ["rt", "fo", "biaxial", "aberrated"])
def test_csv_round_trip_is_exact(results, key, tmp_path):
    path = tmp_path / "g.csv"
    results[key].to_csv(path)
    _assert_same(lo.OverlapResult.from_csv(path), results[key])


@pytest.mark.parametrize("key", ["rt", "fo", "biaxial", "aberrated"])
def test_netcdf_round_trip_is_exact(results, key, tmp_path):
    path = tmp_path / "g.nc"
    results[key].to_netcdf(path)
    _assert_same(lo.OverlapResult.from_netcdf(path), results[key])


def test_csv_layout(results, tmp_path):
    path = tmp_path / "g.csv"
    results["rt"].to_csv(path, attrs={"scenario": "unit test"})
    lines = path.read_text().splitlines()
    header = dict(line[2:].split(": ", 1) for line in lines if line.startswith("# "))
    assert header["method"] == "rt" and float(header["tolerance"]) == 1e-4
    assert header["scenario"] == "unit test"
    assert (
        float(header["beam_wavelength_m"]) == 355e-9
        and float(header["detector_radius_m"]) == 0.45e-3
    )
    columns = [line for line in lines if not line.startswith("#")]
    assert columns[0] == "range_m,overlap,error_estimate"
    assert len(columns) == 1 + RANGES.size
    assert float(columns[1].split(",")[1]) == results["rt"].overlap[0]


def test_xarray_dataset_units_and_attributes(results):
    ds = results["biaxial"].to_xarray()
    assert ds["range"].attrs["units"] == "m"
    assert ds["range"].attrs["long_name"] == "range from the transmitting plane"
    assert ds["overlap"].attrs == {
        **ds["overlap"].attrs,
        "units": "1",
        "long_name": "lidar overlap function",
    }
    assert ds["error_estimate"].attrs["units"] == "1"
    a = ds.attrs
    assert a["Conventions"] == "CF-1.10" and lo.__version__ in a["history"] and a["title"]
    assert a["method"] == "rt" and a["tolerance"] == 1e-6
    system = _biaxial()
    expected = {
        "beam_wavelength_m": 355e-9,
        "beam_waist_radius_m": 1e-3,
        "beam_divergence_rad": 0.2e-3,
        "beam_offset_x_m": 0.1,
        "beam_offset_y_m": -0.01,
        "beam_tilt_x_rad": -0.3e-3,
        "beam_tilt_y_rad": 1e-5,
        "telescope_diameter_m": 0.15,
        "telescope_focal_length_m": 1.0,
        "telescope_obstruction_radius_m": 0.02,
        "telescope_obstruction_distance_m": 0.7,
        "detector_radius_m": system.detector.radius,
        "detector_defocus_m": 3e-3,
        "detector_offset_x_m": 1e-5,
        "detector_numerical_aperture": 0.22,
        "detector_fov_rad": system.fov,
    }
    for key, value in expected.items():
        assert isinstance(a[key], float) and a[key] == value, key
    assert a["beam_type"] == "gaussian" and a["beam_width_law"] == "linear"


def test_netcdf_attributes_survive_the_file(results, tmp_path):
    import xarray as xr

    path = tmp_path / "g.nc"
    results["rt"].to_netcdf(path, attrs={"scenario": "unit test"})
    with xr.open_dataset(path) as ds:
        assert ds.attrs["scenario"] == "unit test" and ds.attrs["Conventions"] == "CF-1.10"
        assert ds["overlap"].attrs["units"] == "1" and ds["range"].attrs["units"] == "m"
        assert ds.attrs["telescope_diameter_m"] == 0.15
        assert "beam_divergence_rad" not in ds.attrs  # None (diffraction-limited): left out
        assert ds["overlap"].dtype == np.float64


def test_flat_top_is_described_and_not_rebuilt(tmp_path):
    beam = lo.FlatTopBeam(
        355e-9, 1e-3, 0.36e-3, grid=256, samples_per_waist=6.0, offset=(0.05, 0.0)
    )
    system = lo.LidarSystem(
        beam=beam, telescope=lo.Telescope(0.15, 1.0), detector=lo.Detector(0.45e-3)
    )
    res = lo.overlap(system, [200.0, 1000.0], method="fo")
    a = res.to_xarray().attrs
    assert a["beam_type"] == "flat_top" and a["beam_angular_diameter_rad"] == 0.36e-3
    assert a["beam_grid_size"] == 256 and a["beam_offset_x_m"] == 0.05
    res.to_netcdf(tmp_path / "f.nc")
    res.to_csv(tmp_path / "f.csv")
    for read in (
        lo.OverlapResult.from_netcdf(tmp_path / "f.nc"),
        lo.OverlapResult.from_csv(tmp_path / "f.csv"),
    ):
        _assert_same(read, res, system_too=False)
        assert read.system is None
        with pytest.warns(
            RuntimeWarning, match="still rising"
        ):  # two ranges cannot show the far-range limit
            assert read.full_overlap_range() == res.full_overlap_range()


def test_missing_xarray_says_what_to_install(results, monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "xarray", None)
    for call in (
        results["rt"].to_xarray,
        lambda: results["rt"].to_netcdf(tmp_path / "g.nc"),
        lambda: lo.OverlapResult.from_netcdf(tmp_path / "g.nc"),
    ):
        with pytest.raises(ImportError, match=r"pip install 'lidar-overlap\[io\]'"):
            call()
    results["rt"].to_csv(tmp_path / "g.csv")  # CSV needs nothing extra
    assert not (tmp_path / "g.nc").exists()


def test_not_a_result_file(tmp_path):
    path = tmp_path / "other.csv"
    path.write_text("a,b,c\n1,2,3\n")
    with pytest.raises(ValueError, match="not a file written by OverlapResult.to_csv"):
        lo.OverlapResult.from_csv(path)
    good = tmp_path / "g.csv"
    lo.overlap(lo.paper_table1(), [10.0, 100.0]).to_csv(good)
    good.write_text(_before_count(good.read_text(), "5,x,1"))
    with pytest.raises(ValueError, match="line .* is invalid: expected 3 numbers"):
        lo.OverlapResult.from_csv(good)


# ----------------------------------------------------------------------------- atomic writes,
# refused files
class _DiskFullAfter:
    """A file object that writes the first ``limit`` characters, then fails as a full disk would."""

    def __init__(self, f, limit):
        self._f, self._left = f, limit

    def write(self, text):
        if len(text) > self._left:
            self._f.write(text[: self._left])
            self._f.flush()
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        self._left -= len(text)
        return self._f.write(text)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._f.close()
        return False


def _leftovers(directory):
    return sorted(p.name for p in directory.iterdir())


def test_a_full_disk_leaves_no_csv(results, tmp_path, monkeypatch):
    from lidar_overlap import _files

    written = []

    def full_disk_open(path, mode="r", **kwargs):
        written.append(path)
        return _DiskFullAfter(open(path, mode, **kwargs), limit=1000)

    monkeypatch.setattr(_files, "open", full_disk_open, raising=False)
    with pytest.raises(OSError) as info:
        results["rt"].to_csv(tmp_path / "g.csv")
    assert info.value.errno == errno.ENOSPC and info.value.filename == str(tmp_path / "g.csv")
    assert written and written[0] != tmp_path / "g.csv"  # it wrote beside the file, not to it
    assert _leftovers(tmp_path) == []


def test_a_full_disk_keeps_the_previous_file(results, tmp_path, monkeypatch):
    from lidar_overlap import _files

    path = tmp_path / "g.csv"
    results["fo"].to_csv(path)
    before = path.read_bytes()
    monkeypatch.setattr(
        _files,
        "open",
        lambda p, mode="r", **kw: _DiskFullAfter(open(p, mode, **kw), 1000),
        raising=False,
    )
    with pytest.raises(OSError):
        results["rt"].to_csv(path)
    assert path.read_bytes() == before and _leftovers(tmp_path) == ["g.csv"]


def test_a_full_disk_leaves_no_netcdf(results, tmp_path, monkeypatch):
    import xarray as xr

    def half_then_full(self, path, *args, **kwargs):
        with open(path, "wb") as f:
            f.write(b"\x89HDF\r\n\x1a\n" + b"\0" * 100)
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(xr.Dataset, "to_netcdf", half_then_full)
    with pytest.raises(OSError) as info:
        results["rt"].to_netcdf(tmp_path / "g.nc")
    assert info.value.errno == errno.ENOSPC and "g.nc" in info.value.filename
    assert _leftovers(tmp_path) == []


def test_files_keep_the_usual_permissions(results, tmp_path):
    results["rt"].to_csv(tmp_path / "g.csv")
    results["rt"].to_netcdf(tmp_path / "g.nc")
    umask = os.umask(0)
    os.umask(umask)
    for name in ("g.csv", "g.nc"):
        assert stat.S_IMODE(os.stat(tmp_path / name).st_mode) == 0o666 & ~umask, name
    (tmp_path / "g.csv").chmod(0o640)
    results["fo"].to_csv(tmp_path / "g.csv")  # replacing keeps the file's own mode
    assert stat.S_IMODE(os.stat(tmp_path / "g.csv").st_mode) == 0o640
    assert _leftovers(tmp_path) == ["g.csv", "g.nc"]


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full on this system")
def test_writing_to_dev_full_fails_and_leaves_it_a_device(results):
    with pytest.raises(OSError) as info:
        results["rt"].to_csv("/dev/full")
    assert info.value.errno == errno.ENOSPC
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode)


def test_a_link_is_kept_and_its_target_replaced(results, tmp_path):
    (tmp_path / "data").mkdir()
    (tmp_path / "link.csv").symlink_to(tmp_path / "data" / "g.csv")
    results["rt"].to_csv(tmp_path / "link.csv")
    assert (tmp_path / "link.csv").is_symlink()
    _assert_same(lo.OverlapResult.from_csv(tmp_path / "data" / "g.csv"), results["rt"])


@pytest.mark.parametrize(
    "row, words",
    [
        ("100.0,nan,0.0", "overlap[1] = nan at range 100.0 m"),
        ("100.0,1.5,0.0", "overlap[1] = 1.5"),
        ("100.0,0.5,-1.0", "error_estimate[1] = -1.0"),
        ("5.0,0.5,0.0", "strictly increasing"),
    ],
)
def test_csv_with_bad_values_is_refused_naming_the_file(tmp_path, row, words):
    path = tmp_path / "g.csv"
    lo.overlap(lo.paper_table1(), [10.0]).to_csv(path)
    path.write_text(_before_count(path.read_text(), row, count=2))
    with pytest.raises(ValueError) as info:
        lo.OverlapResult.from_csv(path)
    assert str(info.value).startswith(f"{path}: ") and words in str(info.value)


def _before_count(text: str, row: str, count: int = 0) -> str:
    """``text`` of a CSV result with ``row`` added as its last data row (and its closing row count
    set to ``count`` when given)."""
    body, trailer = text.rstrip("\n").rsplit("\n", 1)
    assert trailer.startswith("# rows: ")
    return f"{body}\n{row}\n" + (f"# rows: {count}\n" if count else f"{trailer}\n")


def test_csv_that_is_not_text_is_refused(tmp_path):
    path = tmp_path / "g.csv"
    path.write_bytes(b"# method: rt\n\xff\xfe\n")
    with pytest.raises(ValueError, match="not UTF-8 text"):
        lo.OverlapResult.from_csv(path)


def test_netcdf_with_nan_is_refused_naming_the_file(results, tmp_path):
    ds = results["rt"].to_xarray()
    ds["overlap"].values[3] = np.nan
    ds.to_netcdf(tmp_path / "g.nc", encoding={name: {"_FillValue": None} for name in ds.variables})
    with pytest.raises(ValueError, match=r"g\.nc: overlap\[3\] = nan"):
        lo.OverlapResult.from_netcdf(tmp_path / "g.nc")


def _two_way_mean(paths="both", g=1.3):
    """A mean through turbulence as the FO path returns it (values as in the backscatter
    amplification of a small coaxial lidar: a two-way mean above 1)."""
    z = np.array([250.0, 500.0, 1000.0])
    rows = np.array([[0.9, 1.1, g - 0.2], [0.94, 1.14, g + 0.2]])
    return lo.TurbulentOverlapResult(
        ranges=z,
        overlap=rows.mean(axis=0),
        method="fo",
        error_estimate=rows.std(axis=0, ddof=1) / np.sqrt(2.0),
        system=lo.paper_table1(),
        tolerance=math.nan,
        error_kind="standard_error",
        realizations=rows,
        paths=paths,
        uncorrelated=rows * 0.8 if paths == "both" else None,
        amplification=np.full(3, 1.25) if paths == "both" else None,
    )


@pytest.mark.parametrize("suffix", ["csv", "nc"])
def test_a_two_way_mean_above_one_reads_back_as_a_mean_through_turbulence(tmp_path, suffix):
    original = _two_way_mean()
    path = tmp_path / f"g.{suffix}"
    (original.to_csv if suffix == "csv" else original.to_netcdf)(path)
    read = (lo.OverlapResult.from_csv if suffix == "csv" else lo.OverlapResult.from_netcdf)(path)
    assert isinstance(read, lo.TurbulentOverlapResult) and read.paths == "both"
    _assert_same(read, original)
    assert read.overlap.max() > 1.0


def test_a_plain_file_above_one_is_still_refused(tmp_path):
    path = tmp_path / "g.csv"
    _two_way_mean().to_csv(path)
    text = "".join(line for line in path.read_text().splitlines(True) if "turbulence_" not in line)
    path.write_text(text)
    with pytest.raises(ValueError, match="g.csv"):
        lo.OverlapResult.from_csv(path)


def test_turbulence_header_keys_are_the_result_s_own(tmp_path):
    with pytest.raises(ValueError, match="turbulence_paths"):
        lo.paper_table1() and lo.overlap(lo.paper_table1(), [300.0], "rt").to_csv(
            tmp_path / "g.csv", {"turbulence_paths": "both"}
        )
