"""Errors name the culprit: hostile values are refused with a ValueError naming the parameter
at fault (never another one, never pybind11's signature dump), integers beyond double or their
type included, and a divergence below the diffraction limit (M² < 1) is refused by every path.
"""

import math

import pytest
from _hostile_regressions import (
    DIFFRACTION_LIMIT,
    RANGES,
    TABLE1,
    kept,
    lidar,
    refused,
    small_field,
)
from _probe_worker import CLEAN_ERROR, call, names_a_parameter


@pytest.mark.parametrize(
    "probe, name",
    [
        (call("GaussianBeam", wavelength=10**400), "wavelength"),
        (call("Telescope", diameter=10**400), "diameter"),
        (call("Detector", radius=10**400), "radius"),
        (call("Detector.from_fov", 10**400, 1.0), "fov"),
        (call("overlap", TABLE1, [10**400], "rt"), "ranges"),
        (call("emitter_coupling", TABLE1, 10**400), "z"),
        (call("propagate", small_field(), 10**400), "distance"),
        (call("Field.gaussian", 355e-9, 1e-3, 64, 1e-4, power=10**400), "power"),
        (call("optimal_focus_range", 10**400, 1e-3), "focal_length"),
        (call("Turbulence", 10**400), "cn2"),
        (call("Aberrations", w040=10**400), "w040"),
    ],
    ids=[
        "wavelength",
        "diameter",
        "radius",
        "fov",
        "ranges",
        "z",
        "distance",
        "power",
        "focal_length",
        "cn2",
        "w040",
    ],
)
def test_integers_beyond_double_are_refused_by_name(runner, probe, name):
    refused(runner, probe, name)


@pytest.mark.parametrize("method", ["rt", "fo"])
def test_absurd_turbulence_does_not_blame_the_beam(runner, method):
    outcome = kept(
        runner, call("overlap", TABLE1, RANGES, method, turbulence=call("Turbulence", 1e300))
    )
    assert "beam.offset" not in outcome.get("message", ""), outcome["message"]


@pytest.mark.parametrize(
    "target", [1e300, 2**32, 2**64, 1e-300], ids=["1e300", "2_32", "2_64", "1e-300"]
)
def test_a_realignment_target_beyond_the_ranges_is_blamed_on_the_target(runner, target):
    # G is also computed at 100 x the target (its far limit): a target of 2**32 m named "ranges[1]"
    outcome = refused(runner, call("realign", TABLE1, target), "target")
    assert "ranges" not in outcome["message"], outcome["message"]


def test_a_subnormal_diameter_is_blamed_on_the_diameter(runner):
    outcome = refused(runner, call("Telescope", diameter=5e-324), "diameter")
    assert "obstruction_radius =" not in outcome["message"], outcome["message"]


@pytest.mark.parametrize("value", [(True, False), ("0", "0")], ids=["bools", "strings"])
@pytest.mark.parametrize(
    "fn, name, args",
    [
        ("GaussianBeam", "offset", ()),
        ("GaussianBeam", "tilt", ()),
        ("Detector", "offset", ()),
        ("Detector.from_fov", "offset", (0.9e-3, 1.0)),
        ("emitter_coupling", "position", (TABLE1, 100.0)),
        ("Field.gaussian", "center", (355e-9, 1e-3, 64, 1e-4)),
        ("FieldBeam", "offset", (small_field(),)),
    ],
    ids=[
        "beam_offset",
        "beam_tilt",
        "detector_offset",
        "from_fov_offset",
        "position",
        "center",
        "field_beam_offset",
    ],
)
def test_pairs_that_are_not_numbers_are_refused(runner, value, fn, name, args):
    refused(runner, call(fn, *args, **{name: value}), name)


@pytest.mark.parametrize("tolerance", [2.0, 0.0, -1e-4, math.nan])
def test_flat_top_tolerance_outside_the_unit_interval_is_refused(runner, tolerance):
    refused(
        runner,
        call("FlatTopBeam", 355e-9, 1e-3, 1e-3, grid=64, max_iterations=5, tolerance=tolerance),
        "tolerance",
    )


TURBULENT_FO = {
    "turbulence": call("Turbulence", 1e-14),
    "realizations": 1,
    "screens": 1,
    "beam_grid": 32,
    "paths": "transmit",  # a grid this coarse holds the beam's path only
}


@pytest.mark.parametrize(
    "method, options, name",
    [
        ("rt", {"threads": 2**31}, "threads"),
        ("fo", {"fo_path": "2d", "beam_grid": 2**31}, "beam_grid"),
        ("fo", {**TURBULENT_FO, "realizations": 2**31}, "realizations"),
        ("fo", {**TURBULENT_FO, "screens": 2**31}, "screens"),
        ("fo", {**TURBULENT_FO, "beam_grid": 2**31}, "beam_grid"),
        ("fo", {**TURBULENT_FO, "seed": 2**64}, "seed"),
        (
            "rt",
            {"turbulence": call("Turbulence", 1e-14), "realizations": 2**63 - 1},
            "realizations",
        ),
        ("fo", {"max_spectrum_grid": 2**63}, "max_spectrum_grid"),
    ],
    ids=[
        "threads",
        "beam_grid",
        "realizations",
        "screens",
        "turbulent_beam_grid",
        "seed_2_64",
        "rt_realizations",
        "max_spectrum_grid",
    ],
)
def test_integer_options_beyond_their_type_are_refused_by_name(runner, method, options, name):
    """Not a pybind11 signature dump, not a MemoryError: a ValueError naming the option."""
    refused(runner, call("overlap", TABLE1, [100.0], method, **options), name)


@pytest.mark.parametrize("seed", [2**31, 2**63], ids=["2_31", "2_63"])
def test_large_seeds_are_used_or_refused_by_name(runner, seed):
    outcome = kept(runner, call("overlap", TABLE1, [100.0], "fo", **TURBULENT_FO, seed=seed))
    if outcome["verdict"] == CLEAN_ERROR:
        assert outcome["type"] == "ValueError" and names_a_parameter(
            outcome["message"], ["seed"]
        ), outcome


@pytest.mark.parametrize("max_segments", [2**31, 2**64, 10**400], ids=["2_31", "2_64", "10_400"])
def test_a_huge_segment_cap_is_harmless_or_refused_by_name(runner, max_segments):
    outcome = kept(runner, call("overlap", TABLE1, RANGES, "rt", max_segments=max_segments))
    if outcome["verdict"] == CLEAN_ERROR:
        assert names_a_parameter(outcome["message"], ["max_segments"]), outcome["message"]


SUB_DIFFRACTION = call(
    "GaussianBeam", wavelength=355e-9, waist_radius=1e-3, divergence=0.5 * DIFFRACTION_LIMIT
)


@pytest.mark.parametrize(
    "probe",
    [
        SUB_DIFFRACTION,
        call("overlap", lidar(beam=SUB_DIFFRACTION), RANGES, "rt"),
        call("overlap", lidar(beam=SUB_DIFFRACTION), RANGES, "fo"),
        call("overlap", lidar(beam=SUB_DIFFRACTION), RANGES, "fo", fo_path="2d"),
        call("overlap", lidar(beam=SUB_DIFFRACTION), RANGES, "auto"),
        call("emitter_coupling", lidar(beam=SUB_DIFFRACTION), 100.0),
    ],
    ids=["construction", "rt", "fo", "fo_2d", "auto", "emitter"],
)
def test_a_divergence_below_the_diffraction_limit_is_refused_everywhere(runner, probe):
    assert "beam.divergence" in refused(runner, probe, "divergence")["message"]
