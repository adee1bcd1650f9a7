"""The prediction of a drift fit (``lo.fit_drift``) at covariate c, with and without a reference
(:mod:`.drift_reference`):

    G(c) = M(θ(c)) / s(θ(c)) + [G_ref / s_ref - M(θ_ref) / s(θ_ref)],

the bracket, the reference's term, zero without a reference. Each term is normalised as the fit
normalised the data (s: the mean over the fit's normalising ranges, or the far limit, or 1), then
divided by its mean over other ``normalizing`` ranges when a caller (``lo.correct``) asks for
another scale; without a reference the model is divided by its mean over ``normalizing`` at once
(None: absolute). The band: the covariance propagated through the model terms (the reference's
state moves with θ too)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..batch_curves import curves as batch
from ..sensitivity import jacobian
from .drift_reference import reference_state
from .relative_result import RelativeFitResult

if TYPE_CHECKING:
    from .drift_result import DriftFitResult


def prediction(fit: DriftFitResult, z, c, normalizing, band: bool, reference=None):
    """(G at ranges ``z`` (m, strictly increasing) per covariate ``c``, and with ``band`` its
    1-sigma band) of ``fit`` (module docstring), divided by its mean over the ``normalizing``
    ranges (m; None: the fit's own scale, absolute without a reference); ``reference`` the
    reference at ``z``, None: the fit's interpolated."""
    first = fit.curves[0]
    anchored = fit.reference is not None
    fitted = first.normalizing_ranges if isinstance(first, RelativeFitResult) else np.empty(0)
    if normalizing is not None:
        asked = np.asarray(normalizing, dtype=float)
    else:  # with a reference, the data's scale: its term is relative
        asked = fitted if anchored else np.empty(0)
    # the model's first scale: the data's with a reference (its term is on that scale), else the
    # asked one, and then no second
    own = fitted if anchored else asked
    both = np.union1d(np.union1d(z, own), asked)
    theta = np.array(list(fit.parameters.values()))
    systems = [fit.system_at(ci) for ci in c]
    if anchored:
        state = reference_state(
            first.system, list(fit.free), list(fit.parameters), fit.drifting,
            fit.reference_offsets, fit.covariate, fit.reference,
        )  # fmt: skip
        systems.append(state.at(theta))
    p = first.plan.with_system(systems[0]).at(both)
    g = batch(p, systems)
    at, mine, theirs = (np.searchsorted(both, r) for r in (z, own, asked))
    s = g[:, mine].mean(axis=1) if own.size else np.ones(len(systems))
    model = g / s[:, None]
    out, inside = model, None
    if anchored:
        ref, inside = _reference_curve(fit, both, at, own, reference)
        out = model[:-1] + np.where(inside, ref - model[-1], 0.0)
    again = normalizing is not None and not np.array_equal(asked, own)
    n = out[:, theirs].mean(axis=1) if again else np.ones(len(c))
    if not band:
        return out[:, at] / n[:, None]
    # d(model term)/d(free paths) of each system, normalised by s
    free, step = list(fit.free), first.step_tolerance
    d = []
    for i, (system, si) in enumerate(zip(systems, s)):
        j = jacobian(p, system, free, step)
        d.append(j / si - (np.outer(g[i], j[mine].mean(axis=0)) / si**2 if own.size else 0.0))
    shift = 0.0 if inside is None else np.where(inside[:, None], d[-1] @ state.matrix(theta), 0.0)
    sigma = np.empty((len(c), z.size))
    for i in range(len(c)):
        jd = d[i] @ fit.matrix(c[i]) - shift  # d(prediction)/dθ: (J M - J_ref M_ref)
        if again:
            jd = jd / n[i] - np.outer(out[i], jd[theirs].mean(axis=0)) / n[i] ** 2
        jd = jd[at]
        with np.errstate(invalid="ignore"):
            var = np.einsum("ij,jk,ik->i", jd, fit.covariance, jd)
        sigma[i] = np.sqrt(np.maximum(var, 0.0))
    return out[:, at] / n[:, None], sigma


def _reference_curve(fit: DriftFitResult, both, at, own, reference):
    """(the reference on ``both`` normalised as the data were, by its mean over the fit's
    interval, where it applies (a mask on ``both``): within the fitted ranges, interpolated
    linearly between them, and at ``z`` (``at``) where ``reference`` is given there)."""
    zr, gr = fit.reference_ranges, fit.reference
    assert zr is not None and gr is not None
    first = fit.curves[0]
    interval = isinstance(first, RelativeFitResult) and not isinstance(first.normalize, str)
    scale = gr[np.searchsorted(zr, own)].mean() if interval else 1.0
    inside = (both >= zr[0]) & (both <= zr[-1])
    ref = np.interp(both, zr, gr) / scale
    if reference is not None:
        ref[at] = reference / scale
        inside[at] = True
    return ref, inside
