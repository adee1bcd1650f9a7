"""Value types pickle (for process pools and Dask clusters): the copy is equal, computes the same G
bit for bit, keeps its invariants (read-only arrays, frozen), and is validated again when it is
unpickled."""

import dataclasses
import pickle

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap._pickling import rebuild

Z = np.geomspace(50.0, 2000.0, 4)
SYSTEM = lo.paper_table1(obstruction_radius=0.02, defocus=1e-3)
ABERRATED = lo.with_aberrations(
    SYSTEM, lo.Aberrations(zernike={11: 5e-8}, w222=1e-7, field_radius=1e-3)
)
FIELD_BEAM = lo.LidarSystem(
    beam=lo.FieldBeam(lo.annular_field(355e-9, 2e-3, 0.5e-3, 128, 1e-4), tilt=(1e-5, 0.0)),
    telescope=SYSTEM.telescope,
    detector=SYSTEM.detector,
)


def copy(value):
    return pickle.loads(pickle.dumps(value))


@pytest.mark.parametrize(
    "system, method", [(SYSTEM, "rt"), (ABERRATED, lo.RT(1e-3)), (FIELD_BEAM, "fo")]
)
@pytest.mark.filterwarnings(
    "ignore::lidar_overlap.SamplingWarning"
)  # the annulus' hard edges: equality is the point
def test_a_pickled_system_computes_the_same_overlap(system, method):
    again = copy(system)
    assert again == system or isinstance(
        system.beam, lo.FieldBeam
    )  # field beams compare by identity
    assert np.array_equal(
        lo.overlap(again, Z, method).overlap, lo.overlap(system, Z, method).overlap
    )


def test_a_pickled_flat_top_keeps_its_design_and_stays_immutable():
    beam = lo.FlatTopBeam(355e-9, 1e-3, 0.5e-3, grid=128, max_iterations=10, tilt=(2e-5, 0.0))
    again = copy(beam)
    assert (
        type(again) is lo.FlatTopBeam
        and again.tilt == beam.tilt
        and again.efficiency == beam.efficiency
    )
    assert np.array_equal(again.field.values, beam.field.values) and np.array_equal(
        again.phase, beam.phase
    )
    with pytest.raises(ValueError):
        again.phase[0, 0] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        again.tilt = (0.0, 0.0)


@pytest.mark.parametrize(
    "value",
    [
        lo.Turbulence(1e-14, inner_scale=0.01),
        lo.Turbulence("hv57", elevation=1.0),
        lo.Field.gaussian(532e-9, 1e-3, n=32, spacing=2e-4),
        lo.Aberrations(zernike={4: 1e-7}),
        lo.Detector.from_fov(1e-3, 0.5),
    ],
)
def test_other_value_types_round_trip(value):
    again = copy(value)
    if isinstance(value, lo.Field):
        assert np.array_equal(again.values, value.values) and not again.values.flags.writeable
    else:
        assert again == value


def test_an_unpickled_value_is_validated_again():
    with pytest.raises(ValueError, match=r"^telescope\.diameter = -1"):
        rebuild(
            lo.Telescope,
            {
                "diameter": -1.0,
                "focal_length": 1.0,
                "obstruction_radius": 0.0,
                "obstruction_distance": 0.0,
                "aberrations": None,
            },
        )
