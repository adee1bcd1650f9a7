"""Ctrl-C that is never lost in a long call made of many steps (studies, task runners, loops).

Python raises KeyboardInterrupt where the main thread happens to be when SIGINT arrives. Two
places lose it: code that cannot raise (a weakref callback or ``__del__``: Python prints
"Exception ignored" and goes on), and worker threads (Dask's), which never see signals, so their
core calls run to the end. Within :func:`interruptible`, SIGINT also sets a flag that every core
call in any thread asks (``_core._set_interrupt_requested``), and the block ends with
KeyboardInterrupt even if the first one was swallowed. :func:`check` raises it at the next step
of a Python loop.
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager
from typing import Iterator

from . import _core

_state = threading.local()
_requested = {"on": False}


def check() -> None:
    """KeyboardInterrupt if SIGINT arrived within :func:`interruptible` (call between steps)."""
    if _requested["on"]:
        raise KeyboardInterrupt


@contextmanager
def interruptible() -> Iterator[None]:
    """Within: SIGINT raises KeyboardInterrupt as usual, stops core calls in every thread, and
    ends the block with KeyboardInterrupt even if the first one was swallowed. Only the main
    thread can install the handler, and only the default one is replaced (a caller's own SIGINT
    handler is left alone); elsewhere, and when nested, the block changes nothing."""
    if (
        threading.current_thread() is not threading.main_thread()
        or getattr(_state, "active", False)
        or signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    ):
        yield
        return

    def handler(signum, frame):
        _requested["on"] = True
        _core._set_interrupt_requested(True)
        raise KeyboardInterrupt

    _state.active = True
    signal.signal(signal.SIGINT, handler)
    try:
        yield
        check()  # the interrupt was swallowed on the way: raise it now
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)
        _requested["on"] = False
        _core._set_interrupt_requested(False)
        _state.active = False
