"""Automatic alignment on a simulated noisy lidar signal: steer the beam tilt to maximise the signal
at one range.

The lidar's own beam tilt is the unknown misalignment; the search sets the absolute tilt (rad) and
sees only the shot-averaged, background-subtracted photon count in the range bin at ``range``
(``lo.signal(..., noise=True)``), which is proportional to G there plus photon noise. Two searches:

- ``"raster"``: a 5 x 5 grid over the box about the lidar's own tilt, then boxes of one grid step
  about the brightest cell, each level a finer grid (what an operator does by hand), until the step
  is below ``resolution``;
- ``"gradient"``: from the lidar's own tilt, central differences of the signal along x and y (4
  measurements per step, probes one step apart: a probe much shorter than the peak's width would see
  only noise), a step of length ``step`` along the gradient, halved whenever the signal at the new
  tilt is not higher than at the old one, until it is below ``resolution``.

The G of each candidate comes from the ray tracer (a grid in one core call); the best G (for judging
how far a search got) from :func:`lidar_overlap.analysis.design.optimize` with
:class:`MaximumOverlapAt`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Mapping, Optional

import numpy as np

from ... import _checks, _core, _values
from ..._pickling import ByValue
from ...forward.methods import RT
from ...model.system import LidarSystem
from ..studies.signals import signal as _signal
from .objectives import MaximumOverlapAt
from .optimize import Problem, optimize

TILT = ["beam.tilt[0]", "beam.tilt[1]"]
RASTER_POINTS = 5
#: How close to its best G a search must bring the lidar (a fraction of the best G).
WITHIN = 0.99
#: The finest tilt step a search is asked for (rad): far below any actuator's, far above the
#: spacing of doubles near a milliradian tilt.
MIN_RESOLUTION = 1e-12


@dataclass(frozen=True, eq=False)
class AlignResult(ByValue):
    """tilt : the (x, y) tilt the search ends at (rad). tilts : the search's estimate after each
    step (n x 2, rad); shots : the shots fired by then (n); overlap : G at each estimate;
    best_overlap : the best G in the
    box (at ``best_tilt``). shots_to_within : shots after which every estimate has G >= 0.99
    best_overlap (None if the search never got there). steps : measurements taken (each
    ``shots_per_step`` shots)."""

    tilt: tuple
    tilts: np.ndarray
    shots: np.ndarray
    overlap: np.ndarray
    best_overlap: float
    best_tilt: tuple
    shots_to_within: object
    steps: int

    FIELDS: ClassVar = {
        "tilt": _values.pair,
        "tilts": _values.array(2),
        "shots": _values.array(low=0.0),
        "overlap": _values.array(low=0.0),
        "best_overlap": _values.real(low=0.0),
        "best_tilt": _values.pair,
        "steps": _values.count(0),
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        n = self.shots.size
        if self.tilts.shape != (n, 2) or self.overlap.shape != (n,):
            raise ValueError(
                f"tilts has shape {self.tilts.shape} and overlap {self.overlap.shape}: expected "
                f"({n}, 2) and ({n},), one row per step of shots"
            )
        if self.shots_to_within is not None:
            object.__setattr__(
                self, "shots_to_within", _checks.count("shots_to_within", self.shots_to_within, 0)
            )


def align(
    system,
    range,
    *,
    search: str = "raster",
    box: float = 1e-3,
    shots_per_step: int = 100,
    signal: Optional[Mapping] = None,
    resolution: float = 5e-6,
    step: float = 1e-4,
    max_steps: int = 2000,
    tolerance: Optional[float] = None,
    seed: int = 0,
) -> AlignResult:
    """Align ``system``'s beam tilt to maximise its noisy signal at ``range`` (m), within ``box``
    (rad) of its own tilt in x and y (the actuator's travel about where it starts).

    Parameters
    ----------
    signal : keywords of :func:`lidar_overlap.signal` (pulse_energy, receiver_efficiency,
        range_resolution, atmosphere, background), required.
    shots_per_step : shots averaged per measurement.
    resolution : rad, the raster's last grid step and the gradient's smallest step (and probe).
    step : rad, the gradient's first step.
    seed : of the photon noise (measurement k uses seed + k).
    """
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    _checks.choice("search", search, ("raster", "gradient"))
    seed = _checks.count("seed", seed, 0, 2**63 - 1)
    box, resolution, step = (
        _checks.positive(n, v)
        for n, v in (("box", box), ("resolution", resolution), ("step", step))
    )
    if not MIN_RESOLUTION <= resolution <= box:
        raise ValueError(
            f"resolution = {resolution!r} is invalid: expected from {MIN_RESOLUTION:g} rad to box "
            f"= {box!r} rad"
        )
    if search == "gradient" and not resolution <= step <= box:
        raise ValueError(
            f"step = {step!r} is invalid: expected the gradient's first step from resolution = "
            f"{resolution!r} to box = {box!r} rad"
        )
    shots_per_step = _checks.count("shots_per_step", shots_per_step, 1, 10**9)
    max_steps = _checks.count("max_steps", max_steps, 1, 10**6)
    if not isinstance(signal, Mapping):
        raise ValueError(
            f"signal = {_checks.shown(signal)} is invalid: expected a mapping of lo.signal "
            "keywords (pulse_energy, receiver_efficiency, range_resolution, ...)"
        )
    owned = sorted(set(signal) & {"noise", "shots", "seed"})
    if owned:
        raise ValueError(
            f"signal[{owned[0]!r}] is invalid: align sets noise, shots and seed of each "
            "measurement itself (use shots_per_step and seed)"
        )
    start = np.array(system.beam.tilt, dtype=float)
    reach = _core.MAX_ANGLE - float(np.max(np.abs(start)))
    if not box <= reach:
        raise ValueError(
            f"box = {box!r} is invalid: expected at most {reach:.6g} rad, so that the tilts "
            f"searched (the start {tuple(start.tolist())} ± box) stay within ±{_core.MAX_ANGLE:g} "
            "rad"
        )
    lower, upper = start - box, start + box
    best = optimize(
        system, MaximumOverlapAt(range), TILT, np.column_stack([lower, upper]), tolerance=tolerance
    )
    problem = Problem(
        system, MaximumOverlapAt(range), TILT, lower, upper, requested_rt(tolerance), [range]
    )
    counter = iter(np.arange(seed, seed + 10**7))

    def measure(tilts: np.ndarray) -> np.ndarray:
        """Noisy photons per bin and shot at each tilt (rows), the G's in one core call."""
        counts = []
        for r in problem.results(np.clip(tilts, lower, upper)):
            seed_k = int(next(counter))
            noisy = _signal(r, **signal, shots=shots_per_step, noise=True, seed=seed_k).noisy
            assert noisy is not None  # asked for with noise=True
            counts.append(noisy[0])
        return np.array(counts)

    run = _raster if search == "raster" else _gradient
    tilts, measurements = run(measure, start, box, resolution, step, max_steps)
    tilts = np.clip(np.array(tilts), lower, upper)
    g = np.array([r.overlap[0] for r in problem.results(tilts)])
    shots = np.array(measurements) * shots_per_step
    within = g >= WITHIN * best.objective
    last_out = np.flatnonzero(~within)
    first = 0 if last_out.size == 0 else int(last_out[-1]) + 1
    return AlignResult(
        tilt=tuple(tilts[-1]),
        tilts=tilts,
        shots=shots,
        overlap=g,
        best_overlap=best.objective,
        best_tilt=tuple(best.values[p] for p in TILT),
        shots_to_within=int(shots[first]) if first < len(shots) else None,
        steps=int(measurements[-1]),
    )


def _raster(measure, start, box, resolution, step, max_steps):
    """Grids of RASTER_POINTS² about the brightest cell, each one grid step wide, down to
    ``resolution``."""
    centre, half, tilts, counts, taken = start.copy(), box, [], [], 0
    while taken < max_steps:
        axis = np.linspace(-half, half, RASTER_POINTS)
        grid = centre + np.array([(x, y) for x in axis for y in axis])
        values = measure(grid)
        taken += len(grid)
        centre = grid[int(np.argmax(values))]
        tilts.append(centre)
        counts.append(taken)
        half = axis[1] - axis[0]
        if half < resolution:
            break
    return tilts, counts


def _gradient(measure, start, box, resolution, step, max_steps):
    """Normalised-gradient ascent with step halving, probes one step about the current tilt."""
    probes = np.array([(1, 0), (-1, 0), (0, 1), (0, -1)])
    x, tilts, counts, taken, previous = start.copy(), [], [], 0, -np.inf
    direction = np.zeros(2)
    while taken < max_steps and step >= resolution:
        m = measure(x + step * probes)
        taken += 4
        level = float(m.mean())  # the signal at x, to O(step²)
        if level <= previous:  # worse than before: go back, shorter
            x, step = x - step * direction, 0.5 * step
        else:
            previous = level
            grad = np.array([m[0] - m[1], m[2] - m[3]])
            norm = float(np.hypot(*grad))
            direction = grad / norm if norm > 0 else np.zeros(2)
        tilts.append(x.copy())
        counts.append(taken)
        x = np.clip(x + step * direction, start - box, start + box)
    return tilts, counts


def requested_rt(tolerance: Optional[float]) -> RT:
    """Ray tracing at ``tolerance`` (None: RT's default)."""
    return RT() if tolerance is None else RT(tolerance=tolerance)
