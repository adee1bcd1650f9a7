"""What a global fit reports beyond the local fit it ends with: the search (candidates, core calls)
and the distinct minima it polished, with their costs
(:mod:`lidar_overlap.analysis.fitting.global_search`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Dict, Optional, Tuple

from ... import _values
from .relative_result import RelativeFitResult
from .result import FitResult


@dataclass(frozen=True)
class SearchMinimum:
    """One polished minimum: ``parameters`` (path -> SI value) and ``chi_square`` after the local
    fit, ``candidate_cost`` (the search's cost of its starting candidate), ``converged`` and
    ``evaluations`` of the local fit."""

    parameters: Dict[str, float]
    chi_square: float
    candidate_cost: float
    converged: bool
    evaluations: int

    def __post_init__(self) -> None:
        object.__setattr__(self, "parameters", _values.reals()("parameters", self.parameters))


@dataclass(frozen=True)
class SearchReport:
    """How the global search ran: ``method``, ``seed``, ``population`` (candidates per generation),
    ``generations`` run, ``candidates`` evaluated, ``core_calls`` (one per generation on ray
    tracing), ``local_evaluations`` (curves of the local fits, every polished candidate counted),
    ``minima`` (distinct, best first; the first is the result), the ``bounds`` searched,
    ``chosen``: the paths whose bounds the search chose (none given: a box about the start, or the
    fit's defaults) and ``dark_start``: whether the start's model was zero at every fitted range
    (then no box about it)."""

    method: str
    seed: int
    population: int
    generations: int
    candidates: int
    core_calls: int
    local_evaluations: int
    minima: Tuple[SearchMinimum, ...]
    bounds: Dict[str, Tuple[float, float]]
    chosen: Tuple[str, ...] = ()
    dark_start: bool = False

    def __post_init__(self) -> None:
        pairs = {p: _values.pair(f"bounds[{p!r}]", b) for p, b in dict(self.bounds).items()}
        object.__setattr__(self, "bounds", _values.FrozenMap(pairs))
        object.__setattr__(self, "minima", tuple(self.minima))
        chosen = tuple(_values.text(f"chosen[{i}]", p) for i, p in enumerate(self.chosen))
        unknown = [p for p in chosen if p not in pairs]
        if unknown:
            raise ValueError(
                f"chosen = {chosen!r} is invalid: expected paths of bounds, not {unknown[0]!r}"
            )
        object.__setattr__(self, "chosen", chosen)
        object.__setattr__(self, "dark_start", _values.flag("dark_start", self.dark_start))

    def summary(self) -> str:
        lines = [
            f"global search ({self.method}, seed {self.seed}): {self.generations} generations of "
            f"{self.population}, {self.candidates} candidates in {self.core_calls} batched calls"
        ]
        searched = ", ".join(
            f"{p} [{lo:.4g}, {hi:.4g}]{' (chosen)' if p in self.chosen else ''}"
            for p, (lo, hi) in self.bounds.items()
        )
        lines.append(f"  bounds {searched}")
        if self.dark_start:
            lines.append(
                "  the start sees no light at any fitted range: the fit's default bounds searched"
            )
        for rank, m in enumerate(self.minima):
            what = "best" if rank == 0 else f"runner-up {rank}"
            values = ", ".join(f"{p} {v:.4g}" for p, v in m.parameters.items())
            lines.append(f"  {what}: chi-square {m.chi_square:.4g} ({values})")
        return "\n".join(lines)


class _WithSearch:
    search: Optional[SearchReport]

    def summary(self) -> str:
        base = super().summary()  # type: ignore[misc]
        return base if self.search is None else base + "\n" + self.search.summary()

    def __str__(self) -> str:
        return self.summary()


@dataclass(frozen=True, eq=False)
class GlobalFitResult(_WithSearch, FitResult):
    """A :class:`FitResult` of ``lo.fit(..., search="global")`` with its ``search`` report;
    ``evaluations`` counts the search's candidates and the local fits' curves."""

    search: Optional[SearchReport] = None


@dataclass(frozen=True, eq=False)
class GlobalRelativeFitResult(_WithSearch, RelativeFitResult):
    """A :class:`RelativeFitResult` of a global fit, with its ``search`` report."""

    search: Optional[SearchReport] = None


def with_search(result: FitResult, report: SearchReport, evaluations: int) -> FitResult:
    """``result`` as the matching global result type, with ``report`` and the total
    ``evaluations``."""
    kind = GlobalRelativeFitResult if isinstance(result, RelativeFitResult) else GlobalFitResult
    fields = {f.name: getattr(result, f.name) for f in dataclasses.fields(result)}
    fields.update(search=report, evaluations=evaluations)
    return kind(**fields)
