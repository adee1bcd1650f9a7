"""Ctrl-C stops every long core call promptly: a call interrupted by SIGINT raises
KeyboardInterrupt and does less than INTERRUPT_CPU seconds of CPU work (all threads) after the
signal, whatever loop it is in (ranges, realisations, rows of a large grid, blocks of a transform).

CPU time, never the wall clock: the tests pass on a machine fully loaded by other jobs.
"""

import pytest
from _interrupted_run import INTERRUPT_CPU, LONG_CALLS, interrupted_run

CASES = [
    pytest.param(name, warm, id=f"{name}@{warm:g}s")
    for name, (_, _, warms) in LONG_CALLS.items()
    for warm in warms
]


@pytest.mark.parametrize("name, warm", CASES)
def test_ctrl_c_stops_a_long_call_within_a_second(name, warm):
    setup, call, _ = LONG_CALLS[name]
    run = interrupted_run(call, setup, warm_cpu=warm)
    assert "KeyboardInterrupt" in run.stderr and not run.finished, run.stderr[-2000:]
    assert run.cpu < INTERRUPT_CPU, f"used {run.cpu:.2f} CPU seconds after SIGINT"
