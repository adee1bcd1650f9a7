"""The fit problem: everything ``lo.fit`` is asked, checked once by :func:`fit_problem` and handed
as one frozen value to every strategy (:func:`~.solve.fit_local`, :func:`~.relative.fit_relative`,
:func:`~.global_search.fit_global`, :func:`~.ladder.fit_ladder`) and result builder.

A problem holds its data as a tuple of :class:`Curve` (each measured curve with its sigma, its
normalisation and whether the retrieval's extinction bias is fitted) so that fits of several curves
at once are problems with several curves, not new argument lists; the strategies of one curve read
:attr:`FitProblem.curve`. Strategies that move the start, the free parameters or the bounds (the
global search polishing its minima, the ladder fitting its families) derive new problems with
:meth:`FitProblem.derived`, so what they pass on stays checked.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Mapping, Optional, Tuple, Union

import numpy as np

from ... import _checks
from ...forward.methods import RT, Turbulent
from ...model import parameters as _parameters
from ...model.path_syntax import by_scalar
from . import inputs
from .normalization import normalization

LOSSES = ("linear", "soft_l1", "huber", "cauchy", "arctan")
SEARCHES = ("local", "global")
#: The global search's default generations at most (it stops earlier when the population's costs
#: agree) and distinct minima polished.
GENERATIONS, MINIMA = 40, 3
#: The smallest population the global search accepts.
MIN_POPULATION_GIVEN = 5

Normalize = Union[None, str, Tuple[float, float]]
#: The parameters ``lo.fit`` frees when none are named.
DEFAULT_FREE = ("beam.tilt", "detector.defocus")


@dataclass(frozen=True, eq=False)
class Curve:
    """One measured curve: ``ranges`` (m, strictly increasing), ``measured`` (G, or relative G when
    ``normalize`` is given), ``sigma`` (1-sigma error per point; ones when ``sigma_given`` is False:
    unit weights, the covariance then scaled by the reduced chi-square), ``normalize`` (None, "far"
    or (z_low, z_high) in m) and ``extinction_bias`` (whether the retrieval's δα is fitted)."""

    ranges: np.ndarray
    measured: np.ndarray
    sigma: np.ndarray
    sigma_given: bool
    normalize: Normalize = None
    extinction_bias: bool = False


@dataclass(frozen=True)
class Search:
    """How the fit searches: ``kind`` ``"local"`` (from the start) or ``"global"`` (a seeded
    population search, then the local fit); the global search's ``seed``, ``population`` (None: by
    the number of free parameters), ``generations`` (most) and ``minima`` (distinct candidates
    polished)."""

    kind: str = "local"
    seed: int = 0
    population: Optional[int] = None
    generations: int = GENERATIONS
    minima: int = MINIMA


@dataclass(frozen=True, eq=False)
class FitProblem:
    """A checked fit problem (module docstring). ``start``: the system whose values start the fit;
    ``curves``: the data; ``free``: the free scalar paths, or ``"auto"`` (the model ladder);
    ``bounds``: {scalar path: (low, high)} as given over the start's ``fit_bounds`` of the free
    paths (None: the defaults of the parameter table); ``method`` (planned once on the start),
    ``tolerance`` (the model's absolute tolerance on G), ``loss``, ``max_evaluations``,
    ``allow_unconverged``, ``threads``, ``search``."""

    start: Any
    curves: Tuple[Curve, ...]
    free: Union[str, Tuple[str, ...]]
    bounds: Optional[Mapping[str, Any]]
    method: Any
    tolerance: float
    loss: str = "linear"
    max_evaluations: int = 200
    allow_unconverged: bool = False
    threads: int = 0
    search: Search = Search()

    @property
    def curve(self) -> Curve:
        """The one curve of a single-curve problem."""
        if len(self.curves) != 1:
            raise ValueError(f"this fit takes one curve: the problem holds {len(self.curves)}")
        return self.curves[0]

    @property
    def paths(self) -> Tuple[str, ...]:
        """The free scalar paths (not ``"auto"``)."""
        assert not isinstance(self.free, str), "the ladder chooses the free paths"
        return self.free

    def derived(self, **changes) -> "FitProblem":
        """This problem with ``changes`` (``start``, ``free`` as scalar paths, ``bounds``,
        ``allow_unconverged``, ``search``): what a strategy passes on to the one it runs."""
        if "free" in changes:
            changes["free"] = tuple(changes["free"])
        return dataclasses.replace(self, **changes)


def fit_problem(
    system,
    ranges,
    measured,
    sigma=None,
    free=DEFAULT_FREE,
    *,
    bounds=None,
    method="auto",
    tolerance: Optional[float] = None,
    loss: str = "linear",
    max_evaluations: int = 200,
    allow_unconverged: bool = False,
    threads: int = 0,
    normalize: Normalize = None,
    extinction_bias: bool = False,
    search: str = "local",
    seed: Optional[int] = None,
    population: Optional[int] = None,
    generations: int = GENERATIONS,
    minima: int = MINIMA,
) -> FitProblem:
    """The :class:`FitProblem` of ``lo.fit``'s arguments (as documented there), every one checked
    here: a bad value is a ValueError naming it."""
    search = _checks.choice("search", search, SEARCHES)
    extinction_bias = checked_extinction_bias(normalize, extinction_bias)
    auto = isinstance(free, str) and free == "auto"
    paths = "auto" if auto else tuple(free_paths(free))
    if auto and sigma is None:
        raise ValueError(
            "free = 'auto' needs sigma (the curve's noise, e.g. far_range_noise of its far-range "
            "scatter): an information criterion compares chi-squares on the noise's scale"
        )
    settings = fit_settings(
        system,
        free=paths,
        bounds=with_system_bounds(system, bounds, None if auto else paths),
        method=method,
        tolerance=tolerance,
        loss=loss,
        max_evaluations=max_evaluations,
        allow_unconverged=allow_unconverged,
        threads=threads,
    )
    z = _checks.ranges("ranges", ranges)
    y = measured_values(measured, z)
    w = sigma_weights(sigma, y)
    normalization(normalize, z, y, w, extinction_bias)  # its errors name normalize
    curve = Curve(z, y, w, sigma is not None, normalize, extinction_bias)
    the_search = checked_search(search, seed, population, generations, minima)
    return dataclasses.replace(settings, curves=(curve,), search=the_search)


def checked_search(search, seed, population, generations, minima) -> Search:
    """The :class:`Search` of a fit's ``search``, ``seed``, ``population``, ``generations`` and
    ``minima`` arguments, each checked."""
    return Search(
        kind=_checks.choice("search", search, SEARCHES),
        seed=0 if seed is None else _checks.count("seed", seed, 0, 2**32 - 1),
        population=(
            _checks.count("population", population, MIN_POPULATION_GIVEN) if population else None
        ),
        generations=_checks.count("generations", generations, 1),
        minima=_checks.count("minima", minima, 1),
    )


def fit_settings(
    system,
    *,
    free,
    bounds,
    method,
    tolerance,
    loss,
    max_evaluations,
    allow_unconverged,
    threads,
) -> FitProblem:
    """A :class:`FitProblem` without curves yet: the settings every fit shares, checked (a fit of
    other data, the telecover fit, adds its own)."""
    if isinstance(method, Turbulent):
        raise ValueError(
            "method = Turbulent(...) is invalid for a fit: its curves are random draws; fit with "
            "'rt', 'fo' or 'auto'"
        )
    if bounds is not None and not isinstance(bounds, dict):
        raise ValueError(
            f"bounds = {_checks.shown(bounds)} is invalid: expected a dict path -> (low, high)"
        )
    return FitProblem(
        start=system,
        curves=(),
        free=free,
        bounds=bounds,
        method=method,
        tolerance=model_tolerance(tolerance),
        loss=_checks.choice("loss", loss, LOSSES),
        max_evaluations=_checks.count("max_evaluations", max_evaluations, 1),
        allow_unconverged=_checks.flag("allow_unconverged", allow_unconverged),
        threads=threads,
    )


def with_system_bounds(system, bounds, paths) -> Optional[Mapping[str, Any]]:
    """The caller's ``bounds`` over the system's own ``fit_bounds`` (an instrument preset's), by
    scalar path (:func:`~lidar_overlap.model.path_syntax.by_scalar`: a bare pair bounds its scalars
    among ``paths``, or both): the caller's win path by path; of the system's, those of ``paths``
    only (None: all, the ladder picks its family's). Anything but a dict of ``bounds`` is left for
    :func:`fit_settings` to refuse."""
    if not (bounds is None or isinstance(bounds, dict)):
        return bounds
    given = by_scalar("bounds", bounds or {}, paths)
    own = getattr(system, "fit_bounds", None) or {}
    out = {p: v for p, v in own.items() if p not in given and (paths is None or p in paths)}
    return {**out, **given} or None


def free_paths(free):
    """The fit's ``free`` argument as scalar paths (pairs expanded), refused naming ``free``."""
    try:
        return _parameters.plain_paths(
            free,
            "free",
            "the fit is planned on the start, whose model may not include aberrations; fit the "
            "alignment scalars",
        )
    except _checks.ParameterError as exc:
        if exc.parameter == "parameter":  # an unknown path, not a refused value
            raise ValueError(f"free: {exc}; name parameters of the system") from None
        raise


def model_tolerance(tolerance) -> float:
    """The fit's ``tolerance`` (absolute, on G), checked; None: :class:`lidar_overlap.RT`'s
    default."""
    return RT().tolerance if tolerance is None else _checks.tolerance("tolerance", tolerance)


def measured_values(measured, z):
    """The measured G at ranges ``z``, checked: real, finite, one per range."""
    y = inputs.measured_array("measured", measured, "G, one per range")
    if y.shape != z.shape:
        raise ValueError(f"measured has shape {y.shape}: expected {z.shape}, one G per range")
    bad = ~np.isfinite(y)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(
            f"measured[{i}] = {y[i]} is invalid: expected finite values; drop that range (and its "
            "measured value) instead"
        )
    return y


def sigma_weights(sigma, y):
    """``sigma`` as one 1-sigma error per point of ``y``, checked (None: ones)."""
    if sigma is None:
        return np.ones_like(y)
    w = inputs.sigma_array(sigma, y.shape, f"one value per range (shape {y.shape})")
    bad = inputs.bad_sigma(w)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"sigma[{i}] = {w[i]} is invalid: expected {inputs.SIGMA_EXPECTED}")
    return w


def checked_extinction_bias(normalize, extinction_bias) -> bool:
    """``extinction_bias`` checked: a bool, True only with ``normalize`` an interval."""
    if not isinstance(extinction_bias, (bool, np.bool_)):
        raise ValueError(
            f"extinction_bias = {_checks.shown(extinction_bias)} is invalid: expected True or False"
        )
    if extinction_bias and (normalize is None or isinstance(normalize, str)):
        raise ValueError(
            f"extinction_bias=True needs normalize = (z_low, z_high) in m, got {normalize!r}: the "
            "bias is a factor exp(-2 delta_alpha (z - z_ref)) that only the normalisation over an "
            "interval of measured ranges removes (absolute data have no retrieval; 'far' would "
            "extrapolate it 100-fold beyond the data)"
        )
    return bool(extinction_bias)
