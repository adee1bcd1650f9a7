"""One plan over many variants (the runner the analyses use): the systems of a sensitivity, a fit's
Jacobian, an optimisation's candidates or a study's draws, each G bit for bit what a single run of
the plan re-targeted at that system gives (:meth:`lidar_overlap.Plan.with_system`).

A backend that can batch its variants (:attr:`~.Backend.run_many`: plain ray tracing, and a beam of
incoherent components that all run it) computes them in one parallel core call; other plans run
the re-targeted plan for each variant in turn. A turbulent plan runs in parts through its
backend's :attr:`~.Backend.draws`.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from ...model.system import LidarSystem
from . import backend
from . import run as run_plan
from ._result import result
from .batch import Curves, grid, one_call, pairs, through_masks
from .turbulent import Rows

__all__ = [
    "Curves",
    "Rows",
    "grid",
    "one_call",
    "pairs",
    "results",
    "systems",
    "through_masks",
    "turbulent",
    "turbulent_draws",
    "turbulent_result",
    "turbulent_rows",
]


def systems(plan, variants: Sequence[LidarSystem], warn: bool = True) -> Curves:
    """G of each system in ``variants`` (systems of the kind ``plan.system`` is: shifted,
    misaligned, drawn) at ``plan.ranges``: shape (len(variants), ranges). ``warn=False`` keeps
    ray tracing's validity and convergence warnings back (a search's candidates, many of them far
    from the answer, whose own warnings are said)."""
    run_many = backend(plan.backend).run_many
    batched = run_many(plan, variants, warn) if run_many is not None else None
    if batched is not None:
        return batched
    runs = [run_plan(plan.with_system(s)) for s in variants]
    shape = (len(runs), plan.ranges.size)
    return Curves(
        np.array([r.overlap for r in runs]).reshape(shape),
        np.array([r.error_estimate for r in runs]).reshape(shape),
        np.ones(shape, dtype=bool),
    )


def turbulent(plan) -> bool:
    """Whether ``plan`` draws realisations of a turbulent atmosphere (False for a turbulent request
    along a path without turbulence: every draw is the plain curve)."""
    return backend(plan.backend).turbulence


def turbulent_draws(plan):
    """What the realisations of a turbulent ``plan`` share, drawn up front so that any slice of them
    is computed bit for bit as the whole run computes it (the backend's
    :attr:`~.turbulent_parts.Draws.shared`). The work is checked first (the count, and the memory
    of the draws)."""
    return _draws(plan).shared(plan)


def turbulent_rows(plan, first: int, count: int, drawn) -> Rows:
    """Realisations ``first .. first + count - 1`` of a turbulent ``plan`` (:class:`Rows`).
    ``drawn``: what :func:`turbulent_draws` gave."""
    return _draws(plan).rows(plan, first, count, drawn)


def turbulent_result(plan, parts: Sequence[Rows]):
    """The :class:`TurbulentOverlapResult` of all the realisations' rows, ``parts`` in order (from
    :func:`turbulent_rows`), made as ``lo.overlap`` makes it."""
    return _draws(plan).result(plan, parts)


def _draws(plan):
    draws = backend(plan.backend).draws
    if draws is None:
        raise ValueError(
            f"plan.backend = {plan.backend!r} draws no turbulent atmosphere: expected a turbulent "
            "plan (check forward.backends.many.turbulent first)"
        )
    return draws


def results(plan, variants: Sequence[LidarSystem], curves: Curves) -> list:
    """One :class:`OverlapResult` per variant from rows of ``curves`` (as :func:`systems` gives
    them), each stating what a run of ``plan`` re-targeted at that variant states."""
    return [
        result(plan.with_system(s), g, e)
        for s, g, e in zip(variants, curves.overlap, curves.error_estimate)
    ]
