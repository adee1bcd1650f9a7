"""Turbulence realisations through Dask: the draws of ``lo.overlap(system, ranges,
lo.Turbulent(...))`` split into tasks, on one machine or many, bit for bit the single call's.

A turbulent run is a fixed sequence of realisations, set by its seed: the FO path's realisation k
takes the phase screens (seed, k) whatever else the call computes (the core's
``first_realization``), and the RT path draws every wander offset up front from
``numpy.random.default_rng(seed)``, so a task computes any slice of them. The rows are gathered in
order and the statistics made once, over all of them, as ``lo.overlap`` makes
them: the
result does not depend on the chunk size nor on where the tasks ran.

Where they run (:mod:`lidar_overlap.analysis.engines`, as for
:func:`lidar_overlap.tolerance_study`):

- ``client=`` a ``dask.distributed.Client``: chunks of realisations are tasks on that cluster;
- else, with dask installed: dask's threaded scheduler in this process, ``threads`` tasks at once;
- else (no dask) one core call in this process, its threads over the realisations, as ``lo.overlap``
  makes it (or one call per chunk, with ``chunk``).

Task size: each core call makes its set-up once, then its realisations, each costing the same (the
FO path's set-up, a coupling map per range and a screen generator per screen, takes as long as 3 to
20
realisations: 0.05 s
for a 64² beam grid and 4 ranges, 0.5 s for 256² and 20 ranges, on one core). Unless ``chunk`` is
given, the first realisation runs here (on ``threads``) and the others are spread evenly over the
workers, one task each, in tasks of no less than
:data:`~lidar_overlap.analysis.engines.TASK_SECONDS` at that realisation's time: the set-up is then
made once per worker, as by one call per machine. (A tolerance study's members share no set-up: it
cuts them into many tasks of ~0.1 s instead.) A smaller ``chunk`` balances the load on a cluster of
unequal workers.
"""

from __future__ import annotations

import math
import time
from typing import cast

import numpy as np

from ... import _checks
from ...forward.backends import many
from ...forward.compute import run
from ...forward.methods import Turbulent
from ...forward.planning import plan
from ...forward.result import BAND, MAX_REALIZATIONS, TurbulentOverlapResult
from ...model.system import LidarSystem
from .. import engines
from ..datasets import range_coordinate, xarray

#: Most realisations a study may have: the core's bound on one turbulent run.


def turbulent_realizations(
    system: LidarSystem,
    ranges,
    method: Turbulent,
    *,
    client=None,
    chunk: int | None = None,
    threads: int = 0,
):
    """The realisations of ``lo.overlap(system, ranges, method)`` and their statistics, computed as
    tasks through Dask (needs ``[io]``; ``[dask]`` to run them in parallel).

    Parameters
    ----------
    system : a LidarSystem (a Gaussian beam; no aperture mask or receiver aberrations, as for any
        turbulent overlap).
    ranges : m, as for :func:`lidar_overlap.overlap`.
    method : a :class:`lidar_overlap.Turbulent`: the turbulence, the model (RT, FO or Auto, planned
        once, as ``lo.overlap`` plans it), realisations K (up to :data:`MAX_REALIZATIONS`), seed and
        screens.
    client : a ``dask.distributed.Client`` to run on; None runs in this process (see the module).
    chunk : realisations per task, 1 to :data:`MAX_REALIZATIONS`; None: the realisations after the
        first, which runs here, spread evenly over the workers in tasks of at least 0.1 s (see the
        module).
    threads : cores used in this process, 0 for all; with a client only by the first realisation,
        timed here (the workers' threads decide).

    Returns an ``xarray.Dataset``, bit for bit ``lo.overlap(system, ranges, method)``: ``overlap``
    (realization x range, G of each draw of the atmosphere), and per range ``mean`` (the overlap G),
    ``standard_error`` (of the mean), ``std`` (over the draws, ddof=1; 0 for one draw), ``low`` and
    ``high`` (the 5 and 95 % percentiles); the attributes realizations, seed, screens, method, model
    (``"rt"`` or ``"fo"``), turbulence, error_kind, engine and realizations_per_task.
    """
    xr = xarray("turbulent_realizations")  # before any work: the result needs it
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    if not isinstance(method, Turbulent):
        raise ValueError(
            f"method = {_checks.shown(method)} is invalid: expected a lidar_overlap.Turbulent (the "
            "turbulence, the model, realizations, seed)"
        )
    threads = _checks.threads(threads)
    chunk = None if chunk is None else _checks.count("chunk", chunk, 1, MAX_REALIZATIONS)
    kind = engines.engine(client)
    p = plan(
        system, ranges, method, threads=threads
    )  # checks ranges, the turbulence and the model by name
    k, z = method.realizations, p.ranges

    if not many.turbulent(p):  # no turbulence on the path: the plain curve
        res, kind, chunk = cast(TurbulentOverlapResult, run(p)), "loop", k
    else:
        drawn = many.turbulent_draws(p)  # checks the count and the memory, as lo.overlap does
        for message in p.warnings:
            _checks.warn(message)
        parts, chunk = _rows(kind, client, system, p, drawn, chunk, threads)
        res = many.turbulent_result(p, parts)

    unit = {"units": "1"}
    amplification = {}
    if res.amplification is not None:
        amplification["amplification"] = (
            "range",
            res.amplification,
            {
                **unit,
                "long_name": "backscatter amplification: mean overlap over the mean with "
                "uncorrelated paths",
            },
        )
    return xr.Dataset(
        {
            "overlap": (
                ("realization", "range"),
                res.realizations,
                {
                    **unit,
                    "long_name": "lidar overlap function in each realisation of the atmosphere",
                },
            ),
            "mean": (
                "range",
                res.overlap,
                {**unit, "long_name": "mean overlap over the realisations"},
            ),
            "standard_error": (
                "range",
                res.error_estimate,
                {**unit, "long_name": "standard error of the mean"},
            ),
            "std": (
                "range",
                res.std,
                {**unit, "long_name": "standard deviation over the realisations (ddof=1)"},
            ),
            "low": (
                "range",
                res.low,
                {
                    **unit,
                    "percentile": BAND[0],
                    "long_name": "percentile of the overlap over the realisations",
                },
            ),
            "high": (
                "range",
                res.high,
                {
                    **unit,
                    "percentile": BAND[1],
                    "long_name": "percentile of the overlap over the realisations",
                },
            ),
            **amplification,
        },
        coords={"realization": np.arange(k), "range": range_coordinate(z)},
        attrs={
            "title": "Lidar overlap through a turbulent atmosphere",
            "realizations": k,
            "seed": method.seed,
            "screens": method.screens,
            "paths": method.paths,
            "method": repr(method),
            "model": p.method,
            "computed_by": p.engine.description,
            "turbulence": repr(method.turbulence),
            "error_kind": p.error_kind,
            "engine": kind,
            "realizations_per_task": chunk,
        },
    )


def _rows(kind, client, system, p, drawn, chunk, threads):
    """The rows of every realisation, as (G, RT convergence flags, RT error estimates, FO's
    uncorrelated G) per part in order, and the realisations per task."""
    k, request, z = p.turbulence.realizations, p.request, p.ranges
    if kind == "loop" and chunk is None:  # one call: the core's threads over the realisations
        return [_part(system, z, request, threads, 0, k, drawn)], k
    head, done = [], 0
    if chunk is None:  # time the first realisation, here (its set-up on this process's threads)
        start = time.perf_counter()
        head, done = [_part(system, z, request, threads, 0, 1, drawn)], 1
        seconds, parallel = time.perf_counter() - start, engines.workers(client, threads)
        chunk = max(
            1,
            math.ceil(engines.TASK_SECONDS / max(seconds, 1e-9)),
            math.ceil((k - done) / parallel),
        )
    one = threads if kind == "loop" else 1
    bounds = [(s, min(s + chunk, k)) for s in range(done, k, chunk)]
    parts = engines.run_tasks(
        kind,
        client,
        _part,
        system,
        [(z, request, one, s, e - s, drawn) for s, e in bounds],
        engines.workers(client, threads),
    )
    return head + parts, chunk


def _part(system, z, request, threads: int, first: int, count: int, drawn):
    """Rows first .. first + count - 1 of the run (the task), planned here as the caller planned
    it: (G, and for RT the core's convergence flags and error estimates, else None)."""
    return many.turbulent_rows(plan(system, z, request, threads=threads), first, count, drawn)
