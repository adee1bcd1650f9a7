"""Inputs that once hung end within the probe time limit (20 s of CPU time), in a clean
refusal or a finite result.
"""

import pytest
from _hostile_regressions import RANGES, TABLE1, kept, lidar
from _probe_worker import call


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
