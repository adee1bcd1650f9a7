"""``lo.fit_joint``: several curves fitted at once, each with its own system (its wavelength, its
channel's stop), its own normalisation, sigma and retrieval extinction bias, and parameters either
shared by all curves or each curve's own: the channels of one instrument share the optics, and each
constrains the geometry the other sees. The driver is :mod:`.multi_curve`; ``free="auto"`` chooses
the family and which of its parameters are per-curve (:mod:`.joint_auto`).

Names. A shared parameter is named by its path (``"beam.tilt[0]"``); a per-curve one by its path and
the curve's index from 0 (``"beam.divergence@1"``, curve 1's).
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from ... import _checks
from .joint_auto import fit_joint_auto
from .joint_result import JointFitResult, joint_result
from .multi_inputs import (
    checked_bounds,
    checked_curve,
    checked_paths,
    checked_systems,
    is_interval,
    joint_problem,
    multi_settings,
    one_per_curve,
)
from .multi_search import fit_curves
from .problem import GENERATIONS, MINIMA


def fit_joint(
    systems,
    ranges,
    curves,
    *,
    sigma,
    shared=None,
    per_curve=(),
    normalize=None,
    extinction_bias=False,
    free=None,
    method="auto",
    tolerance: Optional[float] = None,
    search: Optional[str] = None,
    seed: Optional[int] = None,
    bounds=None,
    loss: str = "linear",
    max_evaluations: int = 200,
    allow_unconverged: bool = False,
    threads: int = 0,
    population: Optional[int] = None,
    generations: int = GENERATIONS,
    minima: int = MINIMA,
) -> JointFitResult:
    """Fit several measured curves at once (module docstring).

    systems : one LidarSystem per curve (its values start the fit; a shared parameter starts at
    systems[0]'s). ranges, curves : one array each per curve (m; G or relative G). sigma : one
    entry per curve (a scalar or one per range, > 0): required, the curves are weighed by it.
    shared : paths fitted as one value for all curves; per_curve : paths fitted for each curve
    (``"beam.divergence"`` -> ``"beam.divergence@0"``, ``"@1"``, ...). normalize : None, "far",
    (z_low, z_high) in m for every curve, or a list of one per curve. extinction_bias : True fits
    each curve's retrieval extinction bias (with an interval normalisation; profiled per curve).
    free : ``"auto"`` chooses the family and which parameters are per-curve instead of ``shared``
    (:mod:`lidar_overlap.analysis.fitting.joint_auto`); ``per_curve`` then names the paths that may
    be per-curve (those the instrument's physics lets differ between the curves; empty: any).
    bounds : {path: (low, high)} in SI units for every curve's value of that path. method,
    tolerance, loss, max_evaluations, allow_unconverged, threads, search (None or "local": from
    the start; "global": one population search over the joint space, then the local fit), seed,
    population, generations, minima : as in :func:`lidar_overlap.fit`. Returns a
    :class:`JointFitResult`.
    """
    n = _count(curves)
    systems = checked_systems(systems, n)
    zs = per_curve_list("ranges", ranges, n)
    sigmas = per_curve_list("sigma", sigma, n)
    norms = one_per_curve("normalize", normalize, n, is_interval)
    data = tuple(
        checked_curve(i, zs[i], curves[i], sigmas[i], norms[i], extinction_bias) for i in range(n)
    )
    settings = multi_settings(
        systems[0], data, method=method, tolerance=tolerance, loss=loss,
        max_evaluations=max_evaluations, allow_unconverged=allow_unconverged, threads=threads,
        search=search, seed=seed, population=population, generations=generations, minima=minima,
    )  # fmt: skip
    auto = isinstance(free, str) and free == "auto"
    if free is not None and not auto:
        raise ValueError(
            f"free = {_checks.shown(free)} is invalid: expected None (give shared and per_curve) "
            "or 'auto'"
        )
    if auto:
        allowed = checked_paths("per_curve", per_curve, systems, allow_empty=True) or None
        settings = settings.derived(free=("beam.tilt[0]",))
        return fit_joint_auto(settings, systems, checked_bounds_any(bounds), allowed)
    if shared is None:
        raise ValueError("shared is missing: give the paths all curves share, or free='auto'")
    own = checked_paths("per_curve", per_curve, systems, allow_empty=True)
    shared_paths = checked_paths("shared", shared, systems, allow_empty=bool(own))
    both = set(shared_paths) & set(own)
    if both:
        raise ValueError(
            f"per_curve: {', '.join(sorted(both))} is also in shared: expected each path in one"
        )
    given = checked_bounds(bounds, shared_paths + own)
    settings = settings.derived(free=shared_paths + own)
    return joint_result(fit_curves(joint_problem(settings, systems, shared_paths, own, given)))


def checked_bounds_any(bounds) -> Optional[dict]:
    """``bounds`` for ``free="auto"``: checked when its family's paths are known."""
    if bounds is not None and not isinstance(bounds, dict):
        raise ValueError(
            f"bounds = {_checks.shown(bounds)} is invalid: expected a dict path -> (low, high)"
        )
    return bounds


def _count(curves) -> int:
    if not isinstance(curves, (list, tuple)) and not (
        isinstance(curves, np.ndarray) and curves.ndim == 2
    ):
        raise ValueError(
            f"curves = {_checks.shown(curves)} is invalid: expected one array of G per curve"
        )
    if len(curves) < 2:
        raise ValueError(
            f"curves holds {len(curves)} curve: a joint fit needs at least two; fit one curve "
            "with lo.fit"
        )
    return len(curves)


def per_curve_list(name: str, value, n: int) -> list:
    """``value`` as one entry per curve: a list/tuple of ``n`` (or a scalar ``sigma`` for all)."""
    if name == "sigma" and isinstance(value, (int, float)) and not isinstance(value, bool):
        return [value] * n
    return one_per_curve(name, value, n, lambda v: False)
