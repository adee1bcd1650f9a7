"""``lo.fit_joint(..., free="auto")``: the family and which of its parameters are per-curve, chosen
on the joint data by BIC = chi² + K ln n (n independent points of all curves, K global parameters).

What it tries (bounded cost): each family of the ladder that does not extend the model
(alignment; + beam; + focus), first with every parameter shared (the first family by the joint
global search, each next one from the one before's solution); then, within that family, forward
selection of the per-curve parameters: the shared paths are ranked by the chi-square drop of one
Gauss-Newton step from the current solution with that path split into one value per curve, beyond
the step's with it shared (one Jacobian ranks them all; only the paths ``per_curve`` allows, when
given: those the instrument's physics lets differ between the curves); the best is fitted and taken
when it lowers the BIC by more than ``BIC_TIE``, until it does not. The family of lowest BIC after
its selection is chosen (a simpler one within ``BIC_TIE`` preferred). Cost: one search, and per
family at most k + 1 local fits and k Jacobians (k paths).

Model. A fit planned on Fourier optics of systems ray tracing models makes its whole choice on ray
tracing at its tolerance (as the single search compares and polishes its candidates,
:mod:`.multi_search`) and fits only the chosen family on its own plans. The result's
``evaluations`` count every model evaluation of the choice (the search's candidates, each family's
fits, the final fit), as a ladder's scores do.
"""

from __future__ import annotations

import dataclasses
import warnings
from typing import List

import numpy as np

from ...model import parameters as _parameters
from ...model.path_syntax import by_scalar
from .curve_set import CurveSet
from .families import LADDER
from .joint_result import JointFitResult, joint_result
from .ladder import BIC_TIE
from .multi_curve import MultiCurveFit, solve_curves
from .multi_inputs import checked_bounds, has_path, joint_names, joint_problem, path_of
from .multi_result import bic_of
from .multi_search import fit_curves, ray_traced_settings

#: The families tried: those of the ladder that do not extend the model.
FAMILIES = tuple(f for f in LADDER if f.extend is None)[:3]


def _start(fit: MultiCurveFit, names) -> dict:
    """``names``' start values from ``fit``: a per-curve name from its own or its shared value."""
    values = dict(zip(fit.problem.names, fit.values.tolist()))
    return {n: values[n] if n in values else values[path_of(n)] for n in names}


def fit_joint_auto(settings, systems, bounds, allowed=None) -> JointFitResult:
    """The joint fit with its family and per-curve parameters chosen (module docstring); only the
    paths of ``allowed`` may be per-curve (None: any of the family's)."""
    # the choice on ray tracing where the plans are Fourier optics; the chosen fit on the plans
    quiet = ray_traced_settings(settings, systems).derived(allow_unconverged=True)
    choices: List[str] = []
    scored = []
    spent = [0]  # the model evaluations of every fit the choice made
    previous = None
    for i, family in enumerate(FAMILIES):
        paths = tuple(p for p in family.paths if all(has_path(s, p) for s in systems))
        given = checked_bounds(
            {k: v for k, v in by_scalar("bounds", bounds or {}).items() if k in paths}, paths
        )
        start = None
        if previous is not None:
            start = {p: _parameters.get(systems[0], p) for p in paths}
            start.update(zip(previous.problem.names, previous.values.tolist()))
        kind = "global" if i == 0 else "local"
        local = quiet.derived(search=dataclasses.replace(quiet.search, kind=kind))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # each family's verdicts: its score here
            shared_fit = fit_curves(joint_problem(local, systems, paths, (), given, start))
        spent[0] += shared_fit.evaluations
        choices.append(
            f"family '{family.name}', all shared: chi-square {shared_fit.chi_square:.4g}, BIC "
            f"{bic_of(shared_fit):.2f}"
        )
        fit, own = _per_curve(quiet, systems, paths, given, shared_fit, choices, spent, allowed)
        scored.append((bic_of(fit), family, paths, own, given, fit))
        previous = shared_fit
    lowest = min(s[0] for s in scored)
    bic, family, paths, own, given, best = next(s for s in scored if s[0] <= lowest + BIC_TIE)
    choices.append(
        f"chosen: family '{family.name}', per-curve {', '.join(own) if own else 'none'} "
        f"(BIC {bic:.2f})"
    )
    shared = [q for q in paths if q not in own]
    start = _start(best, joint_names(shared, own, len(systems)))
    final = solve_curves(joint_problem(settings, systems, shared, own, given, start))
    final = dataclasses.replace(final, evaluations=final.evaluations + spent[0])
    return joint_result(final, family.name, choices)


def _per_curve(settings, systems, paths, given, fit, choices, spent, allowed):
    """(the fit, the per-curve paths) of the forward selection within one family; ``spent[0]``
    gains the model evaluations of its fits."""
    n = len(systems)
    own: List[str] = []
    best, best_bic = fit, bic_of(fit)
    splittable = [p for p in paths if allowed is None or p in allowed]
    while len(own) < len(splittable):
        candidates = [p for p in splittable if p not in own]
        drops = _linear_drops(settings, systems, paths, own, candidates, given, best)
        spent[0] += 1  # the residuals it ranks from (Jacobians are not model evaluations)
        p = max(drops, key=lambda q: drops[q])
        shared = [q for q in paths if q not in own + [p]]
        start = _start(best, joint_names(shared, own + [p], n))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            trial = solve_curves(joint_problem(settings, systems, shared, own + [p], given, start))
        spent[0] += trial.evaluations
        bic = bic_of(trial)
        choices.append(f"  per-curve {', '.join(own + [p])}: chi-square {trial.chi_square:.4g}, "
                       f"BIC {bic:.2f}")  # fmt: skip
        if not bic < best_bic - BIC_TIE:
            break
        own.append(p)
        best, best_bic = trial, bic
    return best, own


def _linear_drops(settings, systems, paths, own, candidates, given, fit) -> dict:
    """{candidate: the chi-square drop of one Gauss-Newton step from ``fit`` with that path one
    value per curve}: one Jacobian with every candidate split ranks them."""
    n = len(systems)
    shared = [q for q in paths if q not in own + candidates]
    names = joint_names(shared, own + candidates, n)
    problem = joint_problem(settings, systems, shared, own + candidates, given, _start(fit, names))
    model = CurveSet(problem)
    r = model.residuals(problem.start)
    j = model.jacobian(problem.start)
    drops = {}
    fixed = [a for a, name in enumerate(names) if path_of(name) not in candidates]
    summed = [
        j[:, [a for a, name in enumerate(names) if path_of(name) == q]].sum(axis=1)
        for q in candidates
    ]
    # the step with every candidate still shared: what the current solution would gain anyway
    base = _step_drop(np.column_stack([j[:, fixed], *summed]), r)
    for p in candidates:
        keep = [a for a, name in enumerate(names) if path_of(name) not in candidates]
        keep += [a for a, name in enumerate(names) if path_of(name) == p]
        # the other candidates stay shared: their per-curve columns summed
        others = [
            j[:, [a for a, name in enumerate(names) if path_of(name) == q]].sum(axis=1)
            for q in candidates
            if q != p
        ]
        a = np.column_stack([j[:, keep], *others]) if others else j[:, keep]
        drops[p] = _step_drop(a, r) - base
    return drops


def _step_drop(a, r) -> float:
    """The chi-square drop of the Gauss-Newton step in the columns ``a`` from residuals ``r``."""
    step = np.linalg.lstsq(a, -r, rcond=None)[0]
    after = r + a @ step
    return float(r @ r - after @ after)
