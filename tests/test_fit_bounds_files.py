"""A system's ``fit_bounds`` travel with it through files: result files (CSV, NetCDF) and scenario
files read back to the same bounds; files written without them still read, as a system without;
corrupt entries are refused naming them."""

import sys

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.io.scenario import ScenarioError, scenario_from_dict
from lidar_overlap.io.scenario_writer import scenario_toml
from lidar_overlap.model.instruments import chm15k, pollyxt
from lidar_overlap.model.system_attributes import system_attributes, system_from_attributes

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

Z = np.array([300.0, 700.0, 1500.0])
SYSTEMS = [chm15k(), pollyxt("near", 532e-9), lo.paper_table1()]


@pytest.fixture(scope="module")
def result():
    return lo.overlap(chm15k(), Z, "rt", tolerance=1e-3)


@pytest.mark.parametrize("system", SYSTEMS)
def test_the_attributes_carry_the_bounds(system):
    back = system_from_attributes(system_attributes(system))
    assert back == system and back.fit_bounds == system.fit_bounds


def test_a_csv_result_reads_back_with_the_bounds_and_without_them(result, tmp_path):
    path = tmp_path / "chm15k.csv"
    result.to_csv(path)
    back = lo.OverlapResult.from_csv(path)
    assert back.system == chm15k() and dict(back.system.fit_bounds) == dict(chm15k().fit_bounds)
    # a file written before the bounds were: the same system, without them
    old = tmp_path / "old.csv"
    old.write_text("".join(line for line in path.open() if "fit_bound_" not in line))
    assert lo.OverlapResult.from_csv(old).system.fit_bounds is None


def test_a_netcdf_result_reads_back_with_the_bounds(result, tmp_path):
    pytest.importorskip("xarray")
    pytest.importorskip("h5netcdf")
    path = tmp_path / "chm15k.nc"
    result.to_netcdf(path)
    assert lo.OverlapResult.from_netcdf(path).system == chm15k()


@pytest.mark.parametrize(
    "change, message",
    [
        ({"fit_bound_0_low": None}, "fit_bound_0_low' is missing"),
        ({"fit_bound_0_high": "wide"}, "fit_bound_0_high = 'wide' is invalid"),
        ({"fit_bound_1_path": "beam.nothing"}, "fit_bounds: parameter 'beam.nothing'"),
        ({"fit_bound_0_low": 1.0}, r"fit_bounds\['beam.divergence'\].*low < high"),
    ],
)
def test_corrupt_bounds_in_a_file_are_refused_naming_them(change, message):
    attrs = system_attributes(chm15k())
    attrs.update(change)
    attrs = {k: v for k, v in attrs.items() if v is not None}
    with pytest.raises(ValueError, match=message):
        system_from_attributes(attrs)


@pytest.mark.parametrize("system", SYSTEMS)
def test_a_scenario_reads_back_with_the_bounds(system):
    text = scenario_toml(system, Z, "bounded", 1e-3)
    assert ("[fit_bounds]" in text) == (system.fit_bounds is not None)
    assert scenario_from_dict(tomllib.loads(text)).system == system


def _with_table(table: str):
    text = scenario_toml(lo.paper_table1(), Z, "bounded", 1e-3) + "\n[fit_bounds]\n" + table
    return scenario_from_dict(tomllib.loads(text), "s.toml").system.fit_bounds


def test_a_scenarios_bounds_by_quoted_or_bare_path():
    assert dict(_with_table("beam.divergence = [5e-5, 1e-3]\n")) == {
        "beam.divergence": (5e-5, 1e-3)
    }
    assert dict(_with_table('"beam.offset" = [0.0, 0.3]\n')) == {
        "beam.offset[0]": (0.0, 0.3),
        "beam.offset[1]": (0.0, 0.3),
    }


@pytest.mark.parametrize(
    "table, message",
    [
        ("beam.divergence = [5e-5]\n", r"\[fit_bounds\] 'beam.divergence' = \[5e-05\] is invalid"),
        ('beam.divergence = "wide"\n', r"\[fit_bounds\] 'beam.divergence' = 'wide' is invalid"),
        ("beam.divergence = [0.0, inf]\n", r"\[fit_bounds\] 'beam.divergence'"),
        ("beam.nothing = [0.0, 1.0]\n", "s.toml: fit_bounds: parameter 'beam.nothing'"),
        ('"beam.divergence" = [2e-4, 1e-4]\n', r"fit_bounds\['beam.divergence'\].*low < high"),
    ],
)
def test_bad_scenario_bounds_are_refused_naming_them(table, message):
    with pytest.raises(ScenarioError, match=message):
        _with_table(table)
