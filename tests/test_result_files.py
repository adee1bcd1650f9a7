"""OverlapResult files: CSV and NetCDF round trips are exact (ranges, G, error estimates, method, tolerance),
the files carry units and the system description, a Gaussian system is rebuilt from the attributes, and a
missing xarray gives an ImportError saying what to install."""

import dataclasses
import math
import sys

import numpy as np
import pytest

import lidar_overlap as lo

pytest.importorskip("xarray")
RANGES = np.geomspace(5.0, 1000.0, 50)


def _biaxial():
    system = lo.paper_table1(obstruction_radius=0.02, defocus=3e-3, divergence=0.2e-3, width_law="linear")
    beam = dataclasses.replace(system.beam, offset=(0.1, -0.01), tilt=(-0.3e-3, 1e-5))
    detector = dataclasses.replace(system.detector, numerical_aperture=0.22, offset=(1e-5, 0.0))
    return dataclasses.replace(system, beam=beam, detector=detector)


@pytest.fixture(scope="module")
def results():
    return {"rt": lo.overlap(lo.paper_table1(), RANGES, method="rt"),
            "fo": lo.overlap(lo.paper_table1(obstruction_radius=0.02), RANGES[20::4], method="fo"),
            "biaxial": lo.overlap(_biaxial(), RANGES, method="rt", tolerance=1e-6),
            "aberrated": lo.overlap(_aberrated(), RANGES[20::8], method="rt")}


def _aberrated():
    aberrations = lo.Aberrations(zernike={6: 0.2e-6, 11: 0.3e-6}, w222=0.1e-6, field_radius=0.45e-3)
    base = lo.paper_table1()
    return dataclasses.replace(base, telescope=dataclasses.replace(base.telescope, aberrations=aberrations))


def _assert_same(read, original, system_too=True):
    assert np.array_equal(read.ranges, original.ranges)
    assert np.array_equal(read.overlap, original.overlap)
    assert np.array_equal(read.error_estimate, original.error_estimate, equal_nan=True)
    assert read.method == original.method
    assert read.tolerance == original.tolerance or (math.isnan(read.tolerance) and math.isnan(original.tolerance))
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
    assert float(header["beam_wavelength_m"]) == 355e-9 and float(header["detector_radius_m"]) == 0.45e-3
    columns = [line for line in lines if not line.startswith("#")]
    assert columns[0] == "range_m,overlap,error_estimate"
    assert len(columns) == 1 + RANGES.size
    assert float(columns[1].split(",")[1]) == results["rt"].overlap[0]


def test_xarray_dataset_units_and_attributes(results):
    ds = results["biaxial"].to_xarray()
    assert ds["range"].attrs["units"] == "m"
    assert ds["range"].attrs["long_name"] == "range from the transmitting plane"
    assert ds["overlap"].attrs == {**ds["overlap"].attrs, "units": "1", "long_name": "lidar overlap function"}
    assert ds["error_estimate"].attrs["units"] == "1"
    a = ds.attrs
    assert a["Conventions"] == "CF-1.10" and lo.__version__ in a["history"] and a["title"]
    assert a["method"] == "rt" and a["tolerance"] == 1e-6
    system = _biaxial()
    expected = {"beam_wavelength_m": 355e-9, "beam_waist_radius_m": 1e-3, "beam_divergence_rad": 0.2e-3,
                "beam_offset_x_m": 0.1, "beam_offset_y_m": -0.01, "beam_tilt_x_rad": -0.3e-3,
                "beam_tilt_y_rad": 1e-5, "telescope_diameter_m": 0.15, "telescope_focal_length_m": 1.0,
                "telescope_obstruction_radius_m": 0.02, "telescope_obstruction_distance_m": 0.7,
                "detector_radius_m": system.detector.radius, "detector_defocus_m": 3e-3,
                "detector_offset_x_m": 1e-5, "detector_numerical_aperture": 0.22, "detector_fov_rad": system.fov}
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
    beam = lo.FlatTopBeam(355e-9, 1e-3, 0.36e-3, grid=256, samples_per_waist=6.0, offset=(0.05, 0.0))
    system = lo.LidarSystem(beam=beam, telescope=lo.Telescope(0.15, 1.0), detector=lo.Detector(0.45e-3))
    res = lo.overlap(system, [200.0, 1000.0], method="fo")
    a = res.to_xarray().attrs
    assert a["beam_type"] == "flat_top" and a["beam_angular_diameter_rad"] == 0.36e-3
    assert a["beam_grid_size"] == 256 and a["beam_offset_x_m"] == 0.05
    res.to_netcdf(tmp_path / "f.nc")
    res.to_csv(tmp_path / "f.csv")
    for read in (lo.OverlapResult.from_netcdf(tmp_path / "f.nc"), lo.OverlapResult.from_csv(tmp_path / "f.csv")):
        _assert_same(read, res, system_too=False)
        assert read.system is None
        assert read.full_overlap_range() == res.full_overlap_range()


def test_missing_xarray_says_what_to_install(results, monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "xarray", None)
    for call in (results["rt"].to_xarray, lambda: results["rt"].to_netcdf(tmp_path / "g.nc"),
                 lambda: lo.OverlapResult.from_netcdf(tmp_path / "g.nc")):
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
    good.write_text(good.read_text() + "5,x,1\n")
    with pytest.raises(ValueError, match="line .* is invalid: expected 3 numbers"):
        lo.OverlapResult.from_csv(good)
