"""The Payerne CHM15k (142 daily overlap curves of quality >= 1 with the internal temperature,
examples/data/chm15k_payerne_*.csv): the physical drift model (lo.fit_drift) against the empirical
temperature model of Hervo et al. (2016, AMT 9, 2947), the training days' mean and the factory
curve, on held-out days; the splits, baselines and scoring are benchmarks/_payerne.py's (those of
bench_drift_payerne.py: the same draws).

Physical model: lo.fit_drift(..., reference=factory curve), the differential anchor (the days are
the factory curve plus what the model changes, G(T) = G_factory + M(θ(T)) - M(θ_ref), with θ_ref
= θ(T_ref) + an offset of REFERENCE_OFFSETS: the factory's bench state on the drift line, moved
along those paths). The family and the start: the model ladder (lo.fit(free="auto")) on the factory
curve (known before any day; its values only start the fit, which refits them all). The drifting
parameters are chosen by BIC (drifting="auto") on each split's training days. A held-out day: the
fit's prediction at its temperature, the factory curve given at every scored gate.
Coefficients: result.coefficients, every fitted number the prediction needs (the family's values,
the slopes, T_ref and the offsets).

Held out: (a) the warmest 40 % (an extrapolation in temperature), (b) a random 40 % (20 draws).
Score: RMS of predicted - measured G over 100-1000 m, all held-out days and gates pooled. The fits
use the gates FIT_RANGES (every second below 1 km), relative data normalised over NORMALIZE
(every day equals the factory curve beyond ~1 km; the prediction is put on the data's scale by
the factory curve's mean there). Writes results/bench_drift.json.
"""

from __future__ import annotations

import multiprocessing
import sys
import time
import warnings
from concurrent.futures import ProcessPoolExecutor

import numpy as np
from _common import load_average, run_meta, write_result
from _payerne import BASELINES, TEMPERATURE, gates, held_out, read, splits, summary, table

import lidar_overlap as lo
from lidar_overlap.model.instruments import chm15k, chm15k_bounds

FIT_RANGES, NORMALIZE = (30.0, 1520.0), (1000.0, 1500.0)
#: The days' scatter about the drift model (G): one fit per day reaches 0.004, but a temperature
#: model leaves ~0.01; weighed by that, BIC takes the drifts that pay for themselves against the
#: day-to-day scatter, not against a day's.
SIGMA, TOLERANCE = 0.01, 4e-4
#: The ladder's member used: the simplest that reaches the factory curve's structure.
FAMILY = "alignment + beam + focus"
#: The paths whose value at the reference has its own offset from the drift line.
REFERENCE_OFFSETS = ["beam.offset[0]"]
#: Splits fitted at once (each fit single-threaded, CPU s per split as measured in its process).
WORKERS = 2
NAME = "physical drift (factory-referenced)"
OPTIONS = dict(method="rt", tolerance=TOLERANCE, normalize=NORMALIZE, bounds=chm15k_bounds(),
               allow_unconverged=True)  # fmt: skip


def fitted_gates(z):
    """The fitted gates: FIT_RANGES, every second below 1 km (where the curve is smooth)."""
    inside = (z >= FIT_RANGES[0]) & (z <= FIT_RANGES[1])
    return inside & ((np.arange(z.size) % 2 == 0) | (z > 1000.0))


def ladder_start(z, factory):
    """(the FAMILY member's fitted system and free paths, the ladder, its CPU s) on the factory
    curve at the fitted gates."""
    keep = fitted_gates(z)
    c0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the ladder's report says how each family fits
        ladder = lo.fit(chm15k(), z[keep], factory[keep], SIGMA, free="auto", seed=1, **OPTIONS)
    cpu = time.process_time() - c0
    best = next(s.fit for s in ladder.scores if s.family.name == FAMILY)
    start = lo.parameters.replace(best.system, dict(best.parameters))
    return start, list(best.parameters), ladder, cpu


class Physical:
    """The physical model of one split (module docstring): ``fits`` keeps its drift fit."""

    def __init__(self, start, free):
        self.start, self.free, self.fits = start, free, []

    def __call__(self, train, temperature, factory):
        keep = fitted_gates(train.ranges)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", lo.DegeneracyWarning)
            warnings.simplefilter("ignore", lo.FitQualityWarning)
            fit = lo.fit_drift(self.start, train.ranges[keep], train.curves[:, keep],
                               train.covariates[TEMPERATURE], sigma=SIGMA, free=self.free,
                               drifting="auto", reference=factory[keep],
                               reference_offsets=REFERENCE_OFFSETS, **OPTIONS)  # fmt: skip
        self.fits.append(fit)
        near = gates(train)
        scale = factory[(train.ranges >= NORMALIZE[0]) & (train.ranges <= NORMALIZE[1])].mean()
        g = fit.predict(train.ranges[near], temperature, reference=factory[near]) * scale
        return g, fit.coefficients


def described(fit) -> dict:
    """What a drift fit found: the drifting paths and slopes, T_ref, the offsets, every value."""
    return {
        "drifting": list(fit.drifting),
        "drift": {p: list(v) for p, v in fit.drift.items()},
        "reference_covariate": list(fit.reference_covariate),
        "coefficients": fit.coefficients,
        "parameters": dict(fit.parameters),
        "uncertainties": dict(fit.uncertainties),
        "at_bounds": list(fit.at_bounds),
        "evaluations": fit.evaluations,
        "jacobians": fit.jacobian_evaluations,
    }


def one_split(job):
    """(the held-out rows of one split, what its drift fit found)."""
    physical, series, factory, mask = job
    row = held_out(series, factory, mask, {NAME: physical, **BASELINES})
    return row, described(physical.fits[-1])


def all_days(physical, everything, factory) -> dict:
    """The drift fit of all 153 days (drifting="auto"): wall and CPU time (the issue's target:
    <= 120 s), what drifts (slopes per kelvin, with their uncertainties)."""
    t0, c0 = time.perf_counter(), time.process_time()
    physical(everything, everything.covariates[TEMPERATURE][:1], factory)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    fit = physical.fits[-1]
    print(f"all {len(everything)} days: {wall:.0f} s wall, {cpu:.0f} CPU s\n{fit}")
    return {"days": len(everything), "time_s": wall, "cpu_s": cpu, **described(fit),
            "choices": list(fit.choices)}  # fmt: skip


def main(draws=None):
    load = load_average()
    print(f"lidar_overlap {lo.__version__} | load average {load:.2f}")
    everything, series, factory = read()
    start, free, ladder, ladder_cpu = ladder_start(series.ranges, factory)
    print(f"ladder on the factory curve: '{FAMILY}' used, '{ladder.chosen_family.name}' chosen "
          f"by BIC ({ladder_cpu:.0f} CPU s)")  # fmt: skip
    physical = Physical(start, free)
    chosen = splits(series)[: None if draws is None else draws + 1]
    # the splits are independent; spawned workers (a fork after OpenMP's threads can hang)
    with ProcessPoolExecutor(WORKERS, mp_context=multiprocessing.get_context("spawn")) as pool:
        done = list(pool.map(one_split, [(physical, series, factory, m) for _, m in chosen]))
    rows = {name: row for (name, _), (row, _) in zip(chosen, done)}
    for name, (row, fit) in zip(rows, done):
        print(f"{name}: drifting {', '.join(fit['drifting']) or 'none'}; "
              + ", ".join(f"{m} {r['rms']:.4f}" for m, r in row.items()))  # fmt: skip
    result = summary(rows)
    print(table(result))
    whole = all_days(physical, everything, factory)
    write_result("bench_drift", {
        "meta": run_meta(load, fit_ranges_m=FIT_RANGES, normalize_m=NORMALIZE, sigma=SIGMA,
                         tolerance=TOLERANCE, reference_offsets=REFERENCE_OFFSETS),
        "ladder": {"family": FAMILY, "bic_choice": ladder.chosen_family.name, "free": free,
                   "start": {p: lo.parameters.get(start, p) for p in free}, "cpu_s": ladder_cpu},
        "held_out": result, "splits": rows,
        "drift_fits": [fit for _, fit in done],
        "all_days": whole,
    })  # fmt: skip


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else None)
