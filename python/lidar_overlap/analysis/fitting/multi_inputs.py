"""The arguments of the fits of several curves (``lo.fit_joint``, ``lo.fit_drift``), checked once:
each curve as a :class:`~.problem.Curve` (errors name the argument and the curve's index), the
paths the fit frees and the bounds, natural scales and search box of the global parameters."""

from __future__ import annotations

from typing import List, Optional, Sequence, Tuple

import numpy as np

from ... import _checks
from ...model import parameters as _parameters
from ...model.path_syntax import by_scalar
from ...model.system import LidarSystem
from .multi_curve import CurveMap, MultiCurveProblem
from .normalization import normalization
from .problem import (
    Curve,
    FitProblem,
    checked_extinction_bias,
    checked_search,
    fit_settings,
    free_paths,
    measured_values,
    sigma_weights,
    with_system_bounds,
)
from .solve import parameter_bounds


def multi_settings(
    system, data, *, search, seed, population, generations, minima, **options
) -> FitProblem:
    """The settings of a fit of several curves with its ``data`` (the checked curves), free paths
    still to come (``derived(free=...)``): the search's (``search`` None: local) and lo.fit's
    ``options`` (method, tolerance, loss, max_evaluations, allow_unconverged, threads), each checked
    as lo.fit checks it; the one validation of lo.fit_joint's and lo.fit_drift's keywords."""
    the_search = checked_search(search or "local", seed, population, generations, minima)
    settings = fit_settings(system, free=(), bounds=None, **options)
    return settings.derived(curves=data, search=the_search)


def one_per_curve(name: str, value, n: int, single) -> list:
    """``value`` as one entry per curve: a list of ``n`` entries, or one value (``single(value)``
    True) repeated; ValueError naming ``name`` otherwise."""
    if single(value):
        return [value] * n
    if not isinstance(value, (list, tuple)) or len(value) != n:
        raise ValueError(
            f"{name} = {_checks.shown(value)} is invalid: expected one entry per curve ({n})"
        )
    return list(value)


def is_interval(value) -> bool:
    """Whether ``value`` is one normalisation for every curve (None, a text, or (z_low, z_high))."""
    if value is None or isinstance(value, str):
        return True
    return (
        isinstance(value, tuple)
        and len(value) == 2
        and all(isinstance(v, (int, float, np.number)) for v in value)
    )


def checked_curve(i: int, ranges, measured, sigma, normalize, extinction_bias) -> Curve:
    """Curve ``i`` checked as ``lo.fit`` checks its data (sigma required: the curves are weighed
    against each other by it); errors name the argument and ``i``."""
    try:
        z = _checks.ranges("ranges", ranges)
    except ValueError as exc:
        raise ValueError(f"ranges[{i}]: {exc}") from None
    try:
        y = measured_values(measured, z)
    except ValueError as exc:
        raise ValueError(f"curves[{i}]: {exc}") from None
    if sigma is None:
        raise ValueError(
            f"sigma[{i}] = None is invalid: a fit of several curves weighs them by their noise; "
            "give each curve's 1-sigma error (e.g. far_range_noise of its far-range scatter)"
        )
    try:
        w = sigma_weights(sigma, y)
    except ValueError as exc:
        raise ValueError(f"curve {i}: {exc}") from None
    bias = checked_extinction_bias(normalize, extinction_bias)
    try:
        normalization(normalize, z, y, w, bias)
    except ValueError as exc:
        raise ValueError(f"curve {i}: {exc}") from None
    return Curve(z, y, w, True, normalize, bias)


def checked_systems(systems, n: int) -> List[LidarSystem]:
    """``systems``: one LidarSystem per curve."""
    if not isinstance(systems, (list, tuple)) or len(systems) != n:
        raise ValueError(
            f"systems = {_checks.shown(systems)} is invalid: expected one LidarSystem per curve "
            f"({n})"
        )
    for i, s in enumerate(systems):
        if not isinstance(s, LidarSystem):
            raise ValueError(
                f"systems[{i}] = {_checks.shown(s)} is invalid: expected a LidarSystem"
            )
    return list(systems)


def checked_paths(name: str, paths, systems, allow_empty: bool = False) -> Tuple[str, ...]:
    """``paths`` (the argument ``name``) as scalar paths that every system has."""
    if allow_empty and (paths is None or (isinstance(paths, (list, tuple)) and not paths)):
        return ()
    try:
        out = tuple(free_paths(paths))
    except ValueError as exc:
        text = str(exc)
        raise ValueError(name + text[len("free") :] if text.startswith("free") else text) from None
    for i, s in enumerate(systems):
        for path in out:
            if not has_path(s, path):
                raise ValueError(
                    f"{name}: {path} does not exist in systems[{i}] (or is None there): expected "
                    "parameters every curve's system has"
                )
    return out


def has_path(system, path: str) -> bool:
    """Whether ``system`` has a value at ``path``."""
    try:
        return _parameters.get(system, path) is not None
    except ValueError:
        return False


def path_bounds(systems: Sequence, path: str, bounds) -> Tuple[float, float]:
    """The bounds of ``path`` in every one of ``systems`` (each from its own value; the given
    ``bounds`` for that path where there are some, else the system's ``fit_bounds``): their
    intersection."""
    given = None if bounds is None else {k: v for k, v in bounds.items() if k == path}
    lows, highs = [], []
    for s in systems:
        x0 = _parameters.get(s, path)
        own = with_system_bounds(s, given or None, [path])
        lo, hi = parameter_bounds(s, [path], np.array([x0]), own)
        lows.append(lo[0])
        highs.append(hi[0])
    return max(lows), min(highs)


def search_box(system, path: str, start: float, low: float, high: float) -> Tuple[float, float]:
    """A search's box for ``path`` within the fit's (low, high): the table's narrower one where it
    has one (the tilt's few fields of view)."""
    if _parameters.describe(path).search_bounds is None:
        return low, high
    lo, hi = _parameters.search_bounds(system, path, start)
    return max(lo, low), min(hi, high)


def checked_bounds(bounds, paths) -> Optional[dict]:
    """``bounds``: None or {path: (low, high)} of fitted paths, by scalar path (a bare pair bounds
    those of its scalars the fit frees, as in lo.fit)."""
    if bounds is None:
        return None
    if not isinstance(bounds, dict):
        raise ValueError(
            f"bounds = {_checks.shown(bounds)} is invalid: expected a dict path -> (low, high)"
        )
    out = {}
    for path, value in by_scalar("bounds", bounds, paths).items():
        if path not in paths:
            raise ValueError(
                f"bounds: {path} is not a fitted parameter: expected one of {', '.join(paths)}"
            )
        out[path] = _checks.pair(f"bounds[{path!r}]", value)
    return out


def joint_names(shared, own, n: int) -> List[str]:
    """The names of a joint fit's parameters: the ``shared`` paths, then each path of ``own`` once
    per curve of ``n`` (``path@i``: ``path`` of curve i)."""
    return list(shared) + [f"{p}@{i}" for p in own for i in range(n)]


def path_of(name: str) -> str:
    """The system path a joint fit's parameter ``name`` stands for (``path@i``: ``path``)."""
    return name.partition("@")[0]


def joint_problem(settings, systems, shared, own, bounds, start=None) -> MultiCurveProblem:
    """The multi-curve problem of shared and per-curve paths (module docstring's names); ``start``
    {name: value} overrides the systems' values."""
    n = len(systems)
    names = joint_names(shared, own, n)
    k = len(names)
    paths = tuple(shared) + tuple(own)
    maps = []
    for i, s in enumerate(systems):
        m = np.zeros((len(paths), k))
        for a in range(len(shared)):
            m[a, a] = 1.0
        for b in range(len(own)):
            m[len(shared) + b, len(shared) + b * n + i] = 1.0
        maps.append(CurveMap(s, paths, m))
    x0, low, high, scale, s_low, s_high, logs = (np.empty(k) for _ in range(7))
    for a, name in enumerate(names):
        path, _, index = name.partition("@")
        owners = [systems[int(index)]] if index else systems
        system = owners[0]
        x0[a] = _parameters.get(system, path) if start is None else start[name]
        low[a], high[a] = path_bounds(owners, path, bounds)
        if not low[a] <= x0[a] <= high[a]:
            raise ValueError(
                f"{name}: the start {x0[a]:g} lies outside the bounds ({low[a]:g}, {high[a]:g}) "
                "every curve's system allows: start the systems closer, or give bounds"
            )
        scale[a] = _parameters.step_scale(system, path)
        s_low[a], s_high[a] = search_box(system, path, x0[a], low[a], high[a])
        logs[a] = _parameters.searched_in_log(path, s_low[a])
    return MultiCurveProblem(
        settings, tuple(names), tuple(maps), x0, low, high, scale, s_low, s_high, logs.astype(bool)
    )
