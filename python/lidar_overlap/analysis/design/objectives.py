"""Design questions for :func:`lidar_overlap.analysis.design.optimize`: what to minimise and which
constraints must hold (SI units).

Each objective states the ranges it needs G at (``ranges``, m), the number it minimises from an
:class:`OverlapResult` there (``score``), the number it reports (``value``, in ``unit``) and its
constraints (``constraint_values``: name -> value, satisfied when >= 0). Constraints on G use its
lower bound G
- error_estimate,
so a design found feasible stays feasible for the exact G of the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Dict, Mapping, Optional, Tuple

import numpy as np

from ... import _checks
from ..._values import FrozenMap
from ...forward.result import OverlapResult

#: Ranges (between the target and the far range, geometric) at which SmallestFieldOfView checks G.
FULL_OVERLAP_POINTS = 6


def far_limit(system) -> float:
    """G's far-range limit, 1 - (r_obs / R)²: the part of the aperture the obstruction does not
    shade."""
    t = system.telescope
    return 1.0 - (t.obstruction_radius / (0.5 * t.diameter)) ** 2


def _lower(result: OverlapResult) -> np.ndarray:
    """G less its error bound (error estimates that are NaN count as 0)."""
    return result.overlap - np.nan_to_num(result.error_estimate)


@dataclass(frozen=True)
class SmallestFieldOfView:
    """The smallest detector radius (so field of view, 2 r_d / f) for full overlap by a range.

    Minimises ``detector.radius`` (m; which must be a free parameter, beside any others such as
    ``detector.defocus``, ``beam.offset[i]`` or ``beam.tilt[i]``) subject to

    - full overlap: G(z) >= ``fraction`` G_limit at every z of ``ranges``, from
      ``full_overlap_range`` (m) to ``far_range`` (m), G_limit = 1 - (r_obs / R)² the far-range
      limit of the obstructed aperture;
    - far loss: 1 - G(far_range) / G_limit <= ``max_far_loss`` (dimensionless).

    G grows with the detector radius at every range (a larger disc about the same centre contains
    the smaller one, and the coupling integrand is >= 0), so for fixed other parameters the smallest
    radius is found by bisection; the others are searched for the smallest such radius.
    """

    full_overlap_range: float = 150.0
    fraction: float = 0.99
    max_far_loss: float = 0.01
    far_range: float = 1e4
    unit: str = field(default="m", init=False)

    def __post_init__(self) -> None:
        _checks.length("full_overlap_range", self.full_overlap_range)
        _checks.length("far_range", self.far_range)
        _checks.unit_interval("fraction", self.fraction, include_one=True)
        _checks.unit_interval("max_far_loss", self.max_far_loss)
        if not self.far_range > self.full_overlap_range:
            raise ValueError(
                f"far_range = {self.far_range!r} is invalid: expected a range beyond "
                f"full_overlap_range = {self.full_overlap_range!r} m"
            )

    @property
    def ranges(self) -> np.ndarray:
        return np.geomspace(self.full_overlap_range, self.far_range, FULL_OVERLAP_POINTS)

    def score(self, result: OverlapResult) -> float:
        assert result.system is not None  # a candidate's result carries its system
        return float(result.system.detector.radius)

    value = score

    def constraint_values(self, result: OverlapResult) -> Dict[str, float]:
        g = _lower(result) / far_limit(result.system)
        return {
            "full_overlap": float(np.min(g) - self.fraction),
            "far_loss": float(self.max_far_loss - (1 - g[-1])),
        }


@dataclass(frozen=True)
class MaximumOverlapAt:
    """The free parameters (tilt, offsets, defocus, ...) that maximise G at one ``range`` (m): the
    alignment question. Reports G there (dimensionless); no constraints."""

    range: float
    unit: str = field(default="1", init=False)

    def __post_init__(self) -> None:
        _checks.length("range", self.range)

    @property
    def ranges(self) -> np.ndarray:
        return np.array([float(self.range)])

    def score(self, result: OverlapResult) -> float:
        return -float(result.overlap[0])

    def value(self, result: OverlapResult) -> float:
        return float(result.overlap[0])

    def constraint_values(self, result: OverlapResult) -> Dict[str, float]:
        return {}


@dataclass(frozen=True)
class Objective:
    """Any design question: ``function(result) -> float`` to minimise, ``result`` the
    :class:`OverlapResult` of a candidate system at ``ranges`` (m; None: the ``ranges`` given to
    :func:`optimize`). ``constraints`` maps names to functions of the same result that must be >= 0
    (use ``result.overlap - result.error_estimate`` for bounds on G that hold for the exact G).
    ``unit`` is the unit of the function's value."""

    function: Callable[[OverlapResult], float]
    ranges: Optional[Tuple[float, ...]] = None
    constraints: Mapping[str, Callable[[OverlapResult], float]] = field(default_factory=dict)
    unit: str = "1"

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise ValueError(
                f"function = {_checks.shown(self.function)} is invalid: expected a callable of an "
                "OverlapResult returning a float"
            )
        if self.ranges is not None:
            object.__setattr__(self, "ranges", tuple(_checks.ranges("ranges", self.ranges)))
        if not isinstance(self.constraints, Mapping) or not all(
            isinstance(k, str) and callable(v) for k, v in self.constraints.items()
        ):
            raise ValueError(
                f"constraints = {_checks.shown(self.constraints)} is invalid: expected a mapping "
                "of names to callables of an OverlapResult (satisfied when >= 0)"
            )
        object.__setattr__(self, "constraints", FrozenMap(self.constraints))

    def score(self, result: OverlapResult) -> float:
        return _number("function", self.function(result))

    value = score

    def constraint_values(self, result: OverlapResult) -> Dict[str, float]:
        return {
            name: _number(f"constraint {name!r}", c(result)) for name, c in self.constraints.items()
        }


def _number(name: str, value) -> float:
    """A finite float from a user's callable, refused naming it (NaN would silently steer the
    search)."""
    v = _checks.real(
        f"{name} returned", value if not isinstance(value, np.ndarray) or value.ndim else value[()]
    )
    if not math.isfinite(v):
        raise ValueError(f"{name} returned {v!r}: expected a finite number")
    return v
