"""The Payerne CHM15k (TUB120011, 153 daily overlap curves with the internal temperature,
examples/data/chm15k_payerne_*.csv): a physical drift model
(lo.fit_drift) against the empirical temperature model of Hervo et al. (2016, AMT 9, 2947), the
training days' mean and the factory curve, on held-out days.

Physical model: the model ladder (lo.fit(free="auto")) on the factory curve (the manufacturer's,
known before any day: no held-out day enters the start) gives the family and the start; then
lo.fit_drift on the training days, every parameter of that family refitted and shared, those that
drift (linear in temperature about the training mean) chosen by BIC (drifting="auto") on split (a)'s
training days and kept for the other fits. Empirical model (lo.empirical_drift): per range gate,
ln(G_day / G_factory) = a + b T by least squares on the training days (two coefficients per gate of
100 m to 1 km, the scored gates; benchmarks/bench_drift_payerne.py scores it on 20 random draws).

Held out: (a) the warmest 40 % of days (an extrapolation in temperature), (b) a random 40 % (DRAWS
draws). Score: RMS of predicted - measured G over 100-1000 m, all held-out days and gates pooled.
The fits use gates 100-1000 m (every second) and 1-2.9 km (every eighth), normalised over
2000-2890 m like the data (the prediction is put on the data's scale by the factory curve's mean
there, which every day shares). Also timed: the drift fit of all 153 days with the chosen drifts.
Writes results/bench_drift.json.
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path

import numpy as np
from _common import load_average, run_meta, write_result

import lidar_overlap as lo
from lidar_overlap.io.overlap_curves import read_overlap_curve
from lidar_overlap.model.instruments import chm15k

DATA = Path(__file__).resolve().parent.parent / "examples" / "data"
#: The noise the fits weigh the days by: the day-to-day scatter a temperature model leaves (the
#: daily curves are smooth; a single fit reaches ~0.004, the days differ from any one model by
#: ~0.01 near 350 m).
SIGMA = 0.01
LADDER_SIGMA = 0.004
TOLERANCE = 5e-4
NORMALIZE = (2000.0, 2890.0)
SCORED = (100.0, 1000.0)
HELD_OUT, DRAWS = 0.4, 3
OPTIONS = dict(method="rt", tolerance=TOLERANCE, normalize=NORMALIZE, allow_unconverged=True)


def read():
    """Ranges (m), the days' temperatures (K) and curves, the factory curve at the same gates."""
    days = lo.read_overlap_series(DATA / "chm15k_payerne_daily_overlap.csv")
    factory = read_overlap_curve(DATA / "chm15k_payerne_factory_overlap.csv")
    z = days.ranges
    assert np.allclose(factory.ranges[: z.size], z)
    return z, days.covariates["internal_temperature_K"], days.curves, factory.overlap[: z.size]


def fitted_gates(z):
    index = np.arange(z.size)
    return ((z >= 100) & (z <= 1000) & (index % 2 == 0)) | ((z > 1000) & (index % 8 == 0))


def empirical(z, t_train, g_train, factory, t_test):
    """Hervo et al.'s model (lo.empirical_drift) on the scored gates; the others keep the factory's
    G."""
    gates = (z >= SCORED[0]) & (z <= SCORED[1])
    model = lo.empirical_drift(z[gates], g_train[:, gates], t_train, factory[gates])
    out = np.tile(factory, (t_test.size, 1))
    out[:, gates] = model.predict(z[gates], t_test)
    return out, model.coefficients


def rms(prediction, measured, z):
    scored = (z >= SCORED[0]) & (z <= SCORED[1])
    return float(np.sqrt(np.mean((prediction[:, scored] - measured[:, scored]) ** 2)))


def main():
    load_start = load_average()
    z, temperature, g, factory = read()
    keep = fitted_gates(z)
    zf = z[keep]
    scale = factory[(z >= NORMALIZE[0]) & (z <= NORMALIZE[1]) & keep].mean()

    t0, c0 = time.perf_counter(), time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the ladder's report says how each family fits
        ladder = lo.fit(chm15k(), zf, factory[keep], LADDER_SIGMA, free="auto", seed=1,
                        max_evaluations=300, **OPTIONS)  # fmt: skip
    ladder_s, ladder_cpu = time.perf_counter() - t0, time.process_time() - c0
    start = lo.parameters.replace(ladder.chosen.result.system, dict(ladder.chosen.parameters))
    free = list(ladder.chosen.parameters)
    print(f"ladder on the factory curve: '{ladder.chosen_family.name}' ({ladder_s:.0f} s)")

    order = np.argsort(temperature)
    n_out = int(round(HELD_OUT * temperature.size))
    splits = [("warmest 40 %", order[:-n_out], order[-n_out:])]
    rng = np.random.default_rng(0)
    for d in range(DRAWS):
        shuffled = rng.permutation(temperature.size)
        splits.append((f"random 40 % (draw {d})", shuffled[n_out:], shuffled[:n_out]))

    drifting = "auto"
    rows, record_splits = [], []
    for name, train, test in splits:
        t0, c0 = time.perf_counter(), time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", lo.DegeneracyWarning)
            warnings.simplefilter("ignore", lo.FitQualityWarning)
            fit = lo.fit_drift(start, zf, g[train][:, keep], temperature[train], sigma=SIGMA,
                               free=free, drifting=drifting, **OPTIONS)  # fmt: skip
        seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
        if drifting == "auto":
            drifting = list(fit.drifting)
            print(fit)
        physical = fit.predict(z, temperature[test]) * scale
        empirical_g, n_empirical = empirical(z, temperature[train], g[train], factory,
                                             temperature[test])  # fmt: skip
        figures = {
            "physical": rms(physical, g[test], z),
            "empirical": rms(empirical_g, g[test], z),
            "training mean": rms(np.tile(g[train].mean(axis=0), (test.size, 1)), g[test], z),
            "factory": rms(np.tile(factory, (test.size, 1)), g[test], z),
        }
        record_splits.append({
            "split": name, "rms": figures, "seconds": seconds, "cpu_seconds": cpu,
            "evaluations": fit.evaluations, "jacobians": fit.jacobian_evaluations,
            "drift": {p: list(v) for p, v in fit.drift.items()},
            "coefficients": {"physical": len(fit.parameters), "empirical": n_empirical},
        })  # fmt: skip
        rows.append((name, figures, len(fit.parameters), n_empirical, seconds))
        print(f"{name}: " + ", ".join(f"{k} {v:.4f}" for k, v in figures.items())
              + f"  ({seconds:.0f} s)")  # fmt: skip

    t0, c0 = time.perf_counter(), time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.DegeneracyWarning)
        warnings.simplefilter("ignore", lo.FitQualityWarning)
        whole = lo.fit_drift(start, zf, g[:, keep], temperature, sigma=SIGMA, free=free,
                             drifting=drifting, **OPTIONS)  # fmt: skip
    whole_s, whole_cpu = time.perf_counter() - t0, time.process_time() - c0
    print(f"\nall 153 days ({whole_s:.0f} s wall, {whole_cpu:.0f} s CPU, {whole.evaluations} "
          f"evaluations, {whole.jacobian_evaluations} Jacobians):\n{whole}")  # fmt: skip

    print("\n| split | method | coefficients | held-out RMS (100-1000 m) |")
    print("|---|---|---|---|")
    for name, figures, k, n_empirical, _ in rows:
        counts = {"physical": k, "empirical": n_empirical, "training mean": 67, "factory": 0}
        for method, value in figures.items():
            print(f"| {name} | {method} | {counts[method]} | {value:.4f} |")

    write_result("bench_drift", {
        **run_meta(load_start),
        "ladder": {"family": ladder.chosen_family.name, "seconds": ladder_s,
                   "cpu_seconds": ladder_cpu},
        "free": free, "drifting": drifting, "splits": record_splits,
        "all_days": {"seconds": whole_s, "cpu_seconds": whole_cpu,
                     "evaluations": whole.evaluations, "jacobians": whole.jacobian_evaluations,
                     "drift": {p: list(v) for p, v in whole.drift.items()},
                     "parameters": dict(whole.parameters)},
    })  # fmt: skip


if __name__ == "__main__":
    main()
