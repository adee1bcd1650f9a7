"""``lo.fit_joint(..., free="auto")``: the family and which of its parameters are per-curve, chosen
on the joint data by BIC = chi² + K ln n (n independent points of all curves, K global parameters).

What it tries (bounded cost): each family of the ladder without an extended model (alignment; +
beam; + focus), every parameter shared, from the best fit of the family before (the first by the
joint global search); the family of lowest BIC (a simpler one within ``BIC_TIE`` preferred). Then
forward selection of per-curve parameters in that family: each shared path is tried as per-curve
(a local fit from the current solution) and the one of lowest BIC is taken when it lowers the BIC
by more than ``BIC_TIE``, until none does: at most k (k + 1) / 2 local fits for k paths.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import List

from ...model import parameters as _parameters
from .families import LADDER
from .joint_result import JointFitResult, joint_result
from .ladder import BIC_TIE
from .multi_curve import MultiCurveFit, solve_curves
from .multi_inputs import checked_bounds, has_path, joint_problem
from .multi_search import fit_curves

#: The families tried: those of the ladder that do not extend the model.
FAMILIES = tuple(f for f in LADDER if f.extend is None)[:3]


def _bic(fit: MultiCurveFit) -> float:
    n = fit.degrees_of_freedom + len(fit.values)
    return fit.chi_square + len(fit.values) * math.log(n)


def fit_joint_auto(settings, systems, bounds) -> JointFitResult:
    """The joint fit with its family and per-curve parameters chosen (module docstring)."""
    quiet = settings.derived(allow_unconverged=True)
    choices: List[str] = []
    scored = []
    previous = None
    for i, family in enumerate(FAMILIES):
        paths = tuple(p for p in family.paths if all(has_path(s, p) for s in systems))
        given = checked_bounds({k: v for k, v in (bounds or {}).items() if k in paths}, paths)
        start = None
        if previous is not None:
            start = {p: _parameters.get(systems[0], p) for p in paths}
            start.update({n: v for n, v in zip(previous.problem.names, previous.values)})
        kind = "global" if i == 0 else "local"
        local = quiet.derived(search=dataclasses.replace(quiet.search, kind=kind))
        problem = joint_problem(local, systems, paths, (), given, start)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # each family's verdicts: its score here
            fit = fit_curves(problem)
        scored.append((_bic(fit), family, paths, given, fit))
        choices.append(
            f"family '{family.name}', all shared: chi-square {fit.chi_square:.4g}, BIC "
            f"{scored[-1][0]:.2f}"
        )
        previous = fit
    lowest = min(s[0] for s in scored)
    bic, family, paths, given, best = next(s for s in scored if s[0] <= lowest + BIC_TIE)
    own: List[str] = []
    while len(own) < len(paths):
        values = dict(zip(best.problem.names, best.values.tolist()))
        trials = []
        for p in paths:
            if p in own:
                continue
            shared = [q for q in paths if q not in own + [p]]
            names = _names(shared, own + [p], len(systems))
            start = {n: values[n] if n in values else values[n.split("@")[0]] for n in names}
            problem = joint_problem(quiet, systems, shared, own + [p], given, start)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                trial = solve_curves(problem)
            trials.append((_bic(trial), p, trial))
            choices.append(
                f"per-curve {', '.join(own + [p])}: chi-square {trial.chi_square:.4g}, BIC "
                f"{trials[-1][0]:.2f}"
            )
        if not trials:
            break
        trial_bic, p, trial = min(trials, key=lambda t: t[0])
        if not trial_bic < bic - BIC_TIE:
            break
        own.append(p)
        bic, best = trial_bic, trial
    choices.append(
        f"chosen: family '{family.name}', per-curve {', '.join(own) if own else 'none'} "
        f"(BIC {bic:.2f})"
    )
    shared = [q for q in paths if q not in own]
    start = dict(zip(best.problem.names, best.values.tolist()))
    final = solve_curves(joint_problem(settings, systems, shared, own, given, start))
    return joint_result(final, family.name, choices)


def _names(shared, own, n: int) -> List[str]:
    return list(shared) + [f"{p}@{i}" for p in own for i in range(n)]
