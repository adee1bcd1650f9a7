"""The prediction of a drift fit with a reference (:mod:`.drift_reference`): at covariate c,

    G(c) = M(θ(c)) / s(θ(c)) + [G_ref / s_ref - M(θ_ref) / s(θ_ref)],

each term normalised as the fit normalised the data (s: the mean over the fit's normalising ranges,
or the far limit, or 1), then divided by its mean over other ``normalizing`` ranges when a caller
(``lo.correct``) asks for another scale. The band: the covariance propagated through both model
terms (the reference's state moves with θ too)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Optional

import numpy as np

from ..batch_curves import curves as batch
from ..sensitivity import jacobian
from .drift_reference import reference_state
from .relative_result import RelativeFitResult

if TYPE_CHECKING:
    from .drift_result import DriftFitResult


def anchored_prediction(
    fit: DriftFitResult, z, c, normalizing, band: bool, reference: Optional[np.ndarray]
):
    """(G at ranges ``z`` per covariate ``c``, and with ``band`` its 1-sigma band) of ``fit``
    (module docstring); ``reference`` the reference at ``z``, None: the fit's interpolated."""
    assert fit.reference is not None and fit.reference_ranges is not None
    first = fit.curves[0]
    own = first.normalizing_ranges if isinstance(first, RelativeFitResult) else np.empty(0)
    asked = own if normalizing is None else np.asarray(normalizing, dtype=float)
    both = np.union1d(np.union1d(z, own), asked)
    theta = np.array(list(fit.parameters.values()))
    state = reference_state(
        first.system, list(fit.free), list(fit.parameters), fit.drifting,
        fit.reference_offsets, fit.covariate, fit.reference,
    )  # fmt: skip
    systems = [fit.system_at(ci) for ci in c] + [state.at(theta)]
    p = first.plan.with_system(systems[0]).at(both)
    g = batch(p, systems)
    at, mine, theirs = (np.searchsorted(both, r) for r in (z, own, asked))
    s = g[:, mine].mean(axis=1) if own.size else np.ones(len(systems))
    model = g / s[:, None]
    # the reference normalised as the data were (its mean over the fit's interval)
    zr, gr = fit.reference_ranges, fit.reference
    interval = isinstance(first, RelativeFitResult) and not isinstance(first.normalize, str)
    scale = gr[np.searchsorted(zr, own)].mean() if interval else 1.0
    inside = (both >= zr[0]) & (both <= zr[-1])
    ref = np.where(inside, np.interp(both, zr, gr) / scale, model[-1])
    if reference is not None:
        ref[at] = reference / scale
        inside[at] = True
    out = model[:-1] + np.where(inside, ref - model[-1], 0.0)
    again = normalizing is not None and not np.array_equal(asked, own)
    n = out[:, theirs].mean(axis=1) if again else np.ones(len(c))
    if not band:
        return out[:, at] / n[:, None]
    # d(model term)/dθ of each system, then of the renormalised difference
    free = list(fit.free)
    step = first.step_tolerance
    d = []
    for i, (system, si) in enumerate(zip(systems, s)):
        j = jacobian(p, system, free, step)
        dj = j / si - (np.outer(g[i], j[mine].mean(axis=0)) / si**2 if own.size else 0.0)
        m = state.matrix(theta) if i == len(c) else fit.matrix(c[i])
        d.append(dj @ m)
    sigma = np.empty((len(c), z.size))
    for i in range(len(c)):
        jd = d[i] - np.where(inside[:, None], d[-1], 0.0)
        if again:
            jd = jd / n[i] - np.outer(out[i], jd[theirs].mean(axis=0)) / n[i] ** 2
        jd = jd[at]
        with np.errstate(invalid="ignore"):
            var = np.einsum("ij,jk,ik->i", jd, fit.covariance, jd)
        sigma[i] = np.sqrt(np.maximum(var, 0.0))
    return out[:, at] / n[:, None], sigma
