"""The global search of a fit of several curves (``search="global"`` of ``lo.fit_joint`` and
``lo.fit_drift``): the population search of :mod:`lidar_overlap.analysis.fitting.global_search` over
the joint space, each candidate's cost the sum of the curves' whitened costs on thinned ranges (the
curves of a group in one batched call per generation), then the local fit
(:mod:`lidar_overlap.analysis.fitting.multi_curve`) from the best distinct minima; the best becomes
the result, with the search's report.

Model. As the single global search does (:func:`.global_search.ray_traced`): when some curve's plan
is Fourier optics of a system ray tracing models, the candidates are compared and the minima
polished on ray tracing at the fit's tolerance (a generation is then one batched call, not one FO
curve per candidate), and the best minimum is then refined on the fit's own plans, which gives the
result."""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from ...forward.methods import RT
from ..batch_curves import curves as batch
from .curve_set import CurveSet
from .global_result import SearchMinimum, SearchReport
from .global_search import UnitCube, distinct_minima, population_search
from .multi_curve import MultiCurveFit, MultiCurveProblem, solve_curves
from .solve import fit_plan


def search_curves(problem: MultiCurveProblem) -> MultiCurveFit:
    """The global search over the joint space, then the local fit from its best distinct minima
    (module docstring); the best becomes the result, with the search's report."""
    settings = problem.settings
    searched = ray_traced_curves(problem)
    model = CurveSet(searched, thin=True)
    cube = UnitCube(problem.search_low, problem.search_high, problem.logs)

    def cost(x):  # candidates (S, K) -> the sum of the curves' whitened costs
        total = np.zeros(x.shape[0])
        for group in model.groups:
            systems = []
            for row in x:
                for i in group:
                    try:
                        systems.append(model.maps[i].at(row))
                    except ValueError:
                        systems.append(None)
            g = batch(model.plans[group[0]], systems).reshape(x.shape[0], len(group), -1)
            for slot, i in enumerate(group):
                total += model.norms[i].whitened_cost(g[:, slot])
        return total

    start = np.clip(problem.start, problem.search_low, problem.search_high)
    solution, u_all, c_all, calls = population_search(cost, cube, start, settings.search)
    starts = distinct_minima(u_all, c_all, settings.search.minima)
    fits, caught = [], []
    for i in starts:
        theta = cube.values(u_all[i][None])[0]
        local = _allow_unconverged(dataclasses.replace(searched, start=theta))
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            fits.append((solve_curves(local), float(c_all[i])))
        caught.append(record)
    order = sorted(range(len(fits)), key=lambda j: fits[j][0].chi_square)
    best, record, refined = fits[order[0]][0], caught[order[0]], 0
    if searched is not problem:  # the best valley, refined on the fit's own plans
        local = _allow_unconverged(dataclasses.replace(problem, start=best.values))
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            best = solve_curves(local)
        refined = best.evaluations
    for item in record:  # the best's warnings, said once
        warnings.warn_explicit(item.message, item.category, item.filename, item.lineno)
    if not best.converged and not settings.allow_unconverged:
        raise RuntimeError(
            "fit did not converge: the local fit from the global search's best candidate stopped "
            f"short ({best.message}); raise max_evaluations or pass allow_unconverged=True"
        )
    report = SearchReport(
        method="differential evolution"
        + ("" if searched is problem else ", candidates ray traced (the best refined on FO)"),
        seed=settings.search.seed,
        population=int(np.asarray(solution.population).shape[0]),
        generations=int(solution.nit),
        candidates=int(c_all.size),
        core_calls=calls,
        local_evaluations=sum(f.evaluations for f, _ in fits) + refined,
        minima=tuple(
            SearchMinimum(
                dict(zip(problem.names, f.values.tolist())),
                f.chi_square,
                candidate,
                f.converged,
                f.evaluations,
            )
            for f, candidate in (fits[j] for j in order)
        ),
        bounds={
            name: (float(lo), float(hi))
            for name, lo, hi in zip(problem.names, problem.search_low, problem.search_high)
        },
    )
    evaluations = int(c_all.size) + report.local_evaluations
    return MultiCurveFit(**{**best.__dict__, "search": report, "evaluations": evaluations})


def ray_traced_curves(problem: MultiCurveProblem) -> MultiCurveProblem:
    """The problem the search and the polish of its minima run: ``problem`` itself, or the same on
    ray tracing (:func:`ray_traced_settings`)."""
    traced = ray_traced_settings(problem.settings, [m.system for m in problem.maps])
    return problem if traced is problem.settings else dataclasses.replace(problem, settings=traced)


def ray_traced_settings(settings, systems):
    """``settings`` (a FitProblem holding one curve per system of ``systems``) themselves, or the
    same on ray tracing at their tolerance when some curve's plan is Fourier optics of a system ray
    tracing models (module docstring) and every curve's plan then is ray tracing."""
    pairs = list(zip(systems, settings.curves))
    if all(fit_plan(settings, s, c.ranges).method != "fo" for s, c in pairs):
        return settings
    traced = settings.derived(method=RT(tolerance=settings.tolerance))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # RT's validity: the refinement on FO answers it
            methods = {fit_plan(traced, s, c.ranges).method for s, c in pairs}
    except ValueError:  # a system only Fourier optics models
        return settings
    return traced if methods == {"rt"} else settings


def _allow_unconverged(problem: MultiCurveProblem) -> MultiCurveProblem:
    settings = problem.settings.derived(allow_unconverged=True)
    return dataclasses.replace(problem, settings=settings)


def fit_curves(problem: MultiCurveProblem) -> MultiCurveFit:
    """The fit of ``problem`` by its search: global (then local) or local from the start."""
    if problem.settings.search.kind == "global":
        return search_curves(problem)
    return solve_curves(problem)
