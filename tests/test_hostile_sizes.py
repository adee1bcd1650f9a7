"""Hostile sizes end in a clean refusal or a finite result: grids beyond the memory budget
and thread counts beyond any machine are refused by name, extreme lengths end cleanly (they once
crashed the process).
"""

import pytest
from _hostile_regressions import MAX_FLOAT, RANGES, TABLE1, kept, lidar, refused, small_field
from _probe_worker import call


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
