"""Distributions of a tolerance study: what each parameter path may be off by, and the draws.

Every distribution draws an **offset added to the system's value** of its path (SI units, as in
:mod:`lidar_overlap.model.parameters`):

- ``("normal", mean_offset, sd)``: normal offsets; ``sd = 0`` gives ``mean_offset`` exactly;
- ``("uniform", low, high)``: offsets uniform in [low, high);
- any object with ``rvs(size=, random_state=)``, such as a frozen ``scipy.stats`` distribution
  (``scipy.stats.norm(0, 20e-6)``, ``scipy.stats.truncnorm(...)``).

A bare pair (``"beam.tilt"``) stands for both of its scalars, drawn independently from the same
distribution. All draws come from one ``numpy.random.Generator``, parameter by parameter in the
mapping's order, n at a time, so they depend on the seed, n and the mapping only.
"""

from __future__ import annotations

import math
from typing import Any, List, Mapping, Tuple

import numpy as np

from ... import _checks
from ...model import parameters
from ...model.system import LidarSystem

KINDS = ("normal", "uniform")


def normalized(system: LidarSystem, distributions: Any) -> List[Tuple[str, float, Any]]:
    """(path, nominal value, distribution) per scalar path, each checked; errors name
    ``distributions[...]``."""
    if not isinstance(distributions, Mapping) or not distributions:
        raise ValueError(
            f"distributions = {_checks.shown(distributions)} is invalid: expected a non-empty "
            "mapping of parameter paths to distributions, e.g. "
            "{'detector.defocus': ('normal', 0.0, 2e-4)}"
        )
    out, seen = [], set()
    for path, spec in distributions.items():
        name = f"distributions[{_checks.shown(path)}]"
        try:
            scalars = parameters.expand([path])
            nominal = [parameters.get(system, p) for p in scalars]
        except ValueError as exc:
            raise ValueError(f"{name}: {exc}") from None
        spec = _checked(name, spec)
        for p, v in zip(scalars, nominal):
            if p in seen:
                raise ValueError(f"{name} is invalid: {p} is named twice")
            seen.add(p)
            out.append((p, v, spec))
    return out


def draw(specs: List[Tuple[str, float, Any]], n: int, rng: np.random.Generator) -> np.ndarray:
    """The n x len(specs) drawn values (nominal + offset); a non-finite draw is refused naming
    member and path."""
    values = np.empty((n, len(specs)))
    for j, (path, nominal, spec) in enumerate(specs):
        if isinstance(spec, tuple):
            kind, a, b = spec
            offsets = rng.normal(a, b, n) if kind == "normal" else rng.uniform(a, b, n)
        else:
            try:
                offsets = np.asarray(spec.rvs(size=n, random_state=rng), dtype=float)
            except (TypeError, ValueError) as exc:
                raise ValueError(
                    f"distributions[{path!r}] = {_checks.shown(spec)} failed to draw: {exc}"
                ) from None
            if offsets.shape != (n,):
                raise ValueError(
                    f"distributions[{path!r}] = {_checks.shown(spec)} drew shape {offsets.shape}: "
                    f"expected ({n},) from rvs(size={n})"
                )
        values[:, j] = nominal + offsets
        bad = ~np.isfinite(values[:, j])
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(
                f"member {i}: {path} = {values[i, j]} drawn from distributions[{path!r}] is "
                "invalid: expected a finite value"
            )
    return values


def text(spec: Any) -> str:
    """A distribution as text, for the study's attributes."""
    if isinstance(spec, tuple):
        return f"{spec[0]}({spec[1]!r}, {spec[2]!r}) offset"
    dist = getattr(spec, "dist", None)  # scipy.stats frozen distributions
    if dist is not None and hasattr(spec, "args"):
        args = [repr(a) for a in spec.args] + [
            f"{k}={v!r}" for k, v in getattr(spec, "kwds", {}).items()
        ]
        return f"scipy.stats.{getattr(dist, 'name', type(dist).__name__)}({', '.join(args)}) offset"
    return f"{spec!r} offset"


def _checked(name: str, spec: Any):
    """A tuple spec as (kind, float, float) with valid numbers, or an object with ``rvs``."""
    if isinstance(spec, (tuple, list)):
        if len(spec) != 3 or not isinstance(spec[0], str) or spec[0] not in KINDS:
            raise ValueError(
                f"{name} = {_checks.shown(spec)} is invalid: expected ('normal', mean_offset, sd), "
                "('uniform', low, high) or an object with rvs(size, random_state)"
            )
        a, b = _checks.real(f"{name}[1]", spec[1]), _checks.real(f"{name}[2]", spec[2])
        if not (np.isfinite(a) and np.isfinite(b)):
            raise ValueError(f"{name} = {_checks.shown(spec)} is invalid: expected finite numbers")
        if spec[0] == "normal" and b < 0:
            raise ValueError(f"{name} = {_checks.shown(spec)} is invalid: expected sd >= 0")
        if spec[0] == "uniform" and not b >= a:
            raise ValueError(f"{name} = {_checks.shown(spec)} is invalid: expected low <= high")
        if spec[0] == "uniform" and not math.isfinite(b - a):
            raise ValueError(
                f"{name} = {_checks.shown(spec)} is invalid: expected high - low within double "
                "range (< 1.8e308)"
            )
        return (spec[0], a, b)
    if not callable(getattr(spec, "rvs", None)):
        raise ValueError(
            f"{name} = {_checks.shown(spec)} is invalid: expected ('normal', mean_offset, sd), "
            "('uniform', low, high) or an object with rvs(size, random_state)"
        )
    return spec
