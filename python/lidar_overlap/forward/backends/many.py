"""One plan over many variants (the runner the analyses use): the systems of a sensitivity, a fit's
Jacobian, an optimisation's candidates or a study's draws, each G bit for bit what a single run of
the plan re-targeted at that system gives (:meth:`lidar_overlap.Plan.with_system`).

Ray tracing runs every variant in one parallel core call (:mod:`.batch`), a beam of incoherent
components too (every component of every variant in the call); other backends run the re-targeted
plan for each variant in turn.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from ...model.system import LidarSystem
from . import BACKENDS
from . import run as run_plan
from . import turbulent as turbulent_backend
from ._result import result
from .batch import Curves, grid, one_call, pairs, through_masks, warn_rt

__all__ = [
    "Curves",
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

#: Backends whose variants go through one batched core call.
BATCHED = ("rt",)


def systems(plan, variants: Sequence[LidarSystem], warn: bool = True) -> Curves:
    """G of each system in ``variants`` (systems of the kind ``plan.system`` is: shifted,
    misaligned, drawn) at ``plan.ranges``: shape (len(variants), ranges). ``warn=False`` keeps
    ray tracing's validity and convergence warnings back (a search's candidates, many of them far
    from the answer, whose own warnings are said)."""
    z = plan.ranges
    if _batched_mixture(plan):
        return _mixture_systems(plan, variants, warn)
    if plan.backend not in BATCHED:
        runs = [run_plan(plan.with_system(s)) for s in variants]
        shape = (len(runs), z.size)
        return Curves(
            np.array([r.overlap for r in runs]).reshape(shape),
            np.array([r.error_estimate for r in runs]).reshape(shape),
            np.ones(shape, dtype=bool),
        )
    for s in variants:
        plan.with_system(s)  # the same kind of system, or refused naming what changed
    natives = [s._native for s in variants for _ in z]
    flat = pairs(plan, natives, np.tile(z, len(variants)), warn=False)
    shape = (len(variants), z.size)
    if warn:
        warn_rt(plan, flat.converged, flat.error_estimate, np.tile(z, len(variants)))
    return Curves(
        flat.overlap.reshape(shape),
        flat.error_estimate.reshape(shape),
        flat.converged.reshape(shape),
    )


def _batched_mixture(plan) -> bool:
    """A mixture plan whose components all run plain ray tracing on the same options."""
    if plan.backend != "rt_mixture" or not plan.parts:
        return False
    first = plan.parts[0].options
    return all(
        p.backend in BATCHED
        and (p.options.tolerance, p.options.max_segments, p.options.threads)
        == (first.tolerance, first.max_segments, first.threads)
        for p in plan.parts
    )


def _mixture_systems(plan, variants: Sequence[LidarSystem], warn: bool) -> Curves:
    """:func:`systems` of a mixture plan: every component of every variant in one batched call,
    then each variant's components summed with its power shares (in the order
    :func:`.mixture.combine` sums them, so that G is bit for bit a single run's)."""
    split = [plan.with_system(s).system.incoherent_parts for s in variants]
    n = len(plan.parts)
    first = plan.component_plans()[0]
    flat = systems(first, [part for parts in split for _, part in parts], warn)
    shape = (len(variants), n, plan.ranges.size)
    g, e = flat.overlap.reshape(shape), flat.error_estimate.reshape(shape)
    overlap = np.empty((len(variants), plan.ranges.size))
    error = np.empty_like(overlap)
    for v, parts in enumerate(split):
        overlap[v] = sum(w * g[v, i] for i, (w, _) in enumerate(parts))
        error[v] = sum(w * e[v, i] for i, (w, _) in enumerate(parts))
    return Curves(overlap, error, np.asarray(flat.converged.reshape(shape).all(axis=1)))


def turbulent(plan) -> bool:
    """Whether ``plan`` draws realisations of a turbulent atmosphere (False for a turbulent request
    along a path without turbulence: every draw is the plain curve)."""
    return BACKENDS[plan.backend].turbulent


def turbulent_draws(plan):
    """What the realisations of a turbulent ``plan`` share, drawn up front so that any slice of them
    is computed bit for bit as the whole run computes it: for ray tracing the short-term beam radius
    per range (m) and every draw's wander offsets (m, realisations x ranges x 2); None for Fourier
    optics (its realisation k takes the screens (seed, k)); with both paths the RT radii are blurred
    and the offsets those of the image (:func:`turbulent_backend.draws`). The work is
    checked first (the count, and the memory of the draws)."""
    turbulent_backend.check_work(plan.ranges, plan.turbulence.realizations)
    return turbulent_backend.draws(plan) if plan.backend == "rt_turbulent" else None


def turbulent_rows(plan, first: int, count: int, drawn) -> tuple:
    """Realisations ``first .. first + count - 1`` of a turbulent ``plan``: (G, realisations x
    ranges; the RT convergence flags and error estimates, flat, or None for FO; FO's uncorrelated G
    through both paths, or None: RT's mean with uncorrelated paths is exact, made once by
    :func:`turbulent_result`). ``drawn``: what :func:`turbulent_draws` gave."""
    if drawn is None:
        g, uncorrelated = turbulent_backend.fo_rows(plan, first, count)
        return g, None, None, uncorrelated
    radii, offsets = drawn
    return turbulent_backend.rt_rows(plan, radii, offsets[first : first + count])


def turbulent_result(plan, parts):
    """The :class:`TurbulentOverlapResult` of all the realisations' rows, ``parts`` in order (from
    :func:`turbulent_rows`): RT's convergence warning once over all draws, then the statistics
    made over all rows at once, as ``lo.overlap`` makes them."""
    g = np.concatenate([part[0] for part in parts])
    if parts[0][1] is None:  # Fourier optics
        both = parts[0][3] is not None
        uncorrelated = np.concatenate([part[3] for part in parts]) if both else None
        return turbulent_backend.statistics(plan, g, uncorrelated)
    converged = [part[1] for part in parts]
    error = [part[2] for part in parts]
    mean_u, draws = None, g.shape[0]
    if plan.turbulence.paths == "both":  # its exact mean, here once, as lo.overlap computes it
        mean_u, more_converged, more_error = turbulent_backend.rt_uncorrelated_mean(plan)
        converged, error, draws = converged + [more_converged], error + [more_error], draws + 1
    warn_rt(plan, np.concatenate(converged), np.concatenate(error), np.tile(plan.ranges, draws))
    if mean_u is not None:
        turbulent_backend.warn_return_path(plan)
    return turbulent_backend.statistics(plan, g, uncorrelated_mean=mean_u)


def results(plan, variants: Sequence[LidarSystem], curves: Curves) -> list:
    """One :class:`OverlapResult` per variant from rows of ``curves`` (as :func:`systems` gives
    them), each stating what a run of ``plan`` re-targeted at that variant states."""
    return [
        result(plan.with_system(s), g, e)
        for s, g, e in zip(variants, curves.overlap, curves.error_estimate)
    ]
