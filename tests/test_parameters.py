"""Parameter paths: every path reads back what was set, pairs expand to their scalars, and bad
paths, values and systems are refused naming the path."""

import math

import pytest

import lidar_overlap as lo
from lidar_overlap import parameters

BASE = lo.paper_table1(obstruction_radius=0.02)
VALUES = {
    "beam.wavelength": 532e-9,
    "beam.waist_radius": 2e-3,
    "beam.divergence": 2e-4,
    "beam.offset[0]": 0.1,
    "beam.offset[1]": -0.02,
    "beam.tilt[0]": 1e-4,
    "beam.tilt[1]": -2e-5,
    "telescope.diameter": 0.2,
    "telescope.focal_length": 0.8,
    "telescope.obstruction_radius": 0.03,
    "telescope.obstruction_distance": 0.5,
    "detector.radius": 3e-4,
    "detector.defocus": 2e-3,
    "detector.offset[0]": 1e-5,
    "detector.offset[1]": 2e-5,
    "detector.numerical_aperture": 0.22,
    "telescope.aberrations.zernike[11]": 5e-8,
    "telescope.aberrations.w040": 1e-7,
    "telescope.aberrations.field_radius": 1e-3,
}


@pytest.mark.parametrize("path, value", VALUES.items())
def test_each_path_reads_back_what_was_set_and_leaves_the_rest(path, value):
    changed = parameters.replace(BASE, {path: value})
    assert parameters.get(changed, path) == value
    diffraction_limited = path in (
        "beam.wavelength",
        "beam.waist_radius",
    )  # they set the divergence too
    for other in VALUES:
        if other == path or other == "detector.numerical_aperture" or "aberrations" in other:
            continue  # unset in BASE
        if not (diffraction_limited and other == "beam.divergence"):
            assert parameters.get(changed, other) == parameters.get(BASE, other)


def test_all_at_once_and_the_divergence_of_a_diffraction_limited_beam():
    changed = parameters.replace(BASE, VALUES)
    assert all(parameters.get(changed, p) == v for p, v in VALUES.items())
    assert parameters.get(BASE, "beam.divergence") == pytest.approx(
        355e-9 / (math.pi * 1e-3), rel=1e-12
    )


def test_pairs_expand_to_their_scalars():
    assert parameters.expand(["beam.tilt", "detector.defocus"]) == [
        "beam.tilt[0]",
        "beam.tilt[1]",
        "detector.defocus",
    ]
    assert parameters.expand("detector.offset") == ["detector.offset[0]", "detector.offset[1]"]


@pytest.mark.parametrize(
    "path",
    [
        "beam.tilt[2]",
        "beam.color",
        "telescope.aberrations.zernike[0]",
        "telescope.aberrations.zernike[232]",
        "lens.f",
        "",
        None,
        3,
        "beam.tilt[-1]",
    ],
)
def test_unknown_paths_are_refused_naming_them(path):
    with pytest.raises(
        ValueError, match=r"^parameter .* is invalid: expected one of beam\.wavelength"
    ):
        parameters.get(BASE, path)
    with pytest.raises(ValueError, match=r"^parameter .* is invalid"):
        parameters.replace(BASE, {path: 1.0})


@pytest.mark.parametrize(
    "path, value, message",
    [
        ("telescope.diameter", -1.0, r"^telescope\.diameter = -1\.0 makes an invalid system"),
        ("beam.tilt[0]", float("nan"), r"beam\.tilt"),
        (
            "detector.radius",
            "0.1",
            r"^detector\.radius = '0\.1' is invalid: expected a real number",
        ),
        ("telescope.obstruction_radius", 0.2, r"makes an invalid system"),
        (
            "telescope.aberrations.w131",
            1e-7,
            r"^telescope\.aberrations\.w131 = 1e-07 makes an invalid system: .*field_radius",
        ),
    ],
)
def test_bad_values_are_refused_naming_the_path(path, value, message):
    with pytest.raises(ValueError, match=message):
        parameters.replace(BASE, {path: value})


def test_a_parameter_named_twice_and_an_unset_one_are_refused():
    with pytest.raises(ValueError, match="named twice"):
        parameters.expand(["beam.tilt", "beam.tilt[0]"])
    with pytest.raises(ValueError, match="is not set in this system"):
        parameters.get(BASE, "detector.numerical_aperture")


def test_a_field_beam_varies_its_pointing_only():
    beam = lo.FieldBeam(lo.Field.gaussian(355e-9, 1e-3, n=64, spacing=1e-4))
    system = lo.LidarSystem(beam=beam)
    moved = parameters.replace(system, {"beam.tilt[0]": 1e-4})
    assert moved.beam.tilt == (1e-4, 0.0) and moved.beam.field is beam.field
    with pytest.raises(ValueError, match="only its offset and tilt can vary"):
        parameters.replace(system, {"beam.waist_radius": 2e-3})
