"""Named regressions for hostile inputs that crashed the process, hung, returned a silent wrong
number or blamed the wrong parameter. Each probe runs in the worker process of
tests/_probe_runner.py, so a crash fails its test instead of the session, and a hang is cut at the
time limit (20 s).

The contract (tests/_probe_worker.py): a ValueError or TypeError naming a parameter the call set, or
a result whose numbers are finite with every overlap in [0, 1]. Where a test asks for more (the
parameter that must be named, the value that is correct), it says so.
"""

import math

import numpy as np
import pytest
from _probe_runner import ProbeRunner, describe
from _probe_worker import CLEAN_ERROR, FINITE, Attr, call, names_a_parameter

MAX_FLOAT = 1.7976931348623157e308
RANGES = [10.0, 100.0, 1000.0]
TABLE1 = call("paper_table1")
#: λ/(π w0) of the default beam (355 nm, 1 mm waist): the least divergence with M² >= 1.
DIFFRACTION_LIMIT = 355e-9 / (math.pi * 1e-3)
#: |G| allowed for a beam 1e30 m off the axis: no light of it reaches the receiver.
NO_LIGHT = 1e-6
#: Agreement of the 2-D FO path with the radial one (README: 2-D ~1e-6, radial exact to 2e-10).
FO_2D_AGREEMENT = 1e-5


def lidar(beam=None, telescope=None, detector=None):
    """LidarSystem(...) with the given parts, defaults elsewhere."""
    parts = {"beam": beam, "telescope": telescope, "detector": detector}
    return call("LidarSystem", **{k: v for k, v in parts.items() if v is not None})


def small_field():
    return call("Field.gaussian", 355e-9, 1e-3, 64, 1e-4)


@pytest.fixture(scope="module")
def runner():
    with ProbeRunner() as r:
        yield r


def kept(runner, probe) -> dict:
    """The probe ends in a clean error or a finite, in-range result; its outcome."""
    outcome = runner.run(probe)
    assert outcome["verdict"] in (CLEAN_ERROR, FINITE), describe(probe, outcome)
    return outcome


def refused(runner, probe, name: str) -> dict:
    """The probe ends in a ValueError whose message names ``name``; its outcome."""
    outcome = runner.run(probe)
    assert outcome["verdict"] == CLEAN_ERROR and outcome["type"] == "ValueError", describe(
        probe, outcome
    )
    assert names_a_parameter(outcome["message"], [name]), (
        f"{name!r} not named: {outcome['message']}"
    )
    return outcome


# --------------------------------------------------------------------------------- crashes: huge
# grids
@pytest.mark.parametrize(
    "probe, name",
    [
        (call("Field.gaussian", 355e-9, 1e-3, 2**32, 1e-4), "n"),
        (call("propagate", small_field(), 100.0, grid_size=2**32), "grid_size"),
        (
            call(
                "overlap",
                lidar(beam=call("GaussianBeam", offset=(0.1, 0))),
                [100.0],
                "fo",
                fo_path="2d",
                beam_grid=2**40,
            ),
            "beam_grid",
        ),
        (call("FlatTopBeam", 355e-9, 1e-3, 1e-3, grid=2**32), "grid"),
    ],
    ids=["field_n", "propagate_grid_size", "fo_2d_beam_grid", "flat_top_grid"],
)
def test_grids_beyond_memory_are_refused_by_name(runner, probe, name):
    refused(runner, probe, name)


@pytest.mark.parametrize(
    "probe",
    [
        call("overlap", TABLE1, [5e-324], "fo"),
        call("overlap", lidar(beam=call("GaussianBeam", wavelength=MAX_FLOAT)), RANGES, "fo"),
        call("overlap", lidar(telescope=call("Telescope", focal_length=5e-324)), RANGES, "auto"),
        call(
            "overlap",
            lidar(beam=call("GaussianBeam", wavelength=5e-324)),
            RANGES,
            "fo",
            fo_path="2d",
        ),
    ],
    ids=[
        "subnormal_range",
        "max_float_wavelength",
        "subnormal_focal_length",
        "subnormal_wavelength_2d",
    ],
)
def test_extreme_lengths_end_cleanly(runner, probe):
    kept(runner, probe)


@pytest.mark.parametrize("threads", [2**31 - 1, 40000], ids=["2_31_minus_1", "40000"])
@pytest.mark.parametrize(
    "options",
    [{"method": "rt"}, {"method": "fo"}, {"method": "fo", "fo_path": "2d"}, {"method": "auto"}],
    ids=["rt", "fo", "fo_2d", "auto"],
)
def test_thread_counts_beyond_any_machine_are_refused(runner, threads, options):
    options = dict(options)
    refused(
        runner,
        call("overlap", TABLE1, [100.0], options.pop("method"), threads=threads, **options),
        "threads",
    )


# --------------------------------------------------------------------------------- hangs
@pytest.mark.parametrize(
    "probe",
    [
        call(
            "overlap",
            lidar(telescope=call("Telescope", aberrations=call("Aberrations", w040=1e300))),
            RANGES,
            "fo",
        ),
        call(
            "overlap",
            lidar(
                telescope=call(
                    "Telescope",
                    aberrations=call("Aberrations", zernike={j: 1e-9 for j in range(1, 232)}),
                )
            ),
            [100.0, 1000.0],
            "fo",
        ),
        call(
            "overlap",
            lidar(
                telescope=call(
                    "Telescope",
                    aberrations=call("Aberrations", zernike={j: 1e-9 for j in range(1, 1001)}),
                )
            ),
            [100.0],
            "rt",
        ),
        call("overlap", TABLE1, [100.0], "fo", turbulence=call("Turbulence", 1e-14), screens=10**6),
        call(
            "overlap",
            lidar(telescope=call("Telescope", diameter=100.0)),
            RANGES,
            "fo",
            fo_path="radial",
        ),
        call(
            "overlap",
            lidar(detector=call("Detector", offset=(1e3, 0))),
            RANGES,
            "fo",
            fo_path="radial",
        ),
        call(
            "overlap",
            lidar(telescope=call("Telescope", focal_length=1e-6)),
            RANGES,
            "fo",
            fo_path="radial",
        ),
        call("emitter_coupling", TABLE1, 2.0, method="fo"),
    ],
    ids=[
        "w040_1e300_fo",
        "zernike_231_fo",
        "zernike_1000_rt",
        "screens_1e6",
        "radial_diameter_100m",
        "radial_detector_offset_1km",
        "radial_focal_length_1um",
        "emitter_fo_2m",
    ],
)
def test_slow_inputs_end_within_the_time_limit(runner, probe):
    kept(runner, probe)


# --------------------------------------------------------------------------------- silent wrong
# numbers
@pytest.mark.parametrize(
    "probe",
    [
        call("overlap", lidar(beam=call("GaussianBeam", wavelength=1e300)), RANGES, "rt"),
        call("overlap", lidar(beam=call("GaussianBeam", waist_radius=1e-300)), RANGES, "rt"),
        call("overlap", lidar(beam=call("GaussianBeam", divergence=1e300)), RANGES, "rt"),
        call("overlap", lidar(telescope=call("Telescope", diameter=1e-300)), RANGES, "rt"),
        call("overlap", lidar(detector=call("Detector", radius=1e300)), RANGES, "fo"),
        call("emitter_coupling", TABLE1, 1e-300, method="fo"),
        call("propagate", small_field(), 1e300),
        call("Field.gaussian", 355e-9, 1e-300, 64, 1e-4),
    ],
    ids=[
        "rt_wavelength_1e300",
        "rt_waist_1e-300",
        "rt_divergence_1e300",
        "rt_diameter_1e-300",
        "fo_detector_radius_1e300",
        "emitter_fo_z_1e-300",
        "propagate_1e300",
        "field_waist_1e-300",
    ],
)
def test_extreme_values_give_no_nan_or_out_of_range_number(runner, probe):
    kept(runner, probe)


def test_a_beam_far_off_axis_couples_no_light(runner):
    probe = call(
        "overlap", lidar(beam=call("GaussianBeam", offset=(1e30, 0))), RANGES, "fo", fo_path="2d"
    )
    outcome = kept(runner, probe)
    if outcome["verdict"] == FINITE:
        assert max(abs(g) for g in outcome["summary"]["overlap"]) < NO_LIGHT, describe(
            probe, outcome
        )


def test_a_huge_beam_window_is_refused_or_matches_the_radial_path(runner):
    biaxial = lidar(beam=call("GaussianBeam", offset=(0.1, 0)))
    outcome = kept(runner, call("overlap", biaxial, RANGES, "fo", fo_path="2d", beam_window=1e300))
    if outcome["verdict"] == FINITE:
        reference = kept(runner, call("overlap", biaxial, RANGES, "fo", fo_path="radial"))[
            "summary"
        ]["overlap"]
        np.testing.assert_allclose(outcome["summary"]["overlap"], reference, atol=FO_2D_AGREEMENT)


# --------------------------------------------------------------------------------- errors that name
# the culprit
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


# --------------------------------------------------------------------------------- results
def _full_overlap(runner, ranges):
    probe = call(Attr(call("overlap", TABLE1, ranges, "rt"), "full_overlap_range"))
    outcome = kept(runner, probe)
    assert outcome["verdict"] == FINITE, describe(probe, outcome)
    return outcome


def test_full_overlap_range_of_a_curve_short_of_its_limit_warns_or_is_nan(runner):
    outcome = _full_overlap(
        runner, [10.0, 30.0, 60.0, 90.0]
    )  # max G ~0.3; Table 1's far-range limit is 1
    warned = any(is_runtime for _, is_runtime, _ in outcome["warnings"])
    assert warned or math.isnan(outcome["summary"]["value"]), outcome


def test_full_overlap_range_of_a_complete_curve_is_a_range_without_warning(runner):
    outcome = _full_overlap(runner, np.geomspace(5.0, 5000.0, 30).tolist())
    assert 5.0 <= outcome["summary"]["value"] <= 5000.0, outcome
    assert not any(is_runtime for _, is_runtime, _ in outcome["warnings"]), outcome["warnings"]


# --------------------------------------------------------------------------------- M² < 1
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


# --------------------------------------------------------------------------------- reproducibility
def test_fo_2d_does_not_depend_on_threads_or_process(runner):
    biaxial = lidar(
        beam=call("GaussianBeam", offset=(0.1, 0.0), tilt=(1e-4, 0.0)),
        detector=call("Detector", radius=0.3e-3, defocus=2e-3),
    )
    z = [50.0, 200.0, 1000.0]
    probes = {t: call("overlap", biaxial, z, "fo", fo_path="2d", threads=t) for t in (1, 0)}
    one, all_cores = (kept(runner, probes[t]) for t in (1, 0))
    with ProbeRunner() as fresh:
        other_process = kept(fresh, probes[1])
    assert one["verdict"] == FINITE, one
    assert one["summary"]["overlap"] == all_cores["summary"]["overlap"]  # bit for bit
    assert one["summary"]["overlap"] == other_process["summary"]["overlap"]


def test_an_obstruction_shadow_covering_the_na_pupil_gives_zero_in_every_path():
    """Found by the sanitizer build: with the obstruction's shadow wider than the NA cone's pupil no
    light passes; the 2-D FO path then sized its grid from a zero cutoff (20 / 0) and refused the
    range naming max_spectrum_grid. G = 0 exactly is the answer, and each path gives it."""
    import lidar_overlap as lo

    system = lo.LidarSystem(
        beam=lo.GaussianBeam(wavelength=532e-9, waist_radius=2e-3, offset=(0.05, 0.0)),
        telescope=lo.Telescope(
            diameter=0.3, focal_length=0.35, obstruction_radius=0.07, obstruction_distance=0.8
        ),
        detector=lo.Detector(radius=4e-5, numerical_aperture=0.05),
    )
    ranges = [20.0, 1000.0]
    for method, options in (
        ("rt", {}),
        ("fo", {"fo_path": "radial"}),
        ("fo", {"fo_path": "2d"}),
        ("fo", {"fo_path": "2d", "turbulence": lo.Turbulence(1e-15), "realizations": 2}),
    ):
        result = lo.overlap(system, ranges, method, **options)
        assert np.array_equal(result.overlap, np.zeros(2)), (method, options, result.overlap)
