"""The Payerne CHM15k set-up shared by bench_drift.py and bench_drift_payerne.py: the days of
quality >= 1 (142 of 153, examples/data/chm15k_payerne_daily_overlap.csv) and the factory curve,
the held-out splits ((a) the warmest 40 %, (b) a random 40 %, DRAWS seeded draws), the baseline
models and the held-out RMS over INTERVAL."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Callable, Dict, List, Tuple

import numpy as np

import lidar_overlap as lo
from lidar_overlap.io.overlap_curves import read_overlap_curve

DATA = Path(__file__).resolve().parent.parent / "examples" / "data"
INTERVAL = (100.0, 1000.0)  # m: the held-out RMS's gates
HELD_OUT = 0.4
DRAWS, SEED = 20, 34
TEMPERATURE = "internal_temperature_K"

#: A model: (training days, the held-out days' temperatures, the factory curve at the training
#: series' ranges) -> (G predicted at the gates of INTERVAL, one row per held-out day; fitted
#: coefficients).
Model = Callable[[lo.OverlapSeries, np.ndarray, np.ndarray], Tuple[np.ndarray, int]]


def read() -> Tuple[lo.OverlapSeries, lo.OverlapSeries, np.ndarray]:
    """(all 153 days, the days of quality >= 1, the factory curve at the days' ranges)."""
    everything = lo.read_overlap_series(DATA / "chm15k_payerne_daily_overlap.csv")
    factory = read_overlap_curve(DATA / "chm15k_payerne_factory_overlap.csv")
    if not np.array_equal(factory.ranges, everything.ranges):
        raise SystemExit("the factory curve's ranges differ from the series'")
    return everything, everything.select(everything.covariates["quality"] >= 1), factory.overlap


def gates(series: lo.OverlapSeries) -> np.ndarray:
    """The scored gates (INTERVAL) of ``series``."""
    return (series.ranges >= INTERVAL[0]) & (series.ranges <= INTERVAL[1])


def splits(series: lo.OverlapSeries) -> List[Tuple[str, np.ndarray]]:
    """[(name, held-out mask)]: the warmest HELD_OUT of the days, then DRAWS random draws (SEED)."""
    t = series.covariates[TEMPERATURE]
    n = len(series)
    count = int(round(HELD_OUT * n))
    warmest = np.zeros(n, dtype=bool)
    warmest[np.argsort(t)[-count:]] = True
    out = [("warmest", warmest)]
    rng = np.random.default_rng(SEED)
    for d in range(DRAWS):
        mask = np.zeros(n, dtype=bool)
        mask[rng.choice(n, count, replace=False)] = True
        out.append((f"random {d}", mask))
    return out


def empirical(train, temperature, factory):
    """Hervo et al. (2016): ln(G / G_factory) linear in temperature per gate."""
    near = gates(train)
    model = lo.empirical_drift(
        train.ranges[near], train.curves[:, near], train.covariates[TEMPERATURE], factory[near]
    )
    return model.predict(model.ranges, temperature), model.coefficients


def training_mean(train, temperature, factory):
    """The training days' mean curve, one coefficient per gate."""
    mean = train.curves[:, gates(train)].mean(axis=0)
    return np.tile(mean, (temperature.size, 1)), int(mean.size)


def factory_curve(train, temperature, factory):
    """The manufacturer's curve, nothing fitted."""
    return np.tile(factory[gates(train)], (temperature.size, 1)), 0


BASELINES: Dict[str, Model] = {
    "empirical (Hervo et al. 2016)": empirical,
    "training mean": training_mean,
    "factory curve": factory_curve,
}


def held_out(series, factory, mask, models: Dict[str, Model]) -> Dict[str, dict]:
    """{model: {rms, coefficients, cpu_s}}: the RMS of prediction - measured over the held-out
    days (``mask``) and the gates of INTERVAL, the model's coefficients and its CPU time (s)."""
    train, test = series.select(~mask), series.select(mask)
    measured = test.curves[:, gates(test)]
    out = {}
    for name, model in models.items():
        c0 = time.process_time()
        predicted, coefficients = model(train, test.covariates[TEMPERATURE], factory)
        cpu = time.process_time() - c0
        rms = float(np.sqrt(np.mean((predicted - measured) ** 2)))
        out[name] = {"rms": rms, "coefficients": coefficients, "cpu_s": cpu}
    return out


def summary(rows: Dict[str, Dict[str, dict]]) -> dict:
    """The per-split rows ({split: {model: row}}) summed up: split (a) as it is, the random draws'
    mean and standard deviation of the RMS (and of the CPU time) per model."""
    random = [r for name, r in rows.items() if name.startswith("random")]
    out = {"warmest": rows["warmest"], "random": {}}
    for model in rows["warmest"]:
        values = np.array([r[model]["rms"] for r in random])
        cpu = np.array([r[model]["cpu_s"] for r in random])
        out["random"][model] = {
            "rms": float(values.mean()),
            "rms_std": float(values.std(ddof=1)) if values.size > 1 else 0.0,
            "coefficients": random[0][model]["coefficients"],
            "cpu_s": float(cpu.mean()),
            "draws": int(values.size),
        }
    return out


def table(result: dict) -> str:
    """The summary as text: model, coefficients, held-out RMS (a), (b) mean ± std, CPU s."""
    lines = [
        f"held-out RMS over {INTERVAL[0]:g}-{INTERVAL[1]:g} m:",
        f"  {'model':40s} {'coeffs':>6s} {'warmest 40 %':>12s} {'random 40 %':>17s} {'CPU s':>7s}",
    ]
    for name, a in result["warmest"].items():
        b = result["random"][name]
        lines.append(
            f"  {name:40s} {a['coefficients']:6d} {a['rms']:12.4f} "
            f"{b['rms']:9.4f} ± {b['rms_std']:.4f} {b['cpu_s']:7.1f}"
        )
    return "\n".join(lines)
