"""A range-resolved noise estimate of a measured overlap curve: sigma(r), not one figure.

A lidar's relative noise grows with range (the signal falls as r^-2 and with the extinction), so
one noise figure over a far interval is too large near its start and too small near its end. Here
the estimator of :func:`~.overlap_curves.far_range_noise` (1.4826 x MAD of first differences /
sqrt 2) is applied in windows of equal point counts over the flat far interval, and a power law

    sigma(r) = amplitude * (r / reference_range) ** exponent

is fitted to the window estimates (``np.polyfit`` of ln sigma against ln r, each window's squared
residual weighted by its number of points). ``reference_range`` is the windows' weighted geometric
mean range, where the fitted level and exponent are uncorrelated. Shot noise gives an exponent
between 1 (signal dominated) and 2 (background dominated), more with the extinction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Tuple

import numpy as np

from .. import _checks, _values
from .._pickling import ByValue
from .overlap_curves import MIN_NOISE_POINTS, difference_scatter, far_range_noise

#: Window counts accepted (each window needs MIN_NOISE_POINTS points besides).
MAX_WINDOWS = 1000
#: What a profile does below its interval's lower end.
BELOW = ("extrapolate", "hold")


@dataclass(frozen=True, eq=False)
class NoiseProfile(ByValue):
    """sigma(r) = ``amplitude`` (r / ``reference_range``)^``exponent``: the 1-sigma noise of a curve
    (in the curve's units, G relative or absolute) against range r (m), fitted to the windowed
    estimates ``window_sigmas`` at ``window_ranges`` (m, each window's geometric mean range) over
    ``interval`` (z_low, z_high) in m; ``single`` is the one figure of
    :func:`~.overlap_curves.far_range_noise` over the whole interval. A value: checked on
    construction, read-only arrays. Call it on ranges for sigma there."""

    amplitude: float
    exponent: float
    reference_range: float
    interval: tuple
    window_ranges: np.ndarray
    window_sigmas: np.ndarray
    single: float

    FIELDS: ClassVar = {
        "amplitude": _values.real(low=0.0),
        "exponent": _values.real(),
        "reference_range": _values.real(low=0.0),
        "window_ranges": _values.array(low=0.0),
        "window_sigmas": _values.array(low=0.0),
        "single": _values.real(low=0.0),
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        for name in ("amplitude", "reference_range", "single"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} = {getattr(self, name)!r} is invalid: expected > 0")
        low, high = _values.pair("interval", self.interval)
        if not 0 < low < high:
            raise ValueError(
                f"interval = {_checks.shown(self.interval)} is invalid: expected 0 < z_low < "
                "z_high in m"
            )
        object.__setattr__(self, "interval", (low, high))
        n = self.window_ranges.size
        if n < 2 or self.window_sigmas.shape != (n,) or not np.all(self.window_sigmas > 0):
            raise ValueError(
                f"window_sigmas = {_checks.shown(self.window_sigmas)} is invalid: expected one "
                f"value > 0 per window range ({n}, at least 2)"
            )

    def __call__(self, ranges, below: str = "extrapolate") -> np.ndarray:
        """sigma at ``ranges`` (m, finite, > 0), in the curve's units. Outside ``interval`` the
        power law is an extrapolation: beyond it, always; below it with ``below="extrapolate"``
        (the default), while ``below="hold"`` keeps sigma(z_low) there, for a curve whose near
        range is not measured by the far channel's shot noise alone (the retrieval, a second
        telescope)."""
        z = _checks.real_array("ranges", ranges)
        bad = ~(np.isfinite(z) & (z > 0))
        if bad.any():
            i = np.unravel_index(int(np.argmax(bad)), z.shape)
            raise ValueError(
                f"ranges[{', '.join(str(int(k)) for k in i)}] = {float(z[i])!r} is invalid: "
                "expected finite ranges > 0 m"
            )
        if _checks.choice("below", below, BELOW) == "hold":
            z = np.maximum(z, self.interval[0])
        return self.amplitude * (z / self.reference_range) ** self.exponent


def noise_profile(ranges, overlap, interval: Tuple[float, float], windows: int = 4) -> NoiseProfile:
    """The :class:`NoiseProfile` of a curve (``ranges`` in m, strictly increasing; ``overlap`` one
    value per range) over ``interval`` = (z_low, z_high) in m where it is nearly flat, from
    ``windows`` windows of equal point counts (each at least MIN_NOISE_POINTS points).

    ValueError naming the parameter for non-finite input, a curve without scatter (constant or
    clipped, over the interval or in one window), a bad interval, a bad window count or too few
    points per window. Each window's estimate from n points scatters by about 1.65 / sqrt(2 n) of
    its sigma (60 points: 15 %; measured 17 % with sigma growing inside the window), so the
    exponent from 4 windows over 500-3000 m scatters by about 0.16 (tests/test_noise_profile.py).
    """
    single = far_range_noise(ranges, overlap, interval)  # checks ranges, overlap and interval
    z = _checks.ranges("ranges", ranges)
    g = np.asarray(overlap, dtype=float)
    n_windows = _checks.count("windows", windows, 2, MAX_WINDOWS)
    low, high = (float(v) for v in interval)
    if not low > 0:
        raise ValueError(
            f"interval = ({low:g}, {high:g}) m is invalid: expected z_low > 0 (a power law in r)"
        )
    inside = np.flatnonzero((z >= low) & (z <= high))
    if inside.size // n_windows < MIN_NOISE_POINTS:
        raise ValueError(
            f"windows = {n_windows} is invalid for interval = ({low:g}, {high:g}) m: its "
            f"{inside.size} points give {inside.size // n_windows} per window; expected at least "
            f"{MIN_NOISE_POINTS} per window (at most {inside.size // MIN_NOISE_POINTS} windows)"
        )
    centres, sigmas, counts = [], [], []
    for k, part in enumerate(np.array_split(inside, n_windows)):
        sigma = difference_scatter(g[part])
        if not sigma > 0:
            raise ValueError(
                f"windows = {n_windows}: window {k} ({z[part[0]]:g} to {z[part[-1]]:g} m) has no "
                "scatter (constant or quantised values); choose fewer windows or an interval "
                "where the curve is measured, not clipped"
            )
        centres.append(math.exp(float(np.mean(np.log(z[part])))))
        sigmas.append(sigma)
        counts.append(part.size)
    x, w = np.log(centres), np.asarray(counts, dtype=float)
    x_ref = float(np.average(x, weights=w))
    # polyfit weighs the residuals, not their squares: sqrt(counts). About the weighted mean of
    # ln r the intercept is ln sigma there, uncorrelated with the slope.
    exponent, log_amplitude = np.polyfit(x - x_ref, np.log(sigmas), 1, w=np.sqrt(w))
    return NoiseProfile(
        amplitude=math.exp(float(log_amplitude)),
        exponent=float(exponent),
        reference_range=math.exp(x_ref),
        interval=(low, high),
        window_ranges=np.asarray(centres),
        window_sigmas=np.asarray(sigmas),
        single=single,
    )
