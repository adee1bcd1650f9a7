"""A turbulent run in parts (the tasks of :mod:`lidar_overlap.analysis.studies.turbulence`): what
the realisations share, drawn up front; any slice of them, computed bit for bit as the whole run
computes it; and the result of all the slices, as ``lo.overlap`` makes it. One :class:`Draws` per
turbulent backend (:data:`RT` and :data:`FO`), named by its :class:`~.Backend`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Sequence, cast

import numpy as np

from ..result import TurbulentOverlapResult
from . import turbulent
from .batch import warn_rt
from .turbulent import Rows


@dataclass(frozen=True)
class Draws:
    """How a turbulent backend runs in parts: ``shared(plan)`` (what every part needs, checked for
    its work and memory first), ``rows(plan, first, count, shared)`` (realisations ``first ..
    first + count - 1`` as :class:`~.turbulent.Rows`), ``result(plan, parts)`` (the
    :class:`TurbulentOverlapResult` of all the rows, ``parts`` in order)."""

    shared: Callable[[Any], Any]
    rows: Callable[[Any, int, int, Any], Rows]
    result: Callable[[Any, Sequence[Rows]], TurbulentOverlapResult]


def _rt_shared(plan):
    """The short-term beam radius per range (m) and every draw's wander offsets (m, realisations x
    ranges x 2); with both paths the radii blurred and the offsets those of the image."""
    turbulent.check_work(plan.ranges, plan.turbulence.realizations)
    return turbulent.draws(plan)


def _fo_shared(plan) -> None:
    """Nothing: FO's realisation k takes the screens (seed, k)."""
    turbulent.check_work(plan.ranges, plan.turbulence.realizations)
    return None


def _rt_rows(plan, first: int, count: int, drawn) -> Rows:
    radii, offsets = drawn
    return turbulent.rt_rows(plan, radii, offsets[first : first + count])


def _fo_rows(plan, first: int, count: int, drawn) -> Rows:
    g, uncorrelated = turbulent.fo_rows(plan, first, count)
    return Rows(g, None, None, uncorrelated)


def _rt_result(plan, parts: Sequence[Rows]) -> TurbulentOverlapResult:
    """RT's convergence warning once over all draws, then the statistics over all rows at once;
    with both paths the exact mean of the uncorrelated paths, here once, as lo.overlap computes
    it."""
    g = np.concatenate([part.overlap for part in parts])
    converged = [cast(np.ndarray, part.converged) for part in parts]
    error = [cast(np.ndarray, part.error_estimate) for part in parts]
    mean_u, draws = None, g.shape[0]
    if plan.turbulence.paths == "both":
        mean_u, more_converged, more_error = turbulent.rt_uncorrelated_mean(plan)
        converged, error, draws = converged + [more_converged], error + [more_error], draws + 1
    warn_rt(plan, np.concatenate(converged), np.concatenate(error), np.tile(plan.ranges, draws))
    if mean_u is not None:
        turbulent.warn_return_path(plan)
    return turbulent.statistics(plan, g, uncorrelated_mean=mean_u)


def _fo_result(plan, parts: Sequence[Rows]) -> TurbulentOverlapResult:
    g = np.concatenate([part.overlap for part in parts])
    both = parts[0].uncorrelated is not None
    uncorrelated = (
        np.concatenate([cast(np.ndarray, part.uncorrelated) for part in parts]) if both else None
    )
    return turbulent.statistics(plan, g, uncorrelated)


#: Ray tracing of the wandering beam.
RT = Draws(_rt_shared, _rt_rows, _rt_result)
#: Fourier optics through phase screens.
FO = Draws(_fo_shared, _fo_rows, _fo_result)
