"""Tolerance studies: G(z) of many systems drawn around one, and its percentiles, computed through
Dask.

:func:`tolerance_study` draws every member up front
(:mod:`lidar_overlap.analysis.studies.distributions`), so the result depends on the system, the
distributions, n, the ranges, the method and the seed only: not on the chunk size nor on where the
members run. Each member is planned from its own system and run by :func:`lidar_overlap.run`.

Where they run:

- ``client=`` a ``dask.distributed.Client``: chunks of members are tasks on that cluster;
- else, with dask installed: dask's threaded scheduler in this process (no set-up; the core releases
  the GIL), ``threads`` members at once (its synchronous scheduler for one);
- else a plain loop, one member after the other.

Threads: members that run at the same time each pass ``threads=1`` to the core (N callers with
threads=0
would start N teams of all cores: the core's threading contract). The plain loop gives the core
``threads`` only when a member takes :data:`TASK_SECONDS` or more: for the short calls of most
studies an OpenMP team per call costs more than it saves (RT, 60 ranges: 12 ms per member with 2
threads, 1 ms with 1, on 2 busy cores). Results do not depend on it.
"""

from __future__ import annotations

import time
from typing import Any, List, Mapping, Sequence

import numpy as np

from ... import _checks
from ...forward.compute import run
from ...forward.methods import Turbulent
from ...forward.planning import plan
from ...model import parameters
from ...model.system import LidarSystem
from .. import engines
from ..datasets import xarray
from ..engines import TASK_SECONDS, run_tasks
from .distributions import draw, normalized, text

#: Most members a study may have (the draws alone are 8 bytes x n x parameters).
MAX_MEMBERS = 10**7


def tolerance_study(
    system: LidarSystem,
    distributions: Mapping[str, Any],
    n: int,
    ranges,
    *,
    method="rt",
    percentiles: Sequence[float] = (5, 50, 95),
    seed: int = 0,
    client=None,
    chunk: int | None = None,
    threads: int = 0,
):
    """G(z) of ``n`` systems drawn around ``system``, and its percentiles per range (needs ``[io]``;
    ``[dask]`` to run in parallel).

    Parameters
    ----------
    distributions : parameter path -> distribution of the *offset* from the system's value
        (:mod:`lidar_overlap.analysis.studies.distributions`): ``("normal", mean_offset, sd)``,
        ``("uniform", low, high)`` or an object with ``rvs(size, random_state)`` (a frozen
        ``scipy.stats`` distribution). SI units.
    n : members, 1 to :data:`MAX_MEMBERS`.
    ranges : m, as for :func:`lidar_overlap.overlap`.
    method : ``"rt"``, ``"fo"``, ``"auto"`` or an RT, FO or Auto object; each member gets its own
        plan.
    percentiles : in [0, 100], of G over the members at each range (``numpy.percentile``, linear).
    seed : of the one ``numpy.random.Generator`` every draw comes from.
    client : a ``dask.distributed.Client`` to run on; None runs in this process (see the module).
    chunk : members per task; None: as many as run for :data:`TASK_SECONDS` (timed on the first
        members, which run here), but no more than spreads the members over every worker.
    threads : cores used in this process, 0 for all; ignored with a client (its workers' threads
        decide).

    Returns an ``xarray.Dataset``: ``overlap`` (member x range), ``value`` (member x parameter: the
    drawn values, SI), ``nominal`` (parameter), ``overlap_percentile`` (percentile x range);
    attributes n, seed, method, distributions (text), members_per_task and engine. A member whose
    draw makes an invalid system (or range) is an error naming the member and the parameter; none is
    dropped.
    """
    xr = xarray("tolerance_study")  # before any work: the result needs it
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    n = _checks.count("n", n, 1, MAX_MEMBERS)
    seed = _checks.count("seed", seed, 0)
    q = _percentiles(percentiles)
    threads = _checks.threads(threads)
    chunk = None if chunk is None else _checks.count("chunk", chunk, 1, MAX_MEMBERS)
    specs = normalized(system, distributions)
    nominal_plan = plan(system, ranges, method, threads=1)  # checks ranges and method once, by name
    if isinstance(nominal_plan.request, Turbulent):
        raise ValueError(
            "method = Turbulent(...) is invalid in a tolerance study: expected RT, FO or Auto (a "
            "turbulent mean per member is a study of its own)"
        )
    z, request = nominal_plan.ranges, nominal_plan.request
    # G three times at the peak (the chunks, their concatenation, numpy.percentile's sorted copy),
    # draws twice
    _checks.check_memory(
        "n", n, 8.0 * n * (3 * z.size + 2 * len(specs)), "lower n or the number of ranges"
    )
    engine = engines.engine(client)

    values = draw(specs, n, np.random.default_rng(seed))
    paths = [p for p, _, _ in specs]
    for i in range(
        n
    ):  # every member checked before any runs; not kept (~1 KB each): built where it runs
        _member(system, paths, values[i], i)

    head, seconds = _head(system, paths, values, z, request)
    done, workers = len(head), engines.workers(client, threads)
    if chunk is None:
        chunk = engines.items_per_task(seconds, n - done, workers)
    bounds = [(s, min(s + chunk, n)) for s in range(done, n, chunk)]
    loop_threads = threads if seconds >= TASK_SECONDS else 1
    parts = _compute(
        engine, client, bounds, system, (paths, values, z, request), loop_threads, workers
    )
    g = np.concatenate([head] + parts)

    method_text = repr(request)
    return xr.Dataset(
        {
            "overlap": (
                ("member", "range"),
                g,
                {"units": "1", "long_name": "lidar overlap function of each member"},
            ),
            "value": (
                ("member", "parameter"),
                values,
                {"long_name": "drawn value of each parameter (SI units)"},
            ),
            "nominal": (
                "parameter",
                np.array([v for _, v, _ in specs]),
                {"long_name": "the system's value of each parameter (SI units)"},
            ),
            "overlap_percentile": (
                ("percentile", "range"),
                np.percentile(g, q, axis=0),
                {"units": "1", "long_name": "percentile of the overlap over the members"},
            ),
        },
        coords={
            "member": np.arange(n),
            "range": ("range", z, {"units": "m"}),
            "parameter": paths,
            "percentile": ("percentile", q, {"units": "%"}),
        },
        attrs={
            "title": "Lidar overlap tolerance study",
            "n": n,
            "seed": seed,
            "method": method_text,
            "distributions": "; ".join(f"{p}: {text(d)}" for p, _, d in specs),
            "members_per_task": chunk,
            "engine": engine,
        },
    )


def _percentiles(value) -> np.ndarray:
    try:
        q = np.asarray([_checks.real("percentiles", v) for v in value], dtype=float)
    except TypeError:
        raise ValueError(
            f"percentiles = {_checks.shown(value)} is invalid: expected a sequence of numbers in "
            "[0, 100]"
        ) from None
    if q.size == 0 or not np.all((q >= 0) & (q <= 100)):
        raise ValueError(
            f"percentiles = {_checks.shown(value)} is invalid: expected a non-empty sequence of "
            "numbers in [0, 100]"
        )
    return q


def _member(system, paths: List[str], row: np.ndarray, index: int) -> LidarSystem:
    """Member ``index``: ``system`` with the drawn ``row``; an invalid one named by member and
    parameter."""
    try:
        return parameters.replace(system, dict(zip(paths, row.tolist())))
    except ValueError as exc:
        culprits = [
            f"{p} = {v!r}" for p, v in zip(paths, row.tolist()) if not _valid(system, {p: v})
        ]
        drawn = ", ".join(culprits) or "the combination " + ", ".join(
            f"{p} = {v!r}" for p, v in zip(paths, row)
        )
        raise ValueError(
            f"member {index}: the draw {drawn} (from distributions) makes an invalid system: {exc}"
        ) from None


def _valid(system, values) -> bool:
    try:
        parameters.replace(system, values)
    except ValueError:
        return False
    return True


def _head(system, paths, values, z, request):
    """G of the first members, run here one by one for TASK_SECONDS / 10 (at least one, at most 16),
    and the
    time per member that sizes the chunks: one call alone is too noisy a measure on a busy
    machine."""
    rows, start = [], time.perf_counter()
    while len(rows) < min(16, len(values)) and (
        not rows or time.perf_counter() - start < TASK_SECONDS / 10
    ):
        k = len(rows)
        rows.append(_chunk(system, paths, values[k : k + 1], z, request, 1, k)[0])
    return np.array(rows), (time.perf_counter() - start) / len(rows)


def _chunk(system, paths, values, z, request, threads: int, start: int) -> np.ndarray:
    """G of members ``start, start + 1, ...`` (rows), each built from ``system`` and its draw, and
    planned from its own system; an error names the member."""
    out = np.empty((len(values), z.size))
    for k, row in enumerate(values):
        member = _member(system, paths, row, start + k)
        try:
            out[k] = run(plan(member, z, request, threads=threads)).overlap
        except ValueError as exc:
            raise ValueError(f"member {start + k}: {exc}") from None
    return out


def _compute(kind, client, bounds, system, members, loop_threads, parallel) -> list:
    """The members' curves, chunk by chunk (``bounds``) on the engine ``kind``; ``members``: (paths,
    their values per member, ranges, method request)."""
    paths, values, z, request = members
    threads = loop_threads if kind == "loop" else 1
    return run_tasks(
        kind,
        client,
        _chunk,
        system,
        [(paths, values[s:e], z, request, threads, s) for s, e in bounds],
        parallel,
    )
