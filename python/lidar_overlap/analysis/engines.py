"""Where many independent tasks run: on a ``dask.distributed.Client`` (``client=``), in dask's
threaded scheduler in this process (dask installed, no set-up; the core releases the GIL), or in a
plain loop (no dask). Tasks run at the same time each pass ``threads=1`` to the core (its threading
contract: N callers with threads=0 start N teams of all cores); the results do not depend on where
they ran."""

from __future__ import annotations

import functools
import math
import os
from typing import Callable, Sequence

from .. import _checks, _interrupts

#: Each task runs about this long at least (s) when its size is left to the caller: scheduling a
#: task costs ~1 ms on a local cluster, so this keeps the overhead near 1 %.
TASK_SECONDS = 0.1


def engine(client) -> str:
    """``"distributed"``, ``"dask"`` or ``"loop"``; a client that is not a
    ``dask.distributed.Client`` is refused."""
    if client is not None:
        try:
            from distributed import Client
        except ImportError:
            raise ValueError(
                "client is given but dask.distributed is not installed: pip install "
                "'lidar-overlap[dask]'"
            ) from None
        if not isinstance(client, Client):
            raise ValueError(
                f"client = {_checks.shown(client)} is invalid: expected a dask.distributed.Client "
                "or None"
            )
        return "distributed"
    try:
        import dask  # noqa: F401  (only whether it is there)
    except ImportError:
        return "loop"
    return "dask"


def workers(client, threads: int) -> int:
    """Tasks that may run at once: the client's worker threads, else ``threads`` (0: the cores)."""
    if client is not None:
        return max(1, sum(client.nthreads().values()))
    return threads or os.cpu_count() or 1


def items_per_task(seconds_per_item: float, remaining: int, parallel: int) -> int:
    """Items per task: as many as run for :data:`TASK_SECONDS` at ``seconds_per_item``, but no more
    than spreads the ``remaining`` items over ``parallel`` workers; at least one."""
    return min(
        max(1, math.ceil(TASK_SECONDS / max(seconds_per_item, 1e-9))),
        max(1, math.ceil(remaining / parallel)),
    )


def run_tasks(
    kind: str, client, function: Callable, shared, arguments: Sequence[tuple], parallel: int
) -> list:
    """``[function(shared, *args) for args in arguments]``, in order, on the engine ``kind``.
    ``shared`` (a system: it pickles as its constructor arguments) goes to each cluster worker once.
    A task that fails raises its error here; when several fail, the first in order, as in the loop
    (not the first to fail in time)."""
    with _interrupts.interruptible():  # Ctrl-C reaches tasks in worker threads, and is not lost
        return _run_tasks(kind, client, function, shared, arguments, parallel)


def _run_tasks(kind, client, function, shared, arguments, parallel) -> list:
    if kind == "loop":
        out = []
        for args in arguments:
            _interrupts.check()
            out.append(function(shared, *args))
        return out
    if kind == "distributed":
        scattered = client.scatter(shared, broadcast=True)
        futures = [client.submit(function, scattered, *args, pure=False) for args in arguments]
        try:
            return client.gather(futures)
        except Exception:
            for (
                future
            ) in futures:  # waits for the tasks before the first that failed, not for those after
                future.result()
            raise
    import dask

    tasks = [
        dask.delayed(functools.partial(_caught, function, shared, *args), pure=False)()
        for args in arguments
    ]
    done = dask.compute(
        *tasks, scheduler="threads" if parallel > 1 else "sync", num_workers=parallel
    )
    for _, error in done:
        if error is not None:
            raise error
    return [value for value, _ in done]


def _caught(function: Callable, *args) -> tuple:
    """(function(*args), None), or (None, the exception) for run_tasks to raise in order."""
    try:
        return function(*args), None
    except Exception as exc:  # noqa: BLE001 (re-raised by run_tasks)
        return None, exc
