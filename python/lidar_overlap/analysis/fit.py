"""``lo.fit``: free scalars of a lidar system fitted to a measured overlap curve. Absolute data from
the start go to the local least-squares fit (:mod:`lidar_overlap.analysis.fit_solve`, the driver
every fit shares); relative data, the global search and the model ladder to their own modules
(:mod:`~lidar_overlap.analysis.relative`, :mod:`~lidar_overlap.analysis.global_search`,
:mod:`~lidar_overlap.analysis.model_ladder`)."""

from __future__ import annotations

from typing import Optional, Union

from .. import _checks
from .fit_result import FitResult
from .fit_solve import SEARCHES, fit_local
from .global_search import fit_global
from .model_ladder import LadderResult, fit_ladder
from .relative import fit_relative, with_extinction_bias


def fit(
    system,
    ranges,
    measured,
    sigma=None,
    free=("beam.tilt", "detector.defocus"),
    bounds=None,
    method="auto",
    tolerance: Optional[float] = None,
    loss: str = "linear",
    max_evaluations: int = 200,
    *,
    allow_unconverged: bool = False,
    threads: int = 0,
    normalize=None,
    search: str = "local",
    seed: Optional[int] = None,
    extinction_bias: bool = False,
) -> Union[FitResult, LadderResult]:
    """Fit the ``free`` scalars of ``system`` (its values are the start) to ``measured`` G at
    ``ranges``.

    ranges : m, strictly increasing. measured : G at each range. sigma : 1-sigma error of each point
    (a scalar or one per range, > 0); None: unit weights, covariance scaled by the reduced
    chi-square. free : parameter paths (``"beam.tilt"`` stands for both components). bounds :
    {path: (low, high)} in SI units, replacing :func:`default_bounds` for those paths; the start
    must lie within. method : ``"rt"``, ``"fo"``, ``"auto"`` or a method object, planned once on the
    start (module docstring). tolerance : the model's absolute tolerance on G (RT and auto; None:
    RT's default); keep it below 0.1 x the median sigma (warned otherwise). loss : as in
    least_squares (``"soft_l1"``, ``"huber"``, ``"cauchy"``, ``"arctan"`` resist outliers; the
    residual scale is 1 sigma). max_evaluations : most model evaluations. allow_unconverged : return
    a result with ``converged=False`` instead of raising RuntimeError when the optimiser stops
    short.

    normalize : None (absolute G), ``(z_low, z_high)`` in m or ``"far"``: relative data, model and
    data each normalised (:mod:`lidar_overlap.analysis.relative`; returns a ``RelativeFitResult``).
    search : ``"local"`` (from the start) or ``"global"`` (a seeded population search over the
    bounds, then the local fit: :mod:`lidar_overlap.analysis.global_search`; returns a
    ``GlobalFitResult``). seed : the global search's seed (None: 0). ``free="auto"``: a ladder of
    model families fitted in turn and chosen by BIC (needs sigma;
    :mod:`lidar_overlap.analysis.model_ladder`; returns a ``LadderResult``).

    extinction_bias : True fits, with ``normalize=(z_low, z_high)``, the error δα (1/m) of the
    extinction the retrieval of relative data assumed: the model is multiplied by
    exp(-2 δα (z - z_ref)) before normalising, δα within ±1e-4 /m and profiled out for each curve
    (:mod:`lidar_overlap.analysis.relative`; reported as ``extinction_bias`` with its uncertainty).
    It describes the retrieval, not the instrument; with ``free="auto"`` every family carries it.

    Needs scipy (``pip install 'lidar-overlap[fit]'``). Warns :class:`DegeneracyWarning` naming each
    pair of parameters whose ``|correlation|`` exceeds 0.95. Returns a :class:`FitResult`.
    """
    search = _checks.choice("search", search, SEARCHES)
    normalize = with_extinction_bias(normalize, extinction_bias)
    data = (system, ranges, measured, sigma)
    if isinstance(free, str) and free == "auto":
        return fit_ladder(
            *data, bounds, method, tolerance, loss, max_evaluations, allow_unconverged, threads,
            normalize, seed,
        )  # fmt: skip
    options = (free, bounds, method, tolerance, loss, max_evaluations)
    if search == "global":
        return fit_global(*data, *options, allow_unconverged, threads, normalize, seed)
    if normalize is not None:
        return fit_relative(*data, *options, allow_unconverged, threads, normalize)
    return fit_local(
        *data, free, bounds, method, tolerance, loss, max_evaluations,
        allow_unconverged=allow_unconverged, threads=threads,
    )  # fmt: skip
