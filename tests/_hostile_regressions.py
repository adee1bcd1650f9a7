"""Shared by the named regressions for hostile inputs (tests/test_hostile_*.py): the probes' parts
and the two verdicts they ask for. Each probe runs in the worker process of tests/_probe_runner.py,
so a crash fails its test instead of the session, and a hang is cut at the time limit (20 s).

The contract (tests/_probe_worker.py): a ValueError or TypeError naming a parameter the call set, or
a result whose numbers are finite with every overlap in [0, 1]. Where a test asks for more (the
parameter that must be named, the value that is correct), it says so.
"""

import math

from _probe_runner import describe
from _probe_worker import CLEAN_ERROR, FINITE, call, names_a_parameter

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
