"""How well a day's overlap is predicted from its temperature, on a measured CHM15k (Payerne, 153
daily curves, examples/data/): held-out RMS over 100-1000 m of each model, and the time of one
fixed-family fit per day.

Models (benchmarks/_payerne.py's BASELINES, trained on the training days, each predicts the
held-out days' curves at the gates of INTERVAL from their internal temperature; the physical drift
fit, lo.fit_drift, is bench_drift.py's, on the same splits):
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

import numpy as np
from _common import load_average, run_meta, write_result
from _payerne import (
    BASELINES,
    DRAWS,
    HELD_OUT,
    INTERVAL,
    SEED,
    TEMPERATURE,
    gates,
    held_out,
    read,
    splits,
    summary,
    table,
)

import lidar_overlap as lo

#: The fits' ranges (m) and normalisation interval: every day equals the factory curve beyond ~1 km.
FIT_RANGES, NORMALIZE = (30.0, 1520.0), (1000.0, 1500.0)
#: The days' scatter about a smooth model (0.004 in G, the per-day tilt fits' RMS).
SIGMA, TOLERANCE = 0.004, 4e-4
TARGET_S = 60.0


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
    everything, series, factory = read()
    rows = {name: held_out(series, factory, mask, BASELINES) for name, mask in splits(series)}
    result = summary(rows)
    result["held_out_days"], result["days"] = int(splits(series)[0][1].sum()), len(series)
    print(table(result))
    print(f"({int(np.count_nonzero(gates(series)))} gates)")
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
    write_result("bench_drift_payerne", {"meta": meta, "held_out": result, "series": timing})


if __name__ == "__main__":
    main()
