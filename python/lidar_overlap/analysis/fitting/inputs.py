"""The numbers a fit takes from its caller (measured values and their sigma), checked strictly: real
numbers only (no complex value cut to its real part, no strings or booleans read as numbers), within
the bounds where the weighted residuals and their squares stay finite in double precision."""

from __future__ import annotations

import numpy as np

from ... import _checks

#: Largest |measured| value: G and telecover deviations are of order one, and squares of weighted
#: residuals must stay finite.
MAX_MEASURED = 1e6
#: sigma within these bounds keeps residuals / sigma and the Jacobian / sigma, and their squares,
#: finite and normal in double precision.
SIGMA_RANGE = (1e-100, 1e100)


def measured_array(name: str, value, expected: str) -> np.ndarray:
    """``value`` as a float array of real numbers, |x| <= MAX_MEASURED; ValueError naming ``name``
    (shape is the caller's check)."""
    try:
        y = _checks.real_array(name, value)
    except ValueError as exc:
        raise ValueError(f"{exc}; expected {expected}") from None
    big = np.isfinite(y) & (np.abs(y) > MAX_MEASURED)
    if big.any():
        i = np.unravel_index(int(np.argmax(big)), y.shape)
        index = ", ".join(map(str, i))
        raise ValueError(
            f"{name}[{index}] = {float(y[i])!r} is invalid: expected {expected}, of order one "
            f"(|value| <= {MAX_MEASURED:g})"
        )
    return y


def sigma_array(sigma, shape, expected_shape: str) -> np.ndarray:
    """``sigma`` broadcast to ``shape`` (a float array of real numbers); only the type and shape are
    checked here, the values by :func:`bad_sigma`."""
    try:
        w = _checks.real_array("sigma", sigma)
        return np.broadcast_to(w, shape).copy()
    except ValueError as exc:
        raise ValueError(
            f"sigma = {_checks.shown(sigma)} is invalid: expected None, a real number or "
            f"{expected_shape} ({exc})"
        ) from None


def bad_sigma(w: np.ndarray) -> np.ndarray:
    """Where sigma is not a finite value within SIGMA_RANGE."""
    return ~(np.isfinite(w) & (w >= SIGMA_RANGE[0]) & (w <= SIGMA_RANGE[1]))


SIGMA_EXPECTED = (
    f"finite values from {SIGMA_RANGE[0]:g} to {SIGMA_RANGE[1]:g} (the 1-sigma error of each "
    "point); use None for unit weights"
)
