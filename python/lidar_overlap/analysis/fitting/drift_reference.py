"""The reference of a drift fit (``lo.fit_drift(..., reference=G_ref)``): a curve of the same
instrument (its factory curve, say) that the series' curves differ from by what the model changes.

The differential anchor. The instrument's curve is the model M plus a structure the model's family
cannot shape (a stop's edge, a window, the retrieval's own shape); it is the same on every day, so
it cancels in differences. The reference is taken as the instrument at one state on the drift line,
the covariate value c_ref (fitted, one coefficient): θ_ref = θ(c_ref). A day at covariate c is then

    G(c) = G_ref + M(θ(c)) - M(θ(c_ref)),

relative curves each normalised over the data's interval. The fixed parameters are fitted to the
days through the model's response to the drift, not to an absolute shape the family may miss.
``reference_offsets``: paths whose reference value also moves by its own offset from the drift
line (one coefficient each): θ_ref = θ(c_ref) + Σ d_p e_p, for a reference measured under other
conditions than the days (the factory's bench).

The reference's values are nonlinear in the fit's vector (slope x c_ref): :class:`ReferenceState`
gives them and their Jacobian in the vector, which the multi-curve driver applies where a curve's
map is linear (:mod:`lidar_overlap.analysis.fitting.curve_set`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Tuple

import numpy as np

from ... import _checks
from ...model import parameters as _parameters
from .drift_names import OFFSET, REFERENCE, SLOPE  # OFFSET, REFERENCE: importable here too


@dataclass(frozen=True, eq=False)
class ReferenceState:
    """The reference's state as a function of the fit's vector θ: its start ``system``, the free
    ``paths``, ``linear`` (len(paths), K) the part linear in θ (values at the covariate's mean and
    offsets), ``slopes`` (len(paths), K) selecting each drifting path's slope, ``index`` of c_ref in
    θ, ``center`` the covariate's mean, ``curve`` the reference on the measured ranges."""

    system: Any
    paths: Tuple[str, ...]
    linear: np.ndarray
    slopes: np.ndarray
    index: int
    center: float
    curve: np.ndarray

    def values(self, theta) -> np.ndarray:
        """The paths' values at the reference: linear @ θ + (c_ref - center) slopes @ θ."""
        t = np.asarray(theta, dtype=float)
        return self.linear @ t + (t[self.index] - self.center) * (self.slopes @ t)

    def matrix(self, theta) -> np.ndarray:
        """d values / dθ, (len(paths), K)."""
        t = np.asarray(theta, dtype=float)
        m = self.linear + (t[self.index] - self.center) * self.slopes
        m[:, self.index] += self.slopes @ t
        return m

    def at(self, theta):
        """The reference's system at θ."""
        values = self.values(theta).tolist()
        return _parameters.replace(self.system, dict(zip(self.paths, values)))


def reference_state(system, paths, names, moving, offsets, c, curve) -> ReferenceState:
    """The :class:`ReferenceState` of a drift problem whose vector holds ``names`` (the free
    ``paths``, the ``moving`` ones' slopes, then c_ref and the ``offsets``' offsets)."""
    k = len(names)
    linear, slopes = np.zeros((len(paths), k)), np.zeros((len(paths), k))
    linear[:, : len(paths)] = np.eye(len(paths))
    for p in moving:
        slopes[paths.index(p), names.index(p + SLOPE)] = 1.0
    for p in offsets:
        linear[paths.index(p), names.index(p + OFFSET)] = 1.0
    return ReferenceState(
        system, tuple(paths), linear, slopes, names.index(REFERENCE), float(c.mean()), curve
    )


def checked_reference(reference, z: np.ndarray, extinction_bias) -> np.ndarray:
    """The reference curve, one finite G per range of ``z``; ValueError naming ``reference``."""
    r = _checks.real_array("reference", reference, ndim=1)
    if r.size != z.size:
        raise ValueError(
            f"reference has {r.size} values: expected one G per range ({z.size}), the curve the "
            "days differ from on the same ranges"
        )
    r = _checks.finite_array("reference", r, ndim=1)
    if extinction_bias:
        raise ValueError(
            "reference with extinction_bias=True is not supported: each day's profiled "
            "extinction bias would not cancel against the reference; fit without it"
        )
    return r


def reference_bounds(names, paths, offsets, c, x0, low, high, scale, s_low, s_high) -> None:
    """Set, in place, the start, bounds, natural scale and search box of c_ref (the covariate's
    mean; within 5 spans of the series) and of each offset (0; within its path's bounds' width)
    among a drift problem's ``names``."""
    span = float(np.ptp(c))
    b = names.index(REFERENCE)
    x0[b], scale[b] = c.mean(), span
    low[b], high[b] = c.mean() - 5 * span, c.mean() + 5 * span
    s_low[b], s_high[b] = c.min(), c.max()
    for p in offsets:
        a, b = paths.index(p), names.index(p + OFFSET)
        low[b], high[b] = low[a] - high[a], high[a] - low[a]
        s_low[b], s_high[b] = s_low[a] - s_high[a], s_high[a] - s_low[a]
        scale[b] = scale[a]
