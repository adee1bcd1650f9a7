"""The alignment change that moves full overlap to a target range: for each of the beam's tilt and
offset (or any scalar path), the value at which G at the target reaches ``threshold`` of its
far-range limit (G at ``FAR_FACTOR`` x the target), the other parameters as they are, e.g. those of
a fitted system (``fit.system``).

How: G(target) / G(far) as a function of the path's value is scanned over its bounds (one batched
core call), the sign change of ratio - threshold nearest the current value is bracketed, and Brent's
method finds the root to ``xtol``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Dict, Optional, Tuple

import numpy as np

from ... import _checks, _core, _values
from ...forward.planning import plan
from ...model import parameters as _parameters
from ..batch_curves import curves, variants

#: The far-range limit is taken at this multiple of the target range.
FAR_FACTOR = 100.0
#: Values scanned across the bounds before the root is bracketed.
SCAN_POINTS = 41


@dataclass(frozen=True)
class Realignment:
    """For ``path``: ``value`` (SI) that puts full overlap at ``target`` (m), ``change`` from the
    system's value, and ``ratio_before`` (G(target) / G(far) now)."""

    path: str
    value: float
    change: float
    target: float
    ratio_before: float

    FIELDS: ClassVar = {
        "path": _values.text,
        "value": _values.real(),
        "change": _values.real(),
        "target": _values.real(low=0.0),
        "ratio_before": _values.real(low=0.0),
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)


def realign(
    system,
    target: float,
    paths=("beam.tilt[0]", "beam.offset[0]"),
    bounds: Optional[Dict[str, Tuple[float, float]]] = None,
    threshold: float = 0.99,
    tolerance: float = 1e-5,
    *,
    threads: int = 0,
) -> Dict[str, Realignment]:
    """Per path in ``paths`` (each changed alone), the value that puts full overlap (G reaching
    ``threshold`` of its far limit) at ``target`` (m); ray traced to ``tolerance``. ``bounds``:
    {path: (low, high)} searched; default: tilt ± 5 mrad about its value, offset ± the aperture
    diameter. ValueError naming the path when no value within its bounds reaches the target."""
    from scipy import optimize

    target = _checks.length("target", target)
    if FAR_FACTOR * target > _core.MAX_LENGTH:  # the far limit is a range of its own
        raise ValueError(
            f"target = {target!r} is invalid: expected a range up to "
            f"{_core.MAX_LENGTH / FAR_FACTOR:g} m (G is also computed at {FAR_FACTOR:g} x the "
            "target, for its far limit)"
        )
    threshold = _checks.unit_interval("threshold", threshold)
    z = np.array([target, FAR_FACTOR * target])
    p = plan(system, z, "rt", tolerance=tolerance, threads=threads)
    out = {}
    for path in _parameters.expand(list(paths)):
        x0 = _parameters.get(system, path)
        low, high = (bounds or {}).get(path) or _parameters.scan_bounds(system, path, x0)
        grid = np.linspace(low, high, SCAN_POINTS)
        g = curves(p, variants(system, [path], grid[:, None]))
        with np.errstate(divide="ignore", invalid="ignore"):
            f = g[:, 0] / g[:, 1] - threshold
        now = curves(p, [system])[0]
        crossings = [
            i
            for i in range(grid.size - 1)
            if np.isfinite(f[i : i + 2]).all() and f[i] * f[i + 1] < 0
        ]
        if not crossings:
            raise ValueError(
                f"{path}: no value in [{low:g}, {high:g}] puts full overlap at {target:g} m (G "
                f"reaches {threshold:g} of its far limit nowhere there, or everywhere); widen the "
                "bounds or choose another target"
            )
        i = min(crossings, key=lambda i: abs(0.5 * (grid[i] + grid[i + 1]) - x0))

        def ratio(v, path=path):
            gv = curves(p, variants(system, [path], [[v]]))[0]
            return gv[0] / gv[1] - threshold

        root = optimize.brentq(ratio, grid[i], grid[i + 1], xtol=1e-6 * (high - low))
        out[path] = Realignment(path, float(root), float(root - x0), target, float(now[0] / now[1]))
    return out
