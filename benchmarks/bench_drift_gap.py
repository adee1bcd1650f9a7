"""Where the physical drift model loses to the empirical one on the Payerne CHM15k (bench_drift.py's
data, splits and scoring): the gap taken apart, one model change at a time.

Rows of the held-out RMS over 100-1000 m (benchmarks/_payerne.py), on split (a) (the warmest 40 %)
and the first DRAWS_HERE random draws of split (b):
- physical drift, factory reference: bench_drift.py's model (lo.fit_drift, reference = the
  manufacturer's curve), 8-9 coefficients;
- physical drift, training-mean reference: the same call with the training days' mean curve as the
  reference, so that what the days share and the factory curve lacks is in the reference (60 more
  numbers, taken from the training days);
- per-gate linear in G: G = a + b T per gate (120 coefficients): the empirical model without its
  logarithm;
- empirical (Hervo et al. 2016): ln(G / G_factory) = a + b T per gate (120 coefficients).

And the structure the days share: the training days' mean less the factory curve, its part below
the scale of a SMOOTH-gate cubic Savitzky-Golay filter (150-800 m), compared between disjoint random
halves of all days (correlation; HALVES draws) and its RMS against what independent day-to-day
scatter would leave in a mean of that many days. Writes results/bench_drift_gap.json.
"""

from __future__ import annotations

import multiprocessing
import warnings
from concurrent.futures import ProcessPoolExecutor

import numpy as np
from _common import load_average, run_meta, write_result
from _payerne import BASELINES, TEMPERATURE, gates, held_out, read, splits
from bench_drift import NAME, Physical, ladder_start

import lidar_overlap as lo

DRAWS_HERE = 4
SMOOTH, HALVES, BAND = 13, 10, (150.0, 800.0)
EMPIRICAL = "empirical (Hervo et al. 2016)"
MEAN_REFERENCE = "physical drift (training-mean reference)"
LINEAR_G = "per-gate linear in G"


def linear_in_g(train, temperature, factory):
    """G = a + b T per gate, least squares over the training days."""
    near = gates(train)
    t = train.covariates[TEMPERATURE]
    design = np.column_stack([np.ones_like(t), t - t.mean()])
    coefficients, *_ = np.linalg.lstsq(design, train.curves[:, near], rcond=None)
    asked = np.column_stack([np.ones_like(temperature), temperature - t.mean()])
    return asked @ coefficients, int(coefficients.size)


class MeanReferenced:
    """bench_drift's physical model with the training days' mean curve as the reference."""

    def __init__(self, physical):
        self.physical = physical

    def __call__(self, train, temperature, factory):
        g, coefficients = self.physical(train, temperature, train.curves.mean(axis=0))
        return g, coefficients + int(gates(train).sum())


class Guarded:
    """``model``, whose failure (a drift that takes a parameter out of its valid range at a
    held-out temperature, say) scores NaN and keeps its message in ``failures``."""

    def __init__(self, model):
        self.model, self.failures = model, []

    def __call__(self, train, temperature, factory):
        try:
            return self.model(train, temperature, factory)
        except ValueError as error:
            self.failures.append(str(error))
            return np.full((temperature.size, int(gates(train).sum())), np.nan), 0


def one_split(job):
    """The held-out rows of one split for the four models, and the drifting paths each fit chose."""
    start, free, series, factory, mask = job
    physical, mean_referenced = Physical(start, free), Physical(start, free)
    guarded = {NAME: Guarded(physical), MEAN_REFERENCE: Guarded(MeanReferenced(mean_referenced))}
    models = {
        **guarded,
        LINEAR_G: linear_in_g,
        EMPIRICAL: BASELINES[EMPIRICAL],
    }
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # warm days lie beyond the fitted span
        row = held_out(series, factory, mask, models)
    found = {}
    for name, fitted in ((NAME, physical), (MEAN_REFERENCE, mean_referenced)):
        found[name] = {
            "drifting": list(fitted.fits[-1].drifting) if fitted.fits else [],
            "failures": guarded[name].failures,
        }
    return row, found


def high_pass(curve):
    """``curve`` less its cubic Savitzky-Golay smooth over SMOOTH gates."""
    from scipy.signal import savgol_filter

    return curve - savgol_filter(curve, SMOOTH, 3)


def shared_structure(everything, factory) -> dict:
    """The fine structure of the days' mean less the factory curve (module docstring)."""
    z, days = everything.ranges, everything.curves
    band = (z >= BAND[0]) & (z <= BAND[1])
    rng = np.random.default_rng(0)
    correlations = []
    for _ in range(HALVES):
        order = rng.permutation(len(days))
        a, b = (
            high_pass(days[h].mean(axis=0) - factory)[band]
            for h in np.split(order, [len(order) // 2])
        )
        correlations.append(float(np.corrcoef(a, b)[0, 1]))
    by_date = np.split(np.argsort(everything.dates), [len(days) // 2])
    a, b = (high_pass(days[h].mean(axis=0) - factory)[band] for h in by_date)
    mean_structure = high_pass(days.mean(axis=0) - factory)[band]
    per_day = np.array([high_pass(d - factory)[band] for d in days])
    spread = per_day - mean_structure
    return {
        "smooth_gates": SMOOTH, "band_m": BAND, "halves": HALVES,
        "correlation_between_halves": [min(correlations), max(correlations)],
        "correlation_between_halves_by_date": float(np.corrcoef(a, b)[0, 1]),
        "rms": float(np.sqrt(np.mean(mean_structure**2))),
        "rms_if_independent": float(np.sqrt(np.mean(spread**2) / len(days))),
        "factory_own_rms": float(np.sqrt(np.mean(high_pass(factory)[band] ** 2))),
    }  # fmt: skip


def slope_noise(series, factory) -> dict:
    """The empirical model's per-gate slope dG/dT (b of ln(G/G_factory) = a + b T, times the mean G)
    over 100-1000 m: its RMS from all days, and its noise from half the days (the RMS difference of
    two disjoint halves over sqrt 2, mean of HALVES draws), per kelvin."""
    near = gates(series)
    g, t = series.curves[:, near], series.covariates[TEMPERATURE]

    def slope(rows):
        model = lo.empirical_drift(series.ranges[near], g[rows], t[rows], factory[near])
        return model.slope * g[rows].mean(axis=0)

    rng = np.random.default_rng(1)
    noise = []
    for _ in range(HALVES):
        a, b = np.split(rng.permutation(len(g)), [len(g) // 2])
        noise.append(np.sqrt(np.mean((slope(a) - slope(b)) ** 2) / 2))
    whole = slope(np.arange(len(g)))
    return {
        "rms_per_k": float(np.sqrt(np.mean(whole**2))),
        "half_noise_per_k": float(np.mean(noise)),
    }


def main():
    load = load_average()
    everything, series, factory = read()
    start, free, _, _ = ladder_start(series.ranges, factory)
    chosen = splits(series)[: DRAWS_HERE + 1]
    jobs = [(start, free, series, factory, mask) for _, mask in chosen]
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        done = list(pool.map(one_split, jobs))
    rows = {name: row for (name, _), (row, _) in zip(chosen, done)}
    print(f"held-out RMS, 100-1000 m (split (a), then random draws 0-{DRAWS_HERE - 1}):")
    for model in done[0][0]:
        values = " ".join(f"{rows[name][model]['rms']:.5f}" for name in rows)
        print(f"  {model:42s} {rows['warmest'][model]['coefficients']:4d}  {values}")
    structure = shared_structure(everything, factory)
    print(f"shared fine structure: RMS {structure['rms']:.4f} (independent scatter would leave "
          f"{structure['rms_if_independent']:.4f}), correlation between halves "
          f"{structure['correlation_between_halves'][0]:.2f}-"
          f"{structure['correlation_between_halves'][1]:.2f}")  # fmt: skip
    write_result("bench_drift_gap", {
        "meta": run_meta(load, draws=DRAWS_HERE),
        "splits": rows, "drifting": {name: d for (name, _), (_, d) in zip(chosen, done)},
        "shared_structure": structure, "empirical_slope": slope_noise(series, factory),
    })  # fmt: skip


if __name__ == "__main__":
    main()
