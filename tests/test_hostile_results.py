"""What results of sane calls say about themselves: full_overlap_range of a curve short of its
limit warns or is NaN, of a complete curve is a range without warning; and the 2-D FO path gives
the same bits for any thread count and in another process.
"""

import math

import numpy as np
from _hostile_regressions import TABLE1, kept, lidar
from _probe_runner import ProbeRunner, describe
from _probe_worker import FINITE, Attr, call


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
