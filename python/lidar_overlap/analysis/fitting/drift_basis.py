"""How a drifting parameter depends on the covariate in ``lo.fit_drift``: its kind (``"linear"`` or
``"spline"``), the spline's knots, and the columns each kind adds to the fit's vector.

Linear: p(c) = a + b (c - c_ref), columns ``path`` (a) and ``path@slope`` (b).

Spline: a natural cubic spline in c with K knots t_0 < ... < t_{K-1} at the covariate's quantiles
0, 1/(K-1), ..., 1 (t_0 and t_{K-1} its smallest and largest value), written as
p(c) = a + b (c - c_ref) + sum_j g_j (N_j(c) - N_j(c_ref)), j = 1 .. K-2, where N_j is the natural
cubic spline (SciPy's ``CubicSpline``, ``bc_type="natural"``) that is 1 at the interior knot t_j
and 0 at the others. Each term beyond a vanishes at c_ref, and the g-terms take the same value at
t_0 and t_{K-1}, so that
- a is the value at c_ref, as for a linear drift;
- b (``path@slope``) is the mean slope over the covariate's span, (p(t_{K-1}) - p(t_0)) /
  (t_{K-1} - t_0), as for a linear drift, and its uncertainty is b's in the covariance;
- g_j (``path@knot[j]``) is the spline's departure at t_j from the chord through its end values;
- g = 0 is the linear drift: linear is the special case, K - 2 more coefficients (K >= 3).
Outside [t_0, t_{K-1}] a natural spline (zero curvature at its ends) continues linearly, with its
end slope; so does a linear drift, and predictions there are extrapolations (:func:`warn_outside`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import List, Sequence, Tuple

import numpy as np

from ... import _checks
from .drift_names import SLOPE, knot_name  # also importable from here, as before
from .multi_inputs import checked_paths

#: The kinds of drift.
LINEAR, SPLINE = "linear", "spline"
#: ``spline_knots``: K knots, K - 2 coefficients beyond the linear drift's two.
DEFAULT_KNOTS = 4
FEWEST_KNOTS = 3


def checked_drifting(drifting, systems) -> Tuple[Tuple[str, ...], Tuple[str, ...]]:
    """(the drifting scalar paths, those of them that are splines) of the ``drifting`` argument: a
    list of paths (each linear) or a mapping {path: "linear" | "spline"} (pairs expanded)."""
    if not isinstance(drifting, Mapping):
        return checked_paths("drifting", drifting, systems, allow_empty=True), ()
    paths: List[str] = []
    splines: List[str] = []
    for key, kind in drifting.items():
        if not isinstance(kind, str) or kind not in (LINEAR, SPLINE):
            raise ValueError(
                f"drifting[{key!r}] = {_checks.shown(kind)} is invalid: expected '{LINEAR}' or "
                f"'{SPLINE}'"
            )
        if not isinstance(key, str):
            raise ValueError(f"drifting key {_checks.shown(key)} is invalid: expected a path")
        for path in checked_paths("drifting", [key], systems):
            if path in paths:
                raise ValueError(f"drifting names {path} twice: expected each path once")
            paths.append(path)
            if kind == SPLINE:
                splines.append(path)
    return tuple(paths), tuple(splines)


def knots_at_quantiles(count, c: np.ndarray, splines: Sequence[str]) -> np.ndarray:
    """The knots (covariate values) of the spline drifts: ``count`` (the ``spline_knots``
    argument, an integer >= 3) quantiles of the covariate ``c``, strictly increasing; empty
    without a spline drift (``count`` is checked all the same)."""
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)):
        raise ValueError(
            f"spline_knots = {_checks.shown(count)} is invalid: expected an integer >= "
            f"{FEWEST_KNOTS} (the knots of a natural cubic spline, at the covariate's quantiles)"
        )
    count = int(count)
    if count < FEWEST_KNOTS:
        raise ValueError(
            f"spline_knots = {count} is invalid: expected an integer >= {FEWEST_KNOTS} (two knots "
            "make a linear drift: ask for 'linear')"
        )
    if not splines:
        return np.empty(0)
    distinct = np.unique(c).size
    if count > distinct:
        raise ValueError(
            f"spline_knots = {count} is invalid: the covariate has {distinct} distinct values; "
            f"expected at most {distinct} knots"
        )
    knots = np.quantile(c, np.linspace(0.0, 1.0, count))
    if not np.all(np.diff(knots) > 0):
        raise ValueError(
            f"spline_knots = {count} is invalid: the covariate's quantiles coincide (repeated "
            "values); expected fewer knots"
        )
    return knots


@dataclass(frozen=True, eq=False)
class DriftBasis:
    """The columns the drifting paths add to the fit's vector (module docstring): ``drifting``
    paths, ``splines`` among them, the covariate's ``reference`` c_ref and the splines' ``knots``
    (empty without a spline)."""

    drifting: Tuple[str, ...]
    reference: float
    splines: Tuple[str, ...] = ()
    knots: np.ndarray = field(default_factory=lambda: np.empty(0))

    @property
    def names(self) -> List[str]:
        """The added parameters' names: for each drifting path its slope, then a spline's
        departures at its interior knots."""
        out = []
        for p in self.drifting:
            out.append(p + SLOPE)
            if p in self.splines:
                out.extend(knot_name(p, j) for j in range(1, self.knots.size - 1))
        return out

    @property
    def owners(self) -> List[str]:
        """The drifting path each added parameter moves (in the order of :attr:`names`)."""
        out = []
        for p in self.drifting:
            out.extend([p] * (1 + (self.knots.size - 2 if p in self.splines else 0)))
        return out

    def columns(self, covariate) -> np.ndarray:
        """(len(covariate), len(names)): what each added parameter adds per unit to its path's
        value at each covariate value."""
        c = np.atleast_1d(np.asarray(covariate, dtype=float))
        bumps = self._bumps(c) - self._bumps(np.array([self.reference]))
        out = []
        for p in self.drifting:
            out.append((c - self.reference)[:, None])
            if p in self.splines:
                out.append(bumps)
        return np.hstack(out) if out else np.zeros((c.size, 0))

    def _bumps(self, c: np.ndarray) -> np.ndarray:
        """N_j(c) of the interior knots (len(c), K-2), continued linearly beyond the end knots."""
        if not self.splines:
            return np.zeros((c.size, 0))
        from scipy.interpolate import CubicSpline

        # on the span mapped to [0, 1]: N_j does not change, and no covariate's scale overflows
        t, span = self.knots, self.knots[-1] - self.knots[0]
        spline = CubicSpline((t - t[0]) / span, np.eye(t.size), bc_type="natural")
        u = (c - t[0]) / span
        inside = np.clip(u, 0.0, 1.0)
        values = spline(inside) + spline(inside, 1) * (u - inside)[:, None]
        return values[:, 1:-1]


def warn_outside(covariate, span: Tuple[float, float], unit: str) -> None:
    """A warning when a prediction's ``covariate`` leaves the fitted ``span``: there the drift is
    an extrapolation (a spline's continues linearly with its end slope)."""
    c = np.atleast_1d(np.asarray(covariate, dtype=float))
    out = c[(c < span[0]) | (c > span[1])]
    if out.size:
        _checks.warn(
            f"covariate = {out[0]:.6g} {unit} lies outside the fitted span [{span[0]:.6g}, "
            f"{span[1]:.6g}] {unit}: the drift there is extrapolated (linearly)",
            UserWarning,
        )
