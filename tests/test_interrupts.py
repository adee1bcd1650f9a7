"""Ctrl-C is never lost in long calls made of many steps: within _interrupts.interruptible(), a
KeyboardInterrupt swallowed on the way (a weakref callback, a bare except) is raised again when the
block ends, and SIGINT stops core calls running in worker threads, which never see signals."""

from __future__ import annotations

import os
import signal
import threading
import weakref

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _interrupts

#: Seconds a worker thread may take to stop after SIGINT: a generous bound against a hang, not a
#: latency measurement (tests/test_limits.py measures that in CPU time).
JOIN_LIMIT = 120.0

pytestmark = pytest.mark.skipif(not hasattr(signal, "SIGINT"), reason="needs SIGINT")


@pytest.fixture(autouse=True)
def default_sigint():
    """Python's own SIGINT handler, as in an interactive session: a job started in a shell's
    background (a CI runner) inherits SIGINT ignored, and the interpreter then installs none."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


def test_an_interrupt_swallowed_in_a_weakref_callback_is_raised_when_the_block_ends():
    class Thing:
        pass

    def callback(_):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            for _ in range(10**6):  # the handler runs here; the callback cannot raise
                pass
        except KeyboardInterrupt:
            pass

    with pytest.raises(KeyboardInterrupt):
        with _interrupts.interruptible():
            thing = Thing()
            ref = weakref.ref(thing, callback)  # noqa: F841
            del thing  # the callback runs and swallows the interrupt
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_core_call_in_a_worker_thread_stops_on_sigint():
    outcome = {}

    def work():
        try:
            lo.overlap(lo.paper_table1(), np.geomspace(50.0, 3000.0, 3_000_000), "rt", threads=1)
            outcome["end"] = "finished"
        except KeyboardInterrupt:
            outcome["end"] = "interrupted"

    with pytest.raises(KeyboardInterrupt):
        with _interrupts.interruptible():
            worker = threading.Thread(target=work)
            worker.start()
            try:
                os.kill(os.getpid(), signal.SIGINT)
                worker.join(JOIN_LIMIT)
            finally:
                worker.join(JOIN_LIMIT)
    assert outcome.get("end") == "interrupted"


def test_outside_the_main_thread_the_block_changes_nothing():
    seen = {}

    def other():
        with _interrupts.interruptible():
            seen["handler"] = signal.getsignal(signal.SIGINT)

    t = threading.Thread(target=other)
    t.start()
    t.join(JOIN_LIMIT)
    assert seen["handler"] is signal.default_int_handler
