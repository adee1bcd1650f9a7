"""``lo.fit(..., free="auto")``: a ladder of model families, each a physical explanation of an
overlap curve, fitted in turn (global search, then the local fit) and compared by the Bayesian
information criterion BIC = chi² + k ln n (n independent points, k free parameters; chi² with the
given sigma, so an information criterion needs sigma).

Each family starts from the one before's best (its search holds that point), so a larger family
never ends worse than a smaller one for want of search; and each smaller family is refitted locally
from a larger family's solution when that ended lower (a valley its own search missed). A family
whose fit leaves a parameter unconstrained (a singular Jacobian: infinite uncertainty, say an
acceptance that cuts no ray) is not supported by the data and is not chosen; nor is one whose fit of
relative data puts the model's absolute G below ``MIN_FAR_OVERLAP`` where the data are normalised (a
beam mostly outside the field of view can have the right shape, but a working lidar sees most of its
beam far away).

Choice: among the supported families, the one of lowest BIC; if a simpler one is within
``BIC_TIE`` of it, the simplest such one (a BIC difference below 2 is not evidence). Each family
also says whether it reaches the noise: chi²/dof within ``CHI2_SIGMAS`` standard deviations
sqrt(2/dof) of 1, and the residuals' signs not in fewer runs than chance gives (one-sided
Wald-Wolfowitz runs test, p > ``RUNS_P``). When none does, the result says so: the curve needs a
model the ladder does not have.

Cost. Each family runs the global search with the fit's own search settings, so ``generations``,
``population``, ``minima`` and ``max_evaluations`` of ``lo.fit`` search longer (or shorter) in every
family. A fit planned on Fourier optics (auto's choice where diffraction at the receiver matters)
searches on ray tracing and refines on Fourier optics
(:mod:`~lidar_overlap.analysis.fitting.global_search`); its local fits on Fourier optics remain the
ladder's costliest part (about 1-2 CPU minutes on a 100-150 point PollyXT curve).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

import numpy as np

from ... import _checks, _values
from ..._pickling import ByArguments, ByValue
from ...model import parameters as _parameters
from .families import LADDER, Family
from .global_result import with_search
from .global_search import fit_global
from .problem import FitProblem
from .relative import polish
from .result import DegeneracyWarning, FitResult
from .verdict import FitQualityWarning

#: BIC differences below this are no evidence (Kass and Raftery's "not worth more than a mention").
BIC_TIE = 2.0
#: chi²/dof reaches the noise when it is below 1 + CHI2_SIGMAS sqrt(2 / dof).
CHI2_SIGMAS = 3.0
#: The residual signs pass the runs test when its one-sided p-value exceeds this.
RUNS_P = 0.01
#: Relative fits: the least absolute G where the data are normalised for a plausible instrument.
MIN_FAR_OVERLAP = 0.5


@dataclass(frozen=True)
class FailedFit:
    """A family the ladder added whose fit left the model's range: the ``reason``."""

    reason: str


@dataclass(frozen=True, eq=False)
class FamilyScore(ByValue, ByArguments):
    """One family's fit: ``family``, ``fit`` (its FitResult), ``k``, ``bic``, ``chi2_dof``,
    ``runs_p`` (one-sided runs test of the residual signs), ``reaches_noise``; ``dropped``: paths
    the system cannot free (a numerical aperture of None); ``supported``: every parameter has a
    finite uncertainty and, for relative data, the model's absolute G where they are normalised is
    at least MIN_FAR_OVERLAP."""

    family: Family
    fit: Any
    k: int
    bic: float
    chi2_dof: float
    runs_p: float
    reaches_noise: bool
    dropped: Tuple[str, ...]
    supported: bool = True

    def __post_init__(self) -> None:
        _kind("family", self.family, Family, "a Family of the ladder")
        _kind("fit", self.fit, FitResult, "the family's FitResult")
        _values.check(
            self,
            {
                "k": _values.count(0),
                "bic": _values.real(),
                "chi2_dof": _values.real(low=0.0, nan=True, inf=True),
                "runs_p": _values.real(low=0.0),
                "reaches_noise": _values.flag,
                "supported": _values.flag,
            },
        )
        if not self.runs_p <= 1.0:
            raise _checks.refused("runs_p", self.runs_p, "a p-value from 0 to 1")
        if not isinstance(self.dropped, (tuple, list)):
            raise _checks.refused("dropped", self.dropped, "a tuple of parameter paths")
        dropped = tuple(_values.text(f"dropped[{i}]", p) for i, p in enumerate(self.dropped))
        object.__setattr__(self, "dropped", dropped)


@dataclass(frozen=True, eq=False)
class LadderResult(ByValue, ByArguments):
    """The ladder's outcome: ``chosen`` (the FitResult of the family chosen), ``chosen_family``,
    ``scores`` (every family, simplest first), ``criterion`` ("BIC") and ``note`` (None, or why no
    family reaches the noise)."""

    chosen: Any
    chosen_family: Family
    scores: Tuple[FamilyScore, ...]
    criterion: str
    note: Optional[str]

    def __post_init__(self) -> None:
        _kind("chosen", self.chosen, FitResult, "the chosen family's FitResult")
        _kind("chosen_family", self.chosen_family, Family, "a Family of the ladder")
        if not isinstance(self.scores, (tuple, list)) or not self.scores:
            raise _checks.refused("scores", self.scores, "a tuple of FamilyScore, one per family")
        for i, score in enumerate(self.scores):
            _kind(f"scores[{i}]", score, FamilyScore, "a FamilyScore")
        object.__setattr__(self, "scores", tuple(self.scores))
        if not any(s.family == self.chosen_family and s.fit == self.chosen for s in self.scores):
            raise _checks.refused(
                "chosen_family", self.chosen_family, "the family of one of scores, chosen its fit"
            )
        if self.criterion != "BIC":
            raise _checks.refused("criterion", self.criterion, "'BIC'")
        if self.note is not None:
            _values.text("note", self.note)

    def summary(self) -> str:
        lines = [f"model ladder ({self.criterion}): chosen '{self.chosen_family.name}'"]
        for s in self.scores:
            mark = "*" if s.family is self.chosen_family else " "
            lines.append(
                f" {mark} {s.family.name:<30} k {s.k}  BIC {s.bic:9.2f}  chi2/dof {s.chi2_dof:6.3f}"
                f"  runs p {s.runs_p:.3g}  {'reaches the noise' if s.reaches_noise else ''}"
                f"{'' if s.supported else '  (not supported: see FamilyScore.supported)'}"
            )
        if getattr(self.chosen, "extinction_bias", None) is not None:
            lines.append(
                "  every family carries the retrieval's extinction bias (counted in k): it "
                "describes how the data were retrieved, not the instrument"
            )
        if self.note:
            lines.append(f"  {self.note}")
        return "\n".join(lines) + "\n" + self.chosen.summary()

    __str__ = summary


def _kind(name: str, value, kind: type, expected: str) -> None:
    if not isinstance(value, kind):
        raise _checks.refused(name, value, expected)


def runs_p_value(residuals) -> float:
    """One-sided p-value of the Wald-Wolfowitz runs test: the chance of as few sign runs as
    ``residuals`` show if the signs were random (normal approximation). 1.0 when all signs agree is
    impossible to judge, so such a case returns 0.0 (all one sign is structure)."""
    s = np.sign(np.asarray(residuals, dtype=float))
    s = s[s != 0]
    n_pos, n_neg = int((s > 0).sum()), int((s < 0).sum())
    n = n_pos + n_neg
    if n_pos == 0 or n_neg == 0:
        return 0.0
    runs = 1 + int(np.count_nonzero(s[1:] != s[:-1]))
    mean = 2.0 * n_pos * n_neg / n + 1.0
    var = (mean - 1.0) * (mean - 2.0) / (n - 1.0)
    if not var > 0:
        return 1.0
    z = (runs - mean) / math.sqrt(var)
    return 0.5 * math.erfc(-z / math.sqrt(2.0))


def fit_ladder(problem: FitProblem, families=LADDER) -> LadderResult:
    """Fit each of ``families`` (global search from ``problem``'s start, with its data and
    settings) and choose one (module docstring)."""
    with warnings.catch_warnings():
        # each family's own quality and degeneracy warnings are its score in the ladder's report;
        # what the chosen family deserves is said once, below
        warnings.simplefilter("ignore", FitQualityWarning)
        warnings.simplefilter("ignore", DegeneracyWarning)
        fits = _fit_families(problem, families)
    system = problem.start
    failed = [(fam, f) for fam, f in zip(families, fits) if isinstance(f, FailedFit)]
    scores = [
        _score(fam.model(system), fam, f)
        for fam, f in zip(families, fits)
        if not isinstance(f, FailedFit)
    ]
    eligible = [s for s in scores if s.supported] or scores
    best = min(eligible, key=lambda s: s.bic)
    chosen = next(s for s in eligible if s.bic <= best.bic + BIC_TIE)
    note: Optional[str] = None
    if not any(s.reaches_noise for s in scores):
        note = (
            "no family reaches the noise (chi2/dof or the runs test): the curve needs a model the "
            "ladder does not have, or sigma is too small"
        )
    if failed:
        dropped = "; ".join(f"'{fam.name}' could not be fitted ({f.reason})" for fam, f in failed)
        note = f"{note}; {dropped}" if note else dropped
    if not chosen.fit.converged and not problem.allow_unconverged:
        raise RuntimeError(
            f"fit did not converge: the chosen family '{chosen.family.name}' stopped short; raise "
            "max_evaluations or pass allow_unconverged=True"
        )
    if not chosen.reaches_noise:
        _checks.warn(
            f"fit: the chosen family '{chosen.family.name}' does not reach the noise (chi2/dof "
            f"{chosen.chi2_dof:.3g}, runs test p {chosen.runs_p:.2g})"
            + (f"; {note}" if note else ""),
            FitQualityWarning,
        )
    if chosen.fit.degenerate_pairs:
        pairs = ", ".join(f"{a} and {b} ({c:+.3f})" for a, b, c in chosen.fit.degenerate_pairs)
        _checks.warn(f"fit: degenerate parameters in the chosen family: {pairs}", DegeneracyWarning)
    return LadderResult(chosen.fit, chosen.family, tuple(scores), "BIC", note)


def _fit_families(problem: FitProblem, families) -> list:
    """Each family fitted in turn by the global search, each starting from the one before, then
    refitted from a larger family's better solution."""
    fits: list = []
    best: Dict[str, Any] = {}
    for i, family in enumerate(families):
        if i == 0:
            start = problem.start
        else:
            before = families[i - 1].name if family.start_from is None else family.start_from
            start = best.get(before, best[families[i - 1].name])
        start = family.model(start)
        paths = [p for p in family.paths if _freeable(start, p)]
        given = _family_bounds(family, start, paths, problem.bounds)
        try:
            fit = fit_global(
                problem.derived(start=start, free=paths, bounds=given, allow_unconverged=True)
            )
        except ValueError as exc:
            if family.extend is None:  # the user's own model: its errors are the user's to see
                raise
            # a model the ladder added (a wing, a stop) left its range on the way (a Jacobian step
            # beyond the detector plane): the family drops out, said in the report
            fits.append(FailedFit(str(exc)))
            continue
        fits.append(fit)
        best[family.name] = _parameters.replace(start, fit.parameters)
    return _from_larger_families(problem, families, fits)


def _score(system, family: Family, f) -> FamilyScore:
    paths = [p for p in family.paths if _freeable(system, p)]
    dropped = tuple(p for p in family.paths if p not in paths)
    # the retrieval's extinction bias, when fitted, is one more free parameter of every family
    k = len(paths) + (getattr(f, "extinction_bias", None) is not None)
    n = f.degrees_of_freedom + k
    dof = max(f.degrees_of_freedom, 1)
    runs = runs_p_value(f.residuals)
    reaches = f.reduced_chi_square <= 1.0 + CHI2_SIGMAS * math.sqrt(2.0 / dof) and runs > RUNS_P
    supported = all(math.isfinite(v) for v in f.uncertainties.values())
    supported = supported and getattr(f, "model_scale", 1.0) >= MIN_FAR_OVERLAP
    bic = f.chi_square + k * math.log(n)
    return FamilyScore(family, f, k, bic, f.reduced_chi_square, runs, reaches, dropped, supported)


def _from_larger_families(problem: FitProblem, families, fits) -> list:
    """Each family's fit, replaced by a local fit of its own paths from the best solution of the
    larger families when that ends lower: a larger family's search may find a valley the smaller
    one's missed, and the smaller family can reach it too when the extra parameters do not matter
    there. (From the best only: each refit is a local fit of the fit's own model, the ladder's
    costliest step.)"""
    out = list(fits)
    for i in range(len(families) - 2, -1, -1):
        if isinstance(out[i], FailedFit):
            continue
        model = families[i].model(problem.start)
        paths = [p for p in families[i].paths if _freeable(model, p)]
        given = _family_bounds(families[i], model, paths, problem.bounds)
        larger = [
            out[j]
            for j in range(i + 1, len(families))
            if not isinstance(out[j], FailedFit)
            and out[j].chi_square < out[i].chi_square
            and set(paths) <= set(out[j].parameters)  # a larger model of family i's
        ]
        if not larger:
            continue
        better = min(larger, key=lambda f: f.chi_square)
        start = _parameters.replace(model, {p: better.parameters[p] for p in paths})
        local = problem.derived(start=start, free=paths, bounds=given, allow_unconverged=True)
        try:
            g = polish(local)
        except ValueError:  # that start lies outside the smaller family's bounds
            continue
        if g.chi_square < out[i].chi_square:
            out[i] = with_search(g, out[i].search, out[i].evaluations + g.evaluations)
    return out


def _family_bounds(family: Family, system, paths, bounds) -> Dict[str, Tuple[float, float]]:
    """The bounds given for ``paths``, else the family's own defaults (where it has them)."""
    own = family.bounds(system) if family.bounds is not None else {}
    out = {p: v for p, v in own.items() if p in paths}
    out.update({p: v for p, v in (bounds or {}).items() if p in paths})
    return out


def _freeable(system, path: str) -> bool:
    try:
        return _parameters.get(system, path) is not None
    except ValueError:
        return False
