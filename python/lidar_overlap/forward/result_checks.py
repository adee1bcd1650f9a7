"""The invariants of an overlap result's curve: finite increasing ranges, one G and one error per
range, G within [0, its bound] up to a fixed round-off; read-only copies of the arrays."""

from __future__ import annotations

import math

import numpy as np

from .. import _checks
from .._values import frozen

#: The one allowance for G outside [0, 1]: the round-off of a sum of up to ~10^6 order-one terms. It
#: is fixed, not the stated error or tolerance (a result stating an error of 1e300 would otherwise
#: pass any G); the engines clip their own accuracy before building a result.
ROUND_OFF = 1e-9
#: The models a result's curve comes from: ray tracing or Fourier optics.
METHODS = ("rt", "fo")


def checked_curve(ranges, overlap, method, error_estimate, tolerance, upper=1.0):
    """The invariants of :class:`~lidar_overlap.forward.result.OverlapResult`: the arrays as float
    arrays, G clipped within its slack, the tolerance as a float; ValueError naming what is wrong
    otherwise."""
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(
            f"method = {_checks.shown(method)} is invalid: expected the model that computed the "
            f"curve, one of {', '.join(map(repr, METHODS))}"
        )
    z, g, e = (
        _curve_array(name, value)
        for name, value in (
            ("ranges", ranges),
            ("overlap", overlap),
            ("error_estimate", error_estimate),
        )
    )
    if z.size == 0:
        raise ValueError("ranges is empty: expected at least one range (m)")
    for name, values in (("overlap", g), ("error_estimate", e)):
        if values.size != z.size:
            raise ValueError(
                f"{name} has {values.size} values for {z.size} ranges: expected one per range"
            )
    _first_bad("ranges", z, ~(np.isfinite(z) & (z > 0)), "expected a finite range > 0 (m)")
    if z.size > 1 and not np.all(np.diff(z) > 0):
        i = int(np.argmax(~(np.diff(z) > 0))) + 1
        raise _checks.refused(
            f"ranges[{i}]",
            float(z[i]),
            f"a range above {float(z[i - 1])!r} (strictly increasing)",
            f"ranges must be strictly increasing: ranges[{i}] = {float(z[i])!r} follows "
            f"{float(z[i - 1])!r}",
        )
    tolerance = _checks.real("tolerance", tolerance)
    if not (math.isnan(tolerance) or (math.isfinite(tolerance) and tolerance >= 0.0)):
        raise ValueError(
            f"tolerance = {tolerance!r} is invalid: expected a finite value >= 0, or NaN for none"
        )
    _first_bad(
        "error_estimate",
        e,
        ~(np.isnan(e) | (np.isfinite(e) & (e >= 0.0))),
        "expected a finite value >= 0, or NaN where the method gives none",
    )
    outside = ~((g >= -ROUND_OFF) & (g <= upper + ROUND_OFF))  # NaN is outside too
    if outside.any():
        i = int(np.argmax(outside))
        expected = f"G finite and within [0, {upper:g}] (up to round-off, {ROUND_OFF:g})"
        raise _checks.refused(
            f"overlap[{i}]",
            float(g[i]),
            expected,
            f"overlap[{i}] = {float(g[i])!r} at range {float(z[i])!r} m (method {method!r}) is "
            f"invalid: G must be finite and within [0, {upper:g}] (up to round-off, "
            f"{ROUND_OFF:g}); the computation failed at this range",
        )
    if g.min() < 0.0 or g.max() > upper:
        g = np.clip(g, 0.0, upper)
    return z, g, e, tolerance


def _curve_array(name: str, value) -> np.ndarray:
    """A read-only float copy of a 1-D array of real numbers; complex values, bools, strings and
    objects are refused (not cut to their real part or parsed)."""
    try:
        return frozen(_checks.real_array(name, value, ndim=1))
    except ValueError as exc:
        raise ValueError(
            f"{name} is invalid: expected a 1-D array of real numbers ({exc})"
        ) from None


def _first_bad(name: str, values: np.ndarray, bad: np.ndarray, expected: str) -> None:
    if bad.any():
        i = int(np.argmax(bad))
        item = f"{name}[{i}]"
        message = f"{item} = {float(values[i])!r} is invalid: {expected}"
        raise _checks.refused(item, float(values[i]), expected.removeprefix("expected "), message)
