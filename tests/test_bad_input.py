"""Invalid input is rejected with a ValueError that names the offending parameter; nothing is
clamped.

Also checks that the system dataclasses are frozen and that dataclasses.replace re-validates.
Beam profiles, field beams and flat tops: test_bad_input_field_beams.py.
"""

import dataclasses
import math

import numpy as np
import pytest

import lidar_overlap as lo

NAN, INF = math.nan, math.inf
NOT_POSITIVE = [0.0, -1e-3, NAN, INF, -INF]  # invalid for every strictly positive finite size
BAD_PAIRS = [(1.0,), (1.0, 2.0, 3.0), [[1.0, 2.0]], (NAN, 0.0), (0.0, INF), "xy", None]


@pytest.fixture(scope="module")
def system():
    return lo.paper_table1()


@pytest.fixture(scope="module")
def obstructed():
    return lo.paper_table1(obstruction_radius=0.02, obstruction_distance=0.7)


# --- beam
# -------------------------------------------------------------------------------------------


@pytest.mark.parametrize("value", NOT_POSITIVE)
@pytest.mark.parametrize("name", ["wavelength", "waist_radius", "divergence"])
def test_beam_sizes(name, value):
    with pytest.raises(ValueError, match=f"beam.{name}"):
        lo.GaussianBeam(**{name: value})


@pytest.mark.parametrize("value", BAD_PAIRS)
@pytest.mark.parametrize("name", ["offset", "tilt"])
def test_beam_pairs(name, value):
    with pytest.raises(ValueError, match=f"beam.{name}"):
        lo.GaussianBeam(**{name: value})


@pytest.mark.parametrize("value", ["cubic", "Gaussian", "", None])
def test_beam_width_law(value):
    with pytest.raises(ValueError, match="beam.width_law"):
        lo.GaussianBeam(width_law=value)


@pytest.mark.parametrize("value", ["1e-3", True, [1e-3]])
def test_beam_non_numbers(value):
    with pytest.raises(ValueError, match="beam.waist_radius"):
        lo.GaussianBeam(waist_radius=value)


# --- telescope
# --------------------------------------------------------------------------------------


@pytest.mark.parametrize("value", NOT_POSITIVE)
@pytest.mark.parametrize("name", ["diameter", "focal_length"])
def test_telescope_sizes(name, value):
    with pytest.raises(ValueError, match=f"telescope.{name}"):
        lo.Telescope(**{name: value})


@pytest.mark.parametrize("value", [-1e-3, NAN, INF])
def test_obstruction_radius_invalid(value):
    with pytest.raises(ValueError, match="telescope.obstruction_radius"):
        lo.Telescope(diameter=0.15, obstruction_radius=value, obstruction_distance=0.7)


@pytest.mark.parametrize("value", [0.075, 0.08, 1.0])
def test_obstruction_radius_not_inside_aperture(value):
    with pytest.raises(ValueError, match="telescope.obstruction_radius"):
        lo.Telescope(diameter=0.15, obstruction_radius=value, obstruction_distance=0.7)


@pytest.mark.parametrize("value", [-0.1, NAN, INF])
def test_obstruction_distance_invalid(value):
    with pytest.raises(ValueError, match="telescope.obstruction_distance"):
        lo.Telescope(obstruction_radius=0.02, obstruction_distance=value)


def test_valid_edge_values_are_accepted():
    # zero obstruction and zero defocus are valid; so is an obstruction just inside the aperture
    lo.Telescope(diameter=0.15, obstruction_radius=0.0, obstruction_distance=0.0)
    lo.Telescope(diameter=0.15, obstruction_radius=0.0749, obstruction_distance=0.7)
    lo.LidarSystem(detector=lo.Detector(defocus=-0.5))


# --- detector
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("value", NOT_POSITIVE)
def test_detector_radius(value):
    with pytest.raises(ValueError, match="detector.radius"):
        lo.Detector(radius=value)


@pytest.mark.parametrize("value", [NAN, INF, -INF])
def test_detector_defocus_not_finite(value):
    with pytest.raises(ValueError, match="detector.defocus"):
        lo.Detector(defocus=value)


@pytest.mark.parametrize("defocus", [-1.0, -1.5, -10.0])
def test_defocus_not_behind_lens(defocus):
    # the detector plane f + defocus must lie behind the lens: defocus > -f (f = 1 m)
    with pytest.raises(ValueError, match="detector.defocus"):
        lo.LidarSystem(
            telescope=lo.Telescope(focal_length=1.0), detector=lo.Detector(defocus=defocus)
        )
    with pytest.raises(ValueError, match="detector.defocus"):
        lo.paper_table1(defocus=defocus)


@pytest.mark.parametrize("value", [0.0, 1.0, -0.1, 1.5, NAN, INF])
def test_numerical_aperture_outside_unit_interval(value):
    with pytest.raises(ValueError, match="detector.numerical_aperture"):
        lo.Detector(numerical_aperture=value)


@pytest.mark.parametrize("value", BAD_PAIRS)
def test_detector_offset(value):
    with pytest.raises(ValueError, match="detector.offset"):
        lo.Detector(offset=value)


@pytest.mark.parametrize("value", [0.0, -0.9e-3, NAN, INF])
def test_from_fov_bad_fov(value):
    with pytest.raises(ValueError, match="fov"):
        lo.Detector.from_fov(value, 1.0)


@pytest.mark.parametrize("value", [0.0, -1.0, NAN])
def test_from_fov_bad_focal_length(value):
    with pytest.raises(ValueError, match="focal_length"):
        lo.Detector.from_fov(0.9e-3, value)


def test_from_fov_radius():
    assert lo.Detector.from_fov(0.9e-3, 1.0).radius == pytest.approx(0.45e-3, rel=1e-15)
    assert lo.Detector.from_fov(1e-3, 0.5).radius == pytest.approx(0.25e-3, rel=1e-15)


# --- system
# -----------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["beam", "telescope", "detector"])
def test_system_parts_have_the_right_type(name):
    with pytest.raises(ValueError, match=name):
        lo.LidarSystem(**{name: 1.0})


# --- overlap arguments
# ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "ranges",
    [
        [0.0, 1.0, 2.0],  # non-positive
        [-5.0, 10.0],  # negative
        [1.0, NAN, 3.0],  # NaN
        [1.0, INF],  # infinite
        [[1.0, 2.0], [3.0, 4.0]],  # 2-D
        [],  # empty
        5.0,  # scalar (0-D)
        [1.0, 3.0, 2.0],  # not increasing
        [1.0, 1.0, 2.0],  # repeated
        ["a", "b"],  # not numbers
        [259.6, (1.0, 2.0, 3.0), 18064.6],  # ragged (NumPy's own error named nothing)
    ],
)
def test_overlap_bad_ranges(system, ranges):
    with pytest.raises(ValueError, match="ranges"):
        lo.overlap(system, ranges)


@pytest.mark.parametrize("ranges", [[0.5, 10.0], [0.7, 10.0], [0.6, 0.65]])
def test_overlap_ranges_inside_obstruction_distance(obstructed, ranges):
    # scatterers between the aperture stop and the obstruction (z <= 0.7 m) are outside the model
    with pytest.raises(ValueError, match="ranges"):
        lo.overlap(obstructed, ranges)


@pytest.mark.parametrize("value", [0.0, 1.0, -1e-4, 2.0, NAN, INF])
def test_overlap_bad_tolerance(system, value):
    with pytest.raises(ValueError, match="tolerance"):
        lo.overlap(system, [1.0, 2.0], tolerance=value)


@pytest.mark.parametrize("value", [-1, -8, 1.5, "2", None])
def test_overlap_bad_threads(system, value):
    with pytest.raises(ValueError, match="threads"):
        lo.overlap(system, [1.0, 2.0], threads=value)


@pytest.mark.parametrize("value", [0, -1, 2.5])
def test_overlap_bad_max_segments(system, value):
    with pytest.raises(ValueError, match="max_segments"):
        lo.overlap(system, [1.0, 2.0], max_segments=value)


@pytest.mark.parametrize("value", ["RT", "fourier", "", None])
def test_overlap_bad_method(system, value):
    with pytest.raises(ValueError, match="method"):
        lo.overlap(system, [1.0, 2.0], method=value)


def test_overlap_needs_a_system():
    with pytest.raises(ValueError, match="system"):
        lo.overlap(lo.GaussianBeam(), [1.0, 2.0])


# --- emitter_coupling and optimal_focus_range
# -------------------------------------------------------


@pytest.mark.parametrize("value", BAD_PAIRS)
def test_emitter_coupling_bad_position(system, value):
    with pytest.raises(ValueError, match="position"):
        lo.emitter_coupling(system, 100.0, position=value)


@pytest.mark.parametrize("z", [0.0, -1.0, NAN, INF])
def test_emitter_coupling_bad_range(system, z):
    with pytest.raises(ValueError, match="z"):
        lo.emitter_coupling(system, z)


@pytest.mark.parametrize("z", [0.3, 0.7])
def test_emitter_coupling_inside_obstruction_distance(obstructed, z):
    with pytest.raises(ValueError, match="z"):
        lo.emitter_coupling(obstructed, z)


def test_emitter_coupling_bad_method(system):
    with pytest.raises(ValueError, match="method"):
        lo.emitter_coupling(system, 100.0, method="fo-exact")


@pytest.mark.parametrize("defocus", [-1e-3, NAN, 5e-324])  # 5e-324: f (f + δ) / δ overflowed to inf
def test_optimal_focus_range_bad_defocus(defocus):
    with pytest.raises(ValueError, match="defocus"):
        lo.optimal_focus_range(1.0, defocus)


@pytest.mark.parametrize("f", [0.0, -1.0, NAN])
def test_optimal_focus_range_bad_focal_length(f):
    with pytest.raises(ValueError, match="focal_length"):
        lo.optimal_focus_range(f, 1e-3)


# --- immutability and replace
# -----------------------------------------------------------------------


def test_dataclasses_are_frozen(system):
    for obj, name, value in [
        (system.beam, "waist_radius", 2e-3),
        (system.telescope, "diameter", 0.2),
        (system.detector, "radius", 1e-3),
        (system, "beam", lo.GaussianBeam()),
    ]:
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(obj, name, value)
    res = lo.overlap(system, [10.0, 20.0])
    with pytest.raises(dataclasses.FrozenInstanceError):
        res.method = "fo"


def test_replace_builds_a_new_valid_object(system):
    beam = dataclasses.replace(system.beam, waist_radius=2e-3)
    assert beam.waist_radius == 2e-3 and system.beam.waist_radius == 1e-3
    # the native model follows: the diffraction-limited divergence is recomputed from the new waist
    assert beam.half_angle_divergence == pytest.approx(355e-9 / (np.pi * 2e-3), rel=1e-12)
    assert beam.radius(100.0) == pytest.approx(
        np.hypot(2e-3, 100.0 * 355e-9 / (np.pi * 2e-3)), rel=1e-12
    )
    # and so does the overlap: a 1 mrad beam overfills the 0.45 mrad field of view at 300 m
    wide = dataclasses.replace(system, beam=dataclasses.replace(system.beam, divergence=1e-3))
    g_old, g_new = (lo.overlap(s, [300.0], tolerance=1e-8).overlap[0] for s in (system, wide))
    assert g_old > 0.99 and g_new < 0.5


def test_replace_revalidates(system):
    with pytest.raises(ValueError, match="beam.waist_radius"):
        dataclasses.replace(system.beam, waist_radius=-1e-3)
    with pytest.raises(ValueError, match="telescope.obstruction_radius"):
        dataclasses.replace(system.telescope, obstruction_radius=0.1)
    with pytest.raises(ValueError, match="detector.numerical_aperture"):
        dataclasses.replace(system.detector, numerical_aperture=1.2)
    # a combination that is only invalid as a whole: defocus -2 m behind a 1 m lens
    with pytest.raises(ValueError, match="detector.defocus"):
        dataclasses.replace(system, detector=dataclasses.replace(system.detector, defocus=-2.0))
    # a smaller aperture no longer contains an existing obstruction
    blocked = lo.paper_table1(obstruction_radius=0.02)
    with pytest.raises(ValueError, match="telescope.obstruction_radius"):
        dataclasses.replace(
            blocked, telescope=dataclasses.replace(blocked.telescope, diameter=0.03)
        )
