"""``lo.fit``: free scalars of a lidar system fitted to a measured overlap curve. The arguments
become one checked :class:`~lidar_overlap.analysis.fitting.problem.FitProblem`, which goes to one
strategy: absolute data from the start to the local least-squares fit
(:mod:`~lidar_overlap.analysis.fitting.solve`, the driver every fit shares), relative data to
:mod:`~lidar_overlap.analysis.fitting.relative`, the global search and the model ladder to
:mod:`~lidar_overlap.analysis.fitting.global_search` and
:mod:`~lidar_overlap.analysis.fitting.ladder`."""

from __future__ import annotations

import inspect
from typing import Union

from .global_search import fit_global
from .ladder import LadderResult, fit_ladder
from .problem import DEFAULT_FREE, FitProblem, fit_problem
from .relative import polish
from .result import FitResult


def fit(
    system, ranges, measured, sigma=None, free=DEFAULT_FREE, **options
) -> Union[FitResult, LadderResult]:
    """Fit the ``free`` scalars of ``system`` (its values are the start) to ``measured`` G at
    ``ranges``.

    ranges : m, strictly increasing. measured : G at each range. sigma : 1-sigma error of each point
    (a scalar or one per range, > 0); None: unit weights, covariance scaled by the reduced
    chi-square. free : parameter paths (``"beam.tilt"`` stands for both components). bounds :
    {path: (low, high)} in SI units, replacing the defaults for those paths: the system's
    ``fit_bounds`` (an instrument preset's), else
    :func:`lidar_overlap.model.parameters.default_bounds`; the start must lie within. method :
    ``"rt"``, ``"fo"``, ``"auto"`` or a method object, planned once on the start (module
    docstring). tolerance : the model's absolute tolerance on G (RT and auto; None: RT's
    default); keep it below 0.1 x the median sigma (warned otherwise). loss : as in least_squares
    (``"soft_l1"``, ``"huber"``, ``"cauchy"``, ``"arctan"`` resist outliers; the residual scale is
    1 sigma). max_evaluations : most model evaluations. allow_unconverged : return a result with
    ``converged=False`` instead of raising RuntimeError when the optimiser stops short. Every
    argument is checked before any fit runs; ``free`` and those before it may be given by position,
    the others by name.

    normalize : None (absolute G), ``(z_low, z_high)`` in m or ``"far"``: relative data, model and
    data each normalised (:mod:`lidar_overlap.analysis.fitting.relative`; returns a
    ``RelativeFitResult``).
    search : ``"local"`` (from the start) or ``"global"`` (a seeded population search over the
    bounds, then the local fit: :mod:`lidar_overlap.analysis.fitting.global_search`; returns a
    ``GlobalFitResult``). seed : the global search's seed (None: 0); population, generations,
    minima : its candidates per generation (None: 5 per free parameter, at least 15), most
    generations (40) and distinct minima polished (3). ``free="auto"``: a ladder of
    model families fitted in turn and chosen by BIC (needs sigma;
    :mod:`lidar_overlap.analysis.fitting.ladder`; returns a ``LadderResult``).

    extinction_bias : True fits, with ``normalize=(z_low, z_high)``, the error δα (1/m) of the
    extinction the retrieval of relative data assumed: the model is multiplied by
    exp(-2 δα (z - z_ref)) before normalising, δα within ±1e-4 /m and profiled out for each curve
    (:mod:`lidar_overlap.analysis.fitting.normalization`; reported as ``extinction_bias`` with its
    uncertainty). It describes the retrieval, not the instrument; with ``free="auto"`` every family
    carries it.

    Needs scipy (``pip install 'lidar-overlap[fit]'``). Warns :class:`DegeneracyWarning` naming each
    pair of parameters whose ``|correlation|`` exceeds 0.95. Returns a :class:`FitResult`.
    """
    problem = fit_problem(system, ranges, measured, sigma, free, **options)
    return run_strategy(problem)


# lo.fit's keywords are fit_problem's: help() and IDEs show them from the one signature
fit.__signature__ = inspect.signature(fit_problem).replace(  # type: ignore[attr-defined]
    return_annotation="Union[FitResult, LadderResult]"
)


def run_strategy(problem: FitProblem) -> Union[FitResult, LadderResult]:
    """The fit of ``problem`` by its strategy: the model ladder (``free="auto"``), the global
    search, or the local fit (relative or absolute)."""
    if problem.free == "auto":
        return fit_ladder(problem)
    if problem.search.kind == "global":
        return fit_global(problem)
    return polish(problem)
