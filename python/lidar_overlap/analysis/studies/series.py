"""``lo.fit_series``: one local fit per curve of a series (the days of one instrument), the model
family fixed, on a ``dask.distributed`` client or in this process, as an ``xarray.Dataset``.

Warm start, and why the bits do not depend on where it runs: the curves are cut into chunks of
``chunk`` consecutive curves, fixed by the series alone (never by the client or its workers). The
first curve of each chunk starts from ``system``; each further curve of a chunk starts from the
previous curve's fitted values when that fit converged (else from ``system`` again). A chunk is one
task, run with one core thread; so a chunk's fits are the same calls, in the same order, whether
the chunks run in a loop, in dask's threads or on a cluster.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

from ... import _checks
from ...model import parameters
from .. import engines
from ..datasets import xarray
from ..fitting.problem import fit_problem
from ..fitting.relative import polish

#: Curves per task (and per warm-started run): 8 daily fits of a few tenths of a second each keep
#: the task overhead small and leave 153 days 20 tasks to spread.
CHUNK = 8
#: lo.fit keywords fit_series sets itself (one thread per task, an unconverged fit kept and
#: flagged) or leaves out (the global search's: every curve is a local fit from its warm start).
_OWN = ("threads", "allow_unconverged", "search", "seed", "population", "generations", "minima")


def fit_series(
    system,
    ranges,
    curves,
    *,
    coords: Optional[Mapping] = None,
    sigma,
    free: Sequence[str],
    normalize=None,
    chunk: int = CHUNK,
    client=None,
    **options,
):
    """Fit the ``free`` parameters of ``system`` (the start, its family fixed: e.g. the system of a
    ladder fit of the series' median curve) to each row of ``curves`` (n_curves x n_ranges, G at
    ``ranges`` in m), one local ``lo.fit`` per curve, warm-started within chunks of ``chunk``
    curves (module docstring).

    coords : {name: one value per curve}; the first names the series' dimension (e.g. ``"date"``:
    numpy datetime64), the others (covariates, e.g. ``"internal_temperature_K"``: finite numbers)
    are coordinates along it. None: the dimension ``curve``, numbered from 0.
    sigma : 1-sigma error: a scalar, one per range, or one per curve and range (n_curves x
    n_ranges). normalize : as in ``lo.fit`` (relative data). Other keywords (``bounds``,
    ``method``, ``tolerance``, ``loss``, ``max_evaluations``, ``extinction_bias``) go to each
    ``lo.fit``. client : a ``dask.distributed.Client`` (None: dask's threads here, or a loop
    without dask); the result is bit for bit the same on either.

    Returns an ``xarray.Dataset`` along the series' dimension: ``value`` and ``uncertainty``
    (x ``parameter``, SI units in the ``unit`` coordinate), ``rms`` (RMS of model - data, on the
    normalised scale for relative data), ``noise`` (RMS of sigma), ``reduced_chi_square``,
    ``converged``, ``evaluations`` (model curves); with ``extinction_bias=True`` also
    ``extinction_bias`` and ``extinction_bias_uncertainty`` (1/m: each curve's retrieval error δα
    and its 1-sigma uncertainty, ``lo.fit``'s). Needs scipy and xarray.
    """
    xr = xarray("fit_series")
    z = _checks.ranges("ranges", ranges)
    g = _curves(curves, z.size)
    n = g.shape[0]
    sigmas = _sigma(sigma, n, z.size)
    if isinstance(free, str):
        raise ValueError(
            f"free = {free!r} is invalid: expected a list of parameter paths (the family is "
            "fixed in a series: choose it with lo.fit(..., free='auto') on one curve, e.g. the "
            "median)"
        )
    given = sorted(set(options) & set(_OWN))
    if given:
        raise ValueError(f"{given[0]} is set by fit_series itself: expected it left out")
    chunk = _checks.count("chunk", chunk, 1)
    dimension, coordinates = _coordinates(coords, n)
    kind = engines.engine(client)
    settings = dict(options, free=list(free), normalize=normalize, allow_unconverged=True)
    # every argument checked before any fit runs: the settings on the first curve (lo.fit's own
    # checks), the values of all (planning each curve's problem costs ~35 ms)
    for name, values, low in (("curves", g, -np.inf), ("sigma", sigmas, 0.0)):
        bad = ~(np.isfinite(values) & (values > low))
        if bad.any():
            i, j = np.unravel_index(int(np.argmax(bad)), bad.shape)
            expected = "finite" if name == "curves" else "finite and > 0"
            raise ValueError(
                f"{name}[{i}, {j}] = {float(values[i, j])!r} (curve {i}, range {z[j]:g} m) is "
                f"invalid: expected {expected}"
            )
    paths = list(fit_problem(system, z, g[0], sigmas[0], **settings).free)
    bounds = [(s, min(s + chunk, n)) for s in range(0, n, chunk)]
    rows = engines.run_tasks(
        kind,
        client,
        _fit_chunk,
        system,
        [(z, g[s:e], sigmas[s:e], settings, s) for s, e in bounds],
        engines.workers(client, 0),
    )
    fits = [row for part in rows for row in part]
    along = (dimension,)
    table = {
        key: np.array([[f[key][p] for p in paths] for f in fits])
        for key in ("value", "uncertainty")
    }
    described = {**_SCALARS, **(_BIAS if options.get("extinction_bias") else {})}
    scalar = {key: np.array([f[key] for f in fits]) for key in described}
    return xr.Dataset(
        {
            "value": (along + ("parameter",), table["value"], {"long_name": "fitted value"}),
            "uncertainty": (
                along + ("parameter",),
                table["uncertainty"],
                {"long_name": "1-sigma uncertainty of the fitted value"},
            ),
            **{
                key: (along, scalar[key], _attributes(key, text)) for key, text in described.items()
            },
        },
        coords={
            **coordinates,
            "parameter": ("parameter", paths),
            "unit": ("parameter", [parameters.unit(p) for p in paths]),
        },
        attrs={
            "engine": kind,
            "normalize": repr(normalize),
            "chunk": chunk,
            "warm_start": "each curve from the previous converged fit of its chunk; each chunk "
            "from the given system",
        },
    )


#: The per-curve scalars of the dataset, with their meaning.
_SCALARS = {
    "rms": "RMS of model - data (normalised scale for relative data)",
    "noise": "RMS of the curve's 1-sigma errors",
    "reduced_chi_square": "chi-square per degree of freedom",
    "converged": "the optimiser converged",
    "evaluations": "model curves computed",
}


#: With extinction_bias=True, the retrieval's extinction bias per curve (1/m), with its meaning.
_BIAS = {
    "extinction_bias": "the retrieval's extinction bias delta_alpha the fit profiled",
    "extinction_bias_uncertainty": "1-sigma uncertainty of the extinction bias",
}


def _attributes(key: str, text: str) -> Dict[str, str]:
    return {"long_name": text, **({"units": "1/m"} if key in _BIAS else {})}


def _fit_chunk(system, z, curves, sigmas, settings, first) -> List[Dict[str, Any]]:
    """The fits of consecutive curves, each warm-started from the previous converged one."""
    out = []
    start = system
    for k in range(curves.shape[0]):
        try:
            result = polish(fit_problem(start, z, curves[k], sigmas[k], threads=1, **settings))
        except ValueError as exc:
            raise ValueError(f"curve {first + k}: {exc}") from None
        residual = np.asarray(result.residuals) * np.asarray(result.sigma)
        out.append(
            {
                "value": dict(result.parameters),
                "uncertainty": dict(result.uncertainties),
                "rms": float(np.sqrt(np.mean(residual**2))),
                "noise": float(np.sqrt(np.mean(np.asarray(result.sigma) ** 2))),
                "reduced_chi_square": result.reduced_chi_square,
                "converged": bool(result.converged),
                "evaluations": int(result.evaluations),
                # None (not fitted) kept as NaN: the dataset holds these only when it was
                **{key: _number(getattr(result, key, None)) for key in _BIAS},
            }
        )
        start = parameters.replace(system, result.parameters) if result.converged else system
    return out


def _number(value) -> float:
    return math.nan if value is None else float(value)


def _curves(curves, n_ranges: int) -> np.ndarray:
    g = _checks.real_array("curves", curves)
    if g.ndim != 2:
        raise ValueError(
            f"curves has shape {g.shape}: expected (n_curves, {n_ranges}), one row per curve "
            "(one curve alone: lo.fit)"
        )
    if g.shape[1] != n_ranges or g.shape[0] == 0:
        raise ValueError(
            f"curves has shape {g.shape}: expected (n_curves >= 1, {n_ranges}), one column per "
            "range"
        )
    return g


def _sigma(sigma, n: int, n_ranges: int) -> np.ndarray:
    """sigma as one row per curve (each row is checked by lo.fit's own rules)."""
    s = _checks.real_array("sigma", sigma)
    if s.ndim == 0 or s.shape == (n_ranges,):
        return np.broadcast_to(s, (n, n_ranges))
    if s.shape == (n, n_ranges):
        return s
    raise ValueError(
        f"sigma has shape {s.shape}: expected a scalar, ({n_ranges},) one per range or "
        f"({n}, {n_ranges}) one per curve and range"
    )


def _coordinates(coords, n: int):
    """(the series' dimension, its coordinates): each coordinate one value per curve, numbers
    finite, dates without NaT."""
    if coords is None:
        return "curve", {"curve": ("curve", np.arange(n))}
    if not isinstance(coords, Mapping) or not coords:
        raise ValueError(
            f"coords = {_checks.shown(coords)} is invalid: expected a mapping of names to one "
            "value per curve, or None"
        )
    names = list(coords)
    out = {}
    for name in names:
        if not isinstance(name, str) or not name.isidentifier():
            raise ValueError(f"coords key {_checks.shown(name)} is invalid: expected a name")
        values = np.asarray(coords[name])
        if values.shape != (n,):
            raise ValueError(
                f"coords[{name!r}] has shape {values.shape}: expected ({n},), one value per curve"
            )
        if values.dtype.kind == "M":
            bad = np.isnat(values)
        else:
            values = _checks.real_array(f"coords[{name!r}]", values)
            bad = ~np.isfinite(values)
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(
                f"coords[{name!r}][{i}] = {values[i]} is invalid: expected a finite value for "
                "every curve (select the curves that have one)"
            )
        out[name] = (names[0], values)
    return names[0], out
