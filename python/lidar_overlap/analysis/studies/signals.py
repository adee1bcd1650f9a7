"""Elastic lidar signals from an overlap function, and their overlap correction (SI units).

The expected number of photons detected in the range bin at z, per laser shot, is the elastic lidar
equation

    P(z) = N₀ Δz A η G(z) β(z) T(z)² / z²,    N₀ = E₀ / (h c / λ),

with E₀ the pulse energy (J), N₀ the photons it carries, Δz the range resolution (m; the bin the
detector integrates, cτ/2 of its sampling time τ; each value is sampled at the bin's centre, with no
convolution with the pulse), A = π D²/4 the full aperture (G is normalised to the full, unobstructed
aperture, so an obstruction
is in G already: see :mod:`lidar_overlap.forward.compute`), η the receiver efficiency (optics times
detector quantum efficiency), β and T the backscatter and one-way transmission of an
:class:`Atmosphere`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Optional

import numpy as np

from ... import _checks, _values
from ..._pickling import ByValue
from ...forward.result import OverlapResult
from ...model.atmosphere import Atmosphere
from ..fitting.correction import fitted_overlap, is_fit

#: Planck constant (J s) and speed of light (m/s), exact in SI.
PLANCK, LIGHT_SPEED = 6.62607015e-34, 299792458.0
#: Largest pulse energy (J), range resolution (m), background (photons per bin and shot) and number
#: of shots accepted: beyond any lidar, and far from overflowing the counts.
MAX_PULSE_ENERGY, MAX_RANGE_RESOLUTION, MAX_BACKGROUND, MAX_SHOTS = 1e3, 1e4, 1e15, 10**12
#: Expected counts above which a noisy realisation is drawn from the normal distribution of the same
#: mean and variance instead of the Poisson one (whose relative skewness, 1/sqrt(counts), is then
#: below 1e-6).
POISSON_LIMIT = 1e12
#: The default atmosphere of :func:`signal` (one value: atmospheres are immutable).
STANDARD_ATMOSPHERE = Atmosphere()


@dataclass(frozen=True, eq=False)
class LidarSignal(ByValue):
    """Expected elastic lidar signal of one system and atmosphere (see :func:`signal`).

    Attributes
    ----------
    ranges : m, the overlap result's ranges.
    overlap : G at each range (dimensionless).
    photons : expected photons detected per range bin and per shot, background excluded.
    range_corrected : photons · z² (photons m²), the range-corrected signal.
    range_corrected_full_overlap : the same with G = 1 (what an overlap correction should recover).
    std : photons per bin and shot, the standard deviation of the shot-averaged,
        background-subtracted signal: sqrt((photons + background) / shots) (Poisson counts summed
        over the shots; the background is taken as known exactly, so subtracting it adds no
        variance).
    noisy : one such shot-averaged, background-subtracted realisation (photons per bin and shot), or
        None.
    background : photons per bin and shot (sky light and dark counts), subtracted from ``noisy``.
    shots : number of shots averaged.
    wavelength : m.
    """

    ranges: np.ndarray
    overlap: np.ndarray
    photons: np.ndarray
    range_corrected: np.ndarray
    range_corrected_full_overlap: np.ndarray
    std: np.ndarray
    noisy: Optional[np.ndarray]
    background: float
    shots: int
    wavelength: float

    FIELDS: ClassVar = {
        "ranges": _values.array(low=0.0),
        "overlap": _values.array(low=0.0),
        "photons": _values.array(low=0.0),
        "range_corrected": _values.array(low=0.0),
        "range_corrected_full_overlap": _values.array(low=0.0),
        "std": _values.array(low=0.0),
        "noisy": _values.array(optional=True),
        "background": _values.real(low=0.0),
        "shots": _values.count(1),
        "wavelength": _values.real(low=0.0),
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        _same_size(self, ("overlap", "photons", "range_corrected", "range_corrected_full_overlap",
                          "std", "noisy"))  # fmt: skip

    def plot(self, ax=None):
        """The dynamic-range view on log axes: expected photons per bin and shot with and without
        the overlap, the background, the noise level and the noisy realisation. Returns the
        matplotlib Axes."""
        from ...views.plotting import plot_signal

        return plot_signal(self, ax=ax)


@dataclass(frozen=True, eq=False)
class CorrectedSignal(ByValue):
    """An overlap-corrected signal (see :func:`correct`).

    Attributes
    ----------
    ranges : m.
    values : signal / G, in the signal's units; NaN where ``mask``.
    std : its propagated standard deviation, in the same units; NaN where ``mask``.
    mask : True where G < min_overlap (too little overlap to correct).
    """

    ranges: np.ndarray
    values: np.ndarray
    std: np.ndarray
    mask: np.ndarray

    FIELDS: ClassVar = {
        "ranges": _values.array(low=0.0),
        "values": _values.array(nan=True),
        "std": _values.array(nan=True, low=0.0),
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        mask = np.asarray(self.mask)
        if mask.dtype != bool or mask.shape != self.ranges.shape:
            raise ValueError(
                f"mask = {_checks.shown(self.mask)} is invalid: expected one bool per range"
            )
        mask = mask.copy()
        mask.setflags(write=False)
        object.__setattr__(self, "mask", mask)
        _same_size(self, ("values", "std"))
        hidden = np.isnan(self.values) | np.isnan(self.std)
        if np.any(hidden & ~mask):
            i = int(np.argmax(hidden & ~mask))
            raise ValueError(
                f"values[{i}] or std[{i}] is NaN where mask is False: expected NaN only where the "
                "overlap was too small to correct"
            )


def _same_size(result, names) -> None:
    for name in names:
        value = getattr(result, name)
        if value is not None and value.shape != result.ranges.shape:
            raise ValueError(
                f"{name} has shape {value.shape}: expected one value per range "
                f"({result.ranges.size})"
            )


def signal(
    result: OverlapResult,
    atmosphere: Atmosphere = STANDARD_ATMOSPHERE,
    *,
    pulse_energy: float,
    receiver_efficiency: float,
    range_resolution: float,
    background: float = 0.0,
    shots: int = 1,
    noise: bool = False,
    seed: int = 0,
) -> LidarSignal:
    """Expected photons per range bin and shot of the lidar of ``result`` (its ``system``'s
    wavelength and telescope diameter, its overlap at its ranges) looking through ``atmosphere``, by
    the lidar equation of :mod:`lidar_overlap.analysis.studies.signals`.

    Parameters
    ----------
    result : an :class:`OverlapResult` that carries its system.
    atmosphere : the :class:`Atmosphere` (molecules of a standard atmosphere at sea level, zenith,
        by default).
    pulse_energy : J, (0, 1000].
    receiver_efficiency : dimensionless, (0, 1]: optics transmission times detector quantum
        efficiency.
    range_resolution : m, (0, 1e4]: the length of a range bin.
    background : photons per bin and shot, [0, 1e15].
    shots : shots averaged, 1 to 1e12; the noise scales as 1/sqrt(shots).
    noise : draw one noisy realisation (``LidarSignal.noisy``) with
        ``numpy.random.default_rng(seed)``.
    seed : integer >= 0.
    """
    if not isinstance(result, OverlapResult):
        raise ValueError(
            f"result = {_checks.shown(result)} is invalid: expected an OverlapResult (from overlap)"
        )
    if result.system is None:
        raise ValueError(
            "result.system is None: expected a result that carries its lidar system (a result read "
            "from a file keeps it only for Gaussian beams)"
        )
    if not isinstance(atmosphere, Atmosphere):
        raise ValueError(
            f"atmosphere = {_checks.shown(atmosphere)} is invalid: expected an Atmosphere"
        )
    energy = _upto("pulse_energy", pulse_energy, MAX_PULSE_ENERGY, "J")
    efficiency = _checks.unit_interval("receiver_efficiency", receiver_efficiency, include_one=True)
    dz = _upto("range_resolution", range_resolution, MAX_RANGE_RESOLUTION, "m")
    bg = _checks.real("background", background)
    if not 0.0 <= bg <= MAX_BACKGROUND:
        raise ValueError(
            f"background = {bg!r} is invalid: expected photons per bin and shot in [0, "
            f"{MAX_BACKGROUND:g}]"
        )
    shots = _checks.count("shots", shots, 1, MAX_SHOTS)
    seed = _checks.count("seed", seed, 0)
    if not isinstance(noise, (bool, np.bool_)):
        raise ValueError(f"noise = {_checks.shown(noise)} is invalid: expected True or False")

    z, g = result.ranges, result.overlap
    wavelength = result.system.beam.wavelength
    photons_per_pulse = energy * wavelength / (PLANCK * LIGHT_SPEED)
    area = math.pi * result.system.telescope.diameter**2 / 4
    t2 = (
        atmosphere.transmission(wavelength, z) ** 2
    )  # first: it refuses ranges beyond the model by name
    beta = atmosphere.backscatter(wavelength, atmosphere.height(z))
    full = photons_per_pulse * dz * area * efficiency * beta * t2  # P z² with G = 1
    photons = full * g / z**2
    std = np.sqrt((photons + bg) / shots)
    noisy = _draw(photons + bg, shots, seed) - bg if noise else None
    return LidarSignal(
        ranges=z.copy(),
        overlap=g.copy(),
        photons=photons,
        range_corrected=full * g,
        range_corrected_full_overlap=full,
        std=std,
        noisy=noisy,
        background=bg,
        shots=shots,
        wavelength=wavelength,
    )


def _draw(mean_per_shot: np.ndarray, shots: int, seed: int) -> np.ndarray:
    """Shot average of Poisson counts of mean ``mean_per_shot`` summed over ``shots`` (normal where
    large)."""
    rng = np.random.default_rng(seed)
    total = mean_per_shot * shots
    small = total <= POISSON_LIMIT
    counts = np.empty_like(total)
    counts[small] = rng.poisson(total[small])
    counts[~small] = rng.normal(total[~small], np.sqrt(total[~small]))
    return counts / shots


def _upto(name: str, value, maximum: float, unit: str) -> float:
    v = _checks.real(name, value)
    if not 0.0 < v <= maximum:
        raise ValueError(f"{name} = {v!r} is invalid: expected a value in (0, {maximum:g}] {unit}")
    return v


def correct(
    ranges,
    signal,
    overlap,
    *,
    min_overlap: float = 0.1,
    signal_std=None,
    overlap_std=None,
    covariate=None,
) -> CorrectedSignal:
    """Overlap-corrected signal S/G and its uncertainty sqrt((σ_S/G)² + (S σ_G/G²)²) (first-order
    propagation of independent errors).

    Parameters
    ----------
    ranges : m, strictly increasing, one per signal value.
    signal : the measured signal S at each range, in any unit (photons per bin, range-corrected,
        ...): finite.
    overlap : G at each range: an :class:`OverlapResult` at the same ranges, an array of values in
        [0, 1], or a fit result (``lo.fit``): its curve at the ranges (a relative fit's divided by
        its far-range limit) with its 1-sigma band as ``overlap_std`` unless that is given; a drift
        fit (``lo.fit_drift``): its curve at ``covariate``, the same way.
    min_overlap : (0, 1]: where G < min_overlap the signal is not corrected (too little of it
        reaches the detector, and S/G would amplify every error): ``values`` and ``std`` are NaN
        there and ``mask`` True.
    signal_std : the standard deviation of S, in its unit: a scalar or one per range, finite and >=
        0; None means 0 (an exact signal).
    overlap_std : the uncertainty of G: a scalar or one per range in [0, 1]. None means the result's
        ``error_estimate`` when ``overlap`` is an :class:`OverlapResult` (for ``error_kind``
        "bound", RT's quadrature bound, that is a bound on the error, not a standard deviation, so
        ``std`` is then a conservative bound too; for "nominal" and "standard_error" it is used as a
        standard deviation), and 0 for an array.
    covariate : with a drift fit as ``overlap``, the signal's covariate value (e.g. the day's
        internal temperature, in the fit's covariate unit); refused with any other overlap.
    """
    z = _checks.ranges("ranges", ranges)
    s = _profile("signal", signal, z.size)
    if is_fit(overlap):  # a fitted curve: G and its band from the fit (fitting/correction.py)
        overlap, band = fitted_overlap(overlap, z, covariate)
        overlap_std = band if overlap_std is None else overlap_std
    elif covariate is not None:
        raise ValueError(
            f"covariate = {_checks.shown(covariate)} is invalid here: only a drift fit's overlap "
            "(lo.fit_drift) depends on a covariate; leave it out"
        )
    if isinstance(overlap, OverlapResult):
        if not np.array_equal(overlap.ranges, z):
            raise ValueError(
                "overlap.ranges differ from ranges: expected the overlap computed at the signal's "
                "ranges"
            )
        g = overlap.overlap
        if overlap_std is None:
            overlap_std = overlap.error_estimate
            if np.isnan(overlap_std).any():
                i = int(np.argmax(np.isnan(overlap_std)))
                raise ValueError(
                    f"overlap.error_estimate[{i}] is NaN (the method gave no estimate): pass "
                    "overlap_std explicitly (0.0 for an exact G)"
                )
    else:
        g = _profile("overlap", overlap, z.size)
        _within("overlap", g, 0.0, 1.0)
    min_overlap = _checks.unit_interval("min_overlap", min_overlap, include_one=True)
    sigma_s = _spread("signal_std", signal_std, z.size, math.inf)
    sigma_g = _spread("overlap_std", overlap_std, z.size, 1.0)

    mask = g < min_overlap
    use = ~mask
    values = np.full(z.size, np.nan)
    std = np.full(z.size, np.nan)
    with np.errstate(over="ignore", invalid="ignore"):  # inf · 0: refused just below
        values[use] = s[use] / g[use]
        std[use] = np.hypot(sigma_s[use] / g[use], values[use] * sigma_g[use] / g[use])
    overflow = use & ~(np.isfinite(values) & np.isfinite(std))
    if overflow.any():
        i = int(np.argmax(overflow))
        raise ValueError(
            f"signal[{i}] = {s[i]!r} with G = {g[i]!r} overflows the corrected signal or its "
            "uncertainty beyond double range: expected a signal of smaller magnitude (rescale it)"
        )
    return CorrectedSignal(ranges=z.copy(), values=values, std=std, mask=mask)


def _profile(name: str, value, size: int) -> np.ndarray:
    """A 1-D array of ``size`` finite real numbers."""
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} is invalid: expected a 1-D array of numbers ({exc})") from None
    if raw.dtype.kind not in "iuf":
        raise ValueError(
            f"{name} = {_checks.shown(value)} is invalid: expected a 1-D array of real numbers"
        )
    arr = raw.astype(float)
    if arr.shape != (size,):
        raise ValueError(f"{name} has shape {arr.shape}: expected ({size},), one value per range")
    bad = ~np.isfinite(arr)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"{name}[{i}] = {arr[i]!r} is invalid: expected a finite number")
    return arr


def _within(name: str, arr: np.ndarray, low: float, high: float) -> None:
    bad = ~((arr >= low) & (arr <= high))
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(
            f"{name}[{i}] = {arr[i]!r} is invalid: expected a value in [{low:g}, {high:g}]"
        )


def _spread(name: str, value, size: int, maximum: float) -> np.ndarray:
    """A standard deviation per range: None (0), a scalar or one per range, each in [0, maximum] and
    finite."""
    if value is None:
        return np.zeros(size)
    arr = (
        np.full(size, _checks.real(name, value))
        if np.ndim(value) == 0
        else _profile(name, value, size)
    )
    _within(name, arr, 0.0, min(maximum, np.finfo(float).max))
    return arr
