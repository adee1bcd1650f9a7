"""The inputs of ``lo.fit_drift`` checked, each error naming its argument: the series of curves,
the covariate, the curves' 1-sigma errors and the paths offset at the reference."""

from __future__ import annotations

import numpy as np

from ... import _checks
from .multi_inputs import checked_paths
from .problem import measured_values

#: The covariate's spread (max - min, its unit) a slope's variance (squared per unit) survives.
SPREAD = (1e-100, 1e100)


def checked_series(curves, z) -> np.ndarray:
    """``curves`` as (n_curves, n_ranges) G on ranges ``z`` (m), at least two, each measured."""
    try:
        y = _checks.real_array("curves", curves, ndim=2)
    except ValueError as exc:
        raise ValueError(
            f"{exc}: expected (n_curves, n_ranges), curves of equal length (one G per range)"
        ) from None
    if y.shape[1] != z.size:
        raise ValueError(
            f"curves has shape {y.shape}: expected (n_curves, {z.size}), one G per range"
        )
    if y.shape[0] < 2:
        raise ValueError(
            f"curves holds {y.shape[0]} curve: a drift fit needs at least two; fit one curve with "
            "lo.fit"
        )
    for i in range(y.shape[0]):
        try:
            measured_values(y[i], z)
        except ValueError as exc:
            raise ValueError(f"curves[{i}]: {exc}") from None
    return y


def checked_covariate(covariate, n: int) -> np.ndarray:
    """One finite covariate value per curve (``n``), with a finite, nonzero spread."""
    c = _checks.real_array("covariate", covariate, ndim=1)
    if c.size != n:
        raise ValueError(f"covariate has {c.size} values: expected one per curve ({n})")
    c = _checks.finite_array("covariate", c, ndim=1)
    with np.errstate(over="ignore", invalid="ignore"):
        spread = np.ptp(c)
    if not np.isfinite(spread):
        raise ValueError(
            f"covariate spans {spread!r}: expected a spread that is a finite number (center "
            "or rescale the covariate)"
        )
    if 0 < spread < SPREAD[0] or spread > SPREAD[1]:
        raise ValueError(
            f"covariate spans {spread:g}: expected a spread from {SPREAD[0]:g} to {SPREAD[1]:g} "
            "in its unit (beyond it a slope's variance per unit squared leaves the floating-point "
            "range; give the covariate in another unit)"
        )
    if not np.ptp(c) > 0:
        raise ValueError(
            f"covariate is constant ({c[0]:g}): expected at least two different values, a drift "
            "needs a spread"
        )
    return c


def checked_sigma(sigma, shape) -> np.ndarray:
    """``sigma`` (required) broadcast to the curves' ``shape``."""
    if sigma is None:
        raise ValueError(
            "sigma = None is invalid: a drift fit weighs the curves by their noise; give the "
            "1-sigma error (a scalar, one per range or one per curve and range)"
        )
    try:
        return np.broadcast_to(_checks.real_array("sigma", sigma), shape).copy()
    except ValueError as exc:
        raise ValueError(
            f"sigma = {_checks.shown(sigma)} is invalid: expected a scalar, one per range or "
            f"{shape} ({exc})"
        ) from None


def checked_offsets(offsets, anchor, system, paths) -> tuple:
    """The checked ``reference_offsets``: free paths, and only with a reference."""
    if isinstance(offsets, (list, tuple)) and not offsets:
        return ()
    if anchor is None:
        raise ValueError(
            f"reference_offsets = {_checks.shown(offsets)} is invalid without a reference: give "
            "reference= or leave it empty"
        )
    out = checked_paths("reference_offsets", offsets, [system])
    among_free("reference_offsets", out, paths, "paths")
    return out


def among_free(name: str, asked, paths, what: str) -> None:
    """ValueError naming ``name`` unless every path ``asked`` is among the free ``paths`` (``what``
    the message calls them)."""
    outside = [p for p in asked if p not in paths]
    if outside:
        raise ValueError(
            f"{name}: {', '.join(outside)} is not free: expected {what} among free "
            f"({', '.join(paths)})"
        )
