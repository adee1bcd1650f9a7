"""Extreme values give no NaN or out-of-range number: a result of hostile values is finite with
every overlap in [0, 1], and where the right number is known (no light far off axis, the radial
path, G = 0 behind an obstruction) it is that number.
"""

import numpy as np
import pytest
from _hostile_regressions import (
    FO_2D_AGREEMENT,
    NO_LIGHT,
    RANGES,
    TABLE1,
    kept,
    lidar,
    small_field,
)
from _probe_runner import describe
from _probe_worker import FINITE, call


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
        (
            "fo",
            {
                "fo_path": "2d",
                "turbulence": lo.Turbulence(1e-15),
                "realizations": 2,
                "paths": "transmit",  # a fibre's NA is not modelled on the return path
            },
        ),
    ):
        result = lo.overlap(system, ranges, method, **options)
        assert np.array_equal(result.overlap, np.zeros(2)), (method, options, result.overlap)
