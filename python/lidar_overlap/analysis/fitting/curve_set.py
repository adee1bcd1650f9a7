"""The curves of a multi-curve fit evaluated together
(:mod:`lidar_overlap.analysis.fitting.multi_curve`, the driver): each curve's plan, normalisation
and step tolerance; at a θ, the curves (one batched core call per group of curves that share a
start system and ranges), their whitened residuals stacked, and their Jacobians in θ (one batched
call for all the shifted systems of a group), a drift fit's reference term included
(:mod:`lidar_overlap.analysis.fitting.drift_reference`)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, List, Optional, Tuple

import numpy as np

from ..batch_curves import curves as batch
from ..sensitivity import difference_systems
from .global_search import thinned
from .normalization import extended_plan, normalization
from .result import step_tolerance
from .solve import fit_plan

if TYPE_CHECKING:
    from .multi_curve import MultiCurveProblem


class CurveSet:
    """Each curve's plan, normalisation and step tolerance, and the batched evaluation of all curves
    (and their Jacobians) at a θ."""

    def __init__(self, problem: MultiCurveProblem, thin: bool = False) -> None:
        settings = problem.settings
        self.maps = problem.maps
        self.plans, self.norms, self.steps, self.base = [], [], [], []
        for m, curve in zip(self.maps, settings.curves):
            p0 = fit_plan(settings, m.system, curve.ranges)
            if thin:
                norm, p = thinned(p0, curve)
            else:
                norm = normalization(
                    curve.normalize, p0.ranges, curve.measured, curve.sigma, curve.extinction_bias
                )
                p = extended_plan(p0, norm)
            self.plans.append(p)
            self.base.append(p0)
            self.norms.append(norm)
            self.steps.append(step_tolerance(p0, settings.tolerance))
        groups: Dict[Tuple[int, bytes], List[int]] = {}
        for i, (m, p) in enumerate(zip(self.maps, self.plans)):
            groups.setdefault((id(m.system), p.ranges.tobytes()), []).append(i)
        self.groups = list(groups.values())
        self.last: list = [None, None]
        self.rows = sum(n.whitening.shape[0] for n in self.norms)
        self.reference = problem.reference
        if self.reference is not None:  # normalised as the days (they share ranges and interval)
            first = settings.curves[0]
            self.reference_norm = normalization(
                first.normalize, self.base[0].ranges, self.reference.curve, first.sigma, False
            )

    def curves(self, systems, shifted=None):
        """G of each curve's system (and, with ``shifted``, of each curve's shifted systems): one
        batched call per group. Returns (G per curve, G of the shifted systems per curve)."""
        g: List[Any] = [None] * len(systems)
        out: List[Any] = [None] * len(systems)
        for group in self.groups:
            runs, counts = [], []
            for i in group:
                extra = [] if shifted is None else shifted[i]
                runs.extend([systems[i], *extra])
                counts.append(1 + len(extra))
            rows = batch(self.plans[group[0]], runs)
            at = 0
            for i, count in zip(group, counts):
                g[i], out[i] = rows[at], rows[at + 1 : at + count]
                at += count
        return g, out

    def at(self, theta):
        """(systems, G per curve) at θ, the last kept (the Jacobian is asked where the model was
        just evaluated)."""
        key = np.asarray(theta, dtype=float).tobytes()
        if self.last[0] != key:
            systems = [m.at(theta) for m in self.maps]
            g = self.curves(systems)[0]
            if self.reference is not None:
                systems.append(self.reference.at(theta))
                g.append(batch(self.plans[0], systems[-1:])[0])
            self.last = [key, (systems, g)]
        return self.last[1]

    def reference_term(self, theta) -> Any:
        """M(θ_ref) normalised less the normalised reference (0.0 without a reference): what each
        curve's model minus its data subtracts (:mod:`.drift_reference`)."""
        if self.reference is None:
            return 0.0
        g = self.at(theta)[1][-1]
        return self.reference_norm.model(g) - self.reference_norm.data

    def _reference_jacobian(self, theta, system, g) -> np.ndarray:
        """d reference_term / dθ (measured ranges, K). The reference's dM/dp is the difference
        quotient of :func:`..sensitivity.jacobian` (its steps, its quotient: the same bits),
        written out because that one runs the shifted systems with ray tracing's validity warnings
        on: it would repeat them for every shifted system at every optimiser step, which the
        batch (``warn=False``) holds back, as for the curves' own Jacobians."""
        assert self.reference is not None
        runs, w = difference_systems(system, list(self.reference.paths), self.steps[0])
        pairs = batch(self.plans[0], runs).reshape(len(runs) // 2, 2, -1)
        local = ((pairs[:, 0] - pairs[:, 1]) / w[:, None]).T
        return self.reference_norm.model_jacobian(g, local) @ self.reference.matrix(theta)

    def residuals(self, theta) -> np.ndarray:
        """The whitened residuals of all curves, stacked; NaN where θ makes some curve's system
        invalid (a drifting divergence below zero at one end of the covariate): the optimiser
        then shortens its step, as it does for any non-finite residual."""
        try:
            _, g = self.at(theta)
        except ValueError:
            if self.last[0] is None:  # the start itself: the caller's error
                raise
            return np.full(self.rows, np.nan)
        with np.errstate(invalid="ignore"):  # a model that vanishes where it is normalised
            shift = self.reference_term(theta)
            return np.concatenate(
                [n.whitening @ (n.model(gi) - n.data - shift) for n, gi in zip(self.norms, g)]
            )

    def jacobian(self, theta, keep: Optional[list] = None) -> np.ndarray:
        """d(whitened residuals)/dθ (rows, K); ``keep`` receives each curve's own Jacobian
        (model ranges, its paths)."""
        systems, g = self.at(theta)
        shift: Any = 0.0
        if self.reference is not None:
            shift = self._reference_jacobian(theta, systems[-1], g[-1])
        shifted, widths = [], []
        for m, s, h in zip(self.maps, systems, self.steps):
            runs, w = difference_systems(s, list(m.paths), h)
            shifted.append(runs)
            widths.append(w)
        _, rows = self.curves(systems, shifted)
        blocks = []
        for i, (m, n) in enumerate(zip(self.maps, self.norms)):
            pairs = rows[i].reshape(len(m.paths), 2, -1)
            local = ((pairs[:, 0] - pairs[:, 1]) / widths[i][:, None]).T
            if keep is not None:
                keep.append(local)
            jacobian_i = n.model_jacobian(g[i], local)
            if self.reference is None:  # (W J) M, the order of every fit without a reference
                blocks.append(n.whitening @ jacobian_i @ m.matrix)
            else:  # W (J M - s): equal to (W J) M - W s, not to the last bit (benchmarks/README)
                blocks.append(n.whitening @ (jacobian_i @ m.matrix - shift))
        return np.vstack(blocks)

    def independent(self) -> List[int]:
        """Each curve's independent points (its whitened rows, less one for a profiled δα)."""
        return [n.whitening.shape[0] - (n.trend is not None) for n in self.norms]
