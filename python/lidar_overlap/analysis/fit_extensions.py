"""Where :func:`lidar_overlap.fit` hands over when the data are relative, the search is global or
the model is chosen by the data (one hook, so the fit's own body stays the absolute local fit)."""

from __future__ import annotations

from .global_search import fit_global
from .model_ladder import fit_ladder
from .relative import fit_relative


def fit_extended(
    system,
    ranges,
    measured,
    sigma,
    free,
    bounds,
    method,
    tolerance,
    loss,
    max_evaluations,
    allow_unconverged,
    threads,
    normalize,
    search,
    seed,
):
    """:func:`lidar_overlap.fit` with ``normalize`` given, ``search="global"`` or
    ``free="auto"``."""
    if isinstance(free, str) and free == "auto":
        return fit_ladder(
            system,
            ranges,
            measured,
            sigma,
            bounds,
            method,
            tolerance,
            loss,
            max_evaluations,
            allow_unconverged,
            threads,
            normalize,
            seed,
        )
    if search == "global":
        return fit_global(
            system,
            ranges,
            measured,
            sigma,
            free,
            bounds,
            method,
            tolerance,
            loss,
            max_evaluations,
            allow_unconverged,
            threads,
            normalize,
            seed,
        )
    return fit_relative(
        system,
        ranges,
        measured,
        sigma,
        free,
        bounds,
        method,
        tolerance,
        loss,
        max_evaluations,
        allow_unconverged,
        threads,
        normalize,
    )
