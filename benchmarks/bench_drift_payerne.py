"""How well a day's overlap is predicted from its temperature, on a measured CHM15k (Payerne, 153
daily curves, examples/data/): held-out RMS over 100-1000 m of each model, and the time of one
fixed-family fit per day.

Models (each a function in MODELS: trained on the training days, it predicts the held-out days'
curves at the gates of INTERVAL from their internal temperature; another model is one more function
there, e.g. the physical drift fit, lo.fit_drift):
- empirical: Hervo et al. (2016), ln(G / G_factory) linear in temperature per gate
  (lo.empirical_drift), 2 coefficients per gate;
- training mean: the mean curve of the training days, 1 coefficient per gate;
- factory curve: the manufacturer's curve, nothing fitted.

Splits of the days of quality >= 1 (142 of 153): (a) the warmest 40 % held out (extrapolation in
temperature); (b) a random 40 % held out, 20 seeded draws (the mean and spread of the RMS).

Series timing: one model ladder (free="auto") of the median of all 153 days from the CHM15k preset
(lo.instruments.chm15k), relative data normalised over NORMALIZE (the curves are ~1 there); then
lo.fit_series on the 153 days with that family fixed and the beam tilt along x free, warm-started
in chunks; wall and CPU time (all threads), evaluations, the per-day RMS, and the tilt's slope
against temperature over the days of quality >= 1. Target: the 153 fits <= 60 s on 2 cores.
Writes results/bench_drift_payerne.json.
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path
from typing import Callable, Dict, Tuple

import numpy as np
from _common import load_average, run_meta, write_result

import lidar_overlap as lo
from lidar_overlap.io.overlap_curves import read_overlap_curve

DATA = Path(__file__).resolve().parent.parent / "examples" / "data"
INTERVAL = (100.0, 1000.0)  # m: the held-out RMS's gates
HELD_OUT = 0.4
DRAWS, SEED = 20, 34
TEMPERATURE = "internal_temperature_K"
#: The fits' ranges (m) and normalisation interval: every day equals the factory curve beyond ~1 km.
FIT_RANGES, NORMALIZE = (30.0, 1520.0), (1000.0, 1500.0)
#: The days' scatter about a smooth model (0.004 in G, the per-day tilt fits' RMS).
SIGMA, TOLERANCE = 0.004, 4e-4
TARGET_S = 60.0

#: A model: (training days, the held-out days' temperatures, the factory curve at the training
#: series' ranges) -> (G predicted at the gates of INTERVAL, one row per held-out day; fitted
#: coefficients).
Model = Callable[[lo.OverlapSeries, np.ndarray, np.ndarray], Tuple[np.ndarray, int]]


def _gates(series: lo.OverlapSeries) -> np.ndarray:
    return (series.ranges >= INTERVAL[0]) & (series.ranges <= INTERVAL[1])


def empirical(train, temperature, factory):
    near = _gates(train)
    model = lo.empirical_drift(
        train.ranges[near], train.curves[:, near], train.covariates[TEMPERATURE], factory[near]
    )
    return model.predict(model.ranges, temperature), model.coefficients


def training_mean(train, temperature, factory):
    mean = train.curves[:, _gates(train)].mean(axis=0)
    return np.tile(mean, (temperature.size, 1)), int(mean.size)


def factory_curve(train, temperature, factory):
    return np.tile(factory[_gates(train)], (temperature.size, 1)), 0


MODELS: Dict[str, Model] = {
    "empirical (Hervo et al. 2016)": empirical,
    "training mean": training_mean,
    "factory curve": factory_curve,
}


def held_out_rms(series, factory, held_out) -> Dict[str, Tuple[float, int]]:
    """{model: (RMS of prediction - measured over the held-out days and gates, coefficients)}."""
    train = series.select(~held_out)
    test = series.select(held_out)
    measured = test.curves[:, _gates(test)]
    out = {}
    for name, model in MODELS.items():
        predicted, coefficients = model(train, test.covariates[TEMPERATURE], factory)
        out[name] = (float(np.sqrt(np.mean((predicted - measured) ** 2))), coefficients)
    return out


def splits(series, factory) -> dict:
    t = series.covariates[TEMPERATURE]
    n = len(series)
    count = int(round(HELD_OUT * n))
    warmest = np.zeros(n, dtype=bool)
    warmest[np.argsort(t)[-count:]] = True
    rows = {"warmest": held_out_rms(series, factory, warmest)}
    rng = np.random.default_rng(SEED)
    draws = []
    for _ in range(DRAWS):
        mask = np.zeros(n, dtype=bool)
        mask[rng.choice(n, count, replace=False)] = True
        draws.append(held_out_rms(series, factory, mask))
    out = {
        "warmest": {
            name: {"rms": rms, "coefficients": k} for name, (rms, k) in rows["warmest"].items()
        },
        "random": {},
    }
    for name in MODELS:
        values = np.array([d[name][0] for d in draws])
        out["random"][name] = {
            "rms": float(values.mean()),
            "rms_std": float(values.std(ddof=1)),
            "coefficients": draws[0][name][1],
        }
    out["held_out_days"], out["days"] = count, n
    return out


def series_timing(everything: lo.OverlapSeries) -> dict:
    days = everything.within(*FIT_RANGES)
    settings = dict(method="rt", tolerance=TOLERANCE, normalize=NORMALIZE)
    t0, c0 = time.perf_counter(), time.process_time()
    ladder = lo.fit(
        lo.instruments.chm15k(),
        days.ranges,
        np.median(days.curves, axis=0),
        SIGMA,
        free="auto",
        allow_unconverged=True,
        **settings,
    )
    t_ladder, c_ladder = time.perf_counter() - t0, time.process_time() - c0
    print(ladder)
    t0, c0 = time.perf_counter(), time.process_time()
    ds = lo.fit_series(
        ladder.chosen.system,
        days.ranges,
        days.curves,
        coords={"date": days.dates, **days.covariates},
        sigma=SIGMA,
        free=["beam.tilt[0]"],
        **settings,
    )
    t_series, c_series = time.perf_counter() - t0, time.process_time() - c0
    good = ds.quality.values >= 1
    tilt = ds.value.sel(parameter="beam.tilt[0]").values[good]
    (slope, _), cov = np.polyfit(ds[TEMPERATURE].values[good], tilt, 1, cov=True)
    return {
        "days": int(ds.sizes["date"]),
        "ranges": int(days.ranges.size),
        "ladder": {
            "time_s": t_ladder,
            "cpu_s": c_ladder,
            "chosen": ladder.chosen_family.name,
            "model_evaluations": int(sum(s.fit.evaluations for s in ladder.scores)),
        },
        "series": {
            "time_s": t_series,
            "cpu_s": c_series,
            "model_evaluations": int(ds.evaluations.sum()),
            "converged": int(ds.converged.sum()),
            "rms_median": float(ds.rms.median()),
            "rms_quality_ge_1_median": float(np.median(ds.rms.values[good])),
            "target_s": TARGET_S,
            "target_met": t_series <= TARGET_S,
        },
        "tilt_slope_urad_per_K": float(slope * 1e6),
        "tilt_slope_sigma_urad_per_K": float(np.sqrt(cov[0, 0]) * 1e6),
    }


def main():
    load = load_average()
    print(f"lidar_overlap {lo.__version__} | load average {load:.2f}")
    everything = lo.read_overlap_series(DATA / "chm15k_payerne_daily_overlap.csv")
    factory = read_overlap_curve(DATA / "chm15k_payerne_factory_overlap.csv")
    if not np.array_equal(factory.ranges, everything.ranges):
        raise SystemExit("the factory curve's ranges differ from the series'")
    series = everything.select(everything.covariates["quality"] >= 1)
    held_out = splits(series, factory.overlap)
    gates = int(np.count_nonzero(_gates(series)))
    print(f"held-out RMS over {INTERVAL[0]:g}-{INTERVAL[1]:g} m ({gates} gates):")
    print(f"  {'model':32s} {'coefficients':>12s} {'warmest 40 %':>13s} {'random 40 %':>17s}")
    for name in MODELS:
        a, b = held_out["warmest"][name], held_out["random"][name]
        print(
            f"  {name:32s} {a['coefficients']:12d} {a['rms']:13.4f} "
            f"{b['rms']:9.4f} ± {b['rms_std']:.4f}"
        )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        timing = series_timing(everything)
    s = timing["series"]
    print(
        f"{timing['days']} daily fits (beam tilt x free, {timing['ranges']} ranges): "
        f"{s['time_s']:.1f} s, {s['cpu_s']:.1f} CPU s, {s['model_evaluations']} evaluations, "
        f"{s['converged']} converged, median RMS {s['rms_median']:.4f} (target {TARGET_S:g} s: "
        f"{'met' if s['target_met'] else 'NOT met'}); ladder {timing['ladder']['time_s']:.1f} s; "
        f"tilt {timing['tilt_slope_urad_per_K']:+.2f} ± {timing['tilt_slope_sigma_urad_per_K']:.2f}"
        " µrad/K"
    )
    meta = run_meta(
        load,
        interval_m=INTERVAL,
        held_out_fraction=HELD_OUT,
        draws=DRAWS,
        seed=SEED,
        fit_ranges_m=FIT_RANGES,
        normalize_m=NORMALIZE,
        sigma=SIGMA,
        tolerance=TOLERANCE,
    )
    write_result("bench_drift_payerne", {"meta": meta, "held_out": held_out, "series": timing})


if __name__ == "__main__":
    main()
