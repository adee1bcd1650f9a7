"""Errors carry the refused parameter as data (lo.ParameterError: .parameter, .value, .expected),
whether the core or the package's checks refuse it, so that no caller reads a message to learn
which parameter it was; each is still a ValueError whose message names the parameter and the valid
range."""

import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _checks
from lidar_overlap.io.scenario_schema import file_key, prefixed


def _refusal(call):
    with pytest.raises(lo.ParameterError) as info:
        call()
    error = info.value
    assert isinstance(error, ValueError)
    assert error.parameter in str(error)  # the message still names it
    return error


@pytest.mark.parametrize("value", [-1.0, 0.0, math.nan, math.inf, 1e-300, 1e300])
def test_the_core_refuses_a_wavelength_by_name_value_and_range(value):
    error = _refusal(lambda: lo.GaussianBeam(wavelength=value, waist_radius=1e-3))
    assert error.parameter == "beam.wavelength"
    assert error.value == value or (math.isnan(value) and math.isnan(error.value))
    assert "length from" in error.expected and error.expected in str(error)


@pytest.mark.parametrize("value", [2.0, 0.0, 1e-300, math.nan])
def test_the_package_checks_refuse_a_tolerance_by_name(value):
    error = _refusal(lambda: lo.RT(tolerance=value))
    assert error.parameter == "tolerance"
    assert error.expected.startswith(f"a value in [{_checks.MIN_TOLERANCE:g}, 1)")


@pytest.mark.parametrize("bad", [True, "3", 2**64, -1])
def test_a_count_is_refused_with_the_value_given(bad):
    error = _refusal(lambda: lo.RT(max_segments=bad))
    assert error.parameter == "max_segments" and error.value is bad


def test_a_range_behind_the_obstruction_is_named_by_its_index_and_reindexed():
    system = lo.paper_table1(obstruction_radius=0.02)
    error = _refusal(lambda: lo.overlap(system, [0.01, 100.0, 200.0]))
    assert error.parameter == "ranges[0]" and error.value == 0.01
    moved = _checks.reindexed(error, 40)
    assert moved.parameter == "ranges[40]" and str(moved).startswith("ranges[40] = 0.01")
    assert (moved.value, moved.expected) == (error.value, error.expected)


def test_an_unordered_grid_names_the_range_that_breaks_the_order():
    error = _refusal(lambda: lo.overlap(lo.paper_table1(), [100.0, 300.0, 200.0]))
    assert error.parameter == "ranges[2]" and error.value == 200.0


def test_the_core_memory_budget_names_the_grid_and_the_budget():
    error = _refusal(
        lambda: lo.overlap(lo.paper_table1(), [500.0], "fo", fo_path="2d", beam_grid=2**15)
    )
    assert error.parameter == "beam_grid" and error.value == 2**15
    assert "max_memory" in error.expected


def test_a_scenario_file_places_the_parameter_under_its_section_and_key():
    error = _refusal(
        lambda: lo.GaussianBeam(wavelength=355e-9, waist_radius=1e-3, offset=(math.nan, 0.0))
    )
    assert error.parameter == "beam.offset"
    assert prefixed("s.toml", "beam", error).startswith("s.toml: [beam] offset = (nan, 0.0)")
    radius = _refusal(lambda: lo.Detector(radius=-1.0, defocus=0.0))
    assert prefixed("s.toml", "detector", radius).startswith("s.toml: [detector] radius = -1")
    assert file_key("aberrations.zernike[11]") == ("telescope.aberrations.zernike", "11", "")
    assert file_key("detector.radius") == ("detector", "radius", "")
    assert file_key("ranges[3]") is None
    plain = ValueError("beam.offset is odd")  # no parameter as data: under its section as it is
    assert prefixed("s.toml", "run", plain) == "s.toml: [run] beam.offset is odd"


def test_the_return_path_refusal_keeps_its_parameter_and_says_the_way_out():
    system = lo.paper_table1()
    turbulence = lo.Turbulence(cn2=1e-13)
    method = lo.Turbulent(turbulence, lo.FO(path="2d", beam_grid=32), realizations=2, paths="both")
    error = _refusal(lambda: lo.overlap(system, np.array([300.0, 600.0]), method))
    assert error.parameter == "beam_grid" and error.value == 32
    assert "paths = 'transmit'" in str(error)
