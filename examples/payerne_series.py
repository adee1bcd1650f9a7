"""A year and a half of daily overlap curves of one CHM15k ceilometer (Payerne, examples/data/): how
the curve moves with the instrument's internal temperature.

1. Two temperature models trained on the coolest 60 % of the days of quality >= 1 and asked for
   the warmest 40 % (an extrapolation): the empirical model of Hervo et al. (2016), ln(G /
   G_factory) linear in temperature at each range gate (lo.empirical_drift, two coefficients per
   gate), and the physical drift model, lo.fit_drift with the factory curve as its reference (the
   family chosen by a ladder on the factory curve, the drifting parameters by BIC, the beam's
   offset at the reference its own: 8 coefficients). Their held-out RMS over 100-1000 m beside the
   training days' mean and the factory curve's, what drifts per kelvin, and four held-out days
   drawn with every prediction.
2. One physical parameter per day: a model ladder (free="auto") of the median curve from the
   CHM15k preset chooses the family once; lo.fit_series then fits the beam's tilt along x to each
   day, that family fixed (relative data, normalised over 1000-1500 m), and the tilt is drawn
   against the date and against the temperature.

Writes payerne_empirical_held_out.png and payerne_series_tilt.png; prints the table and the tilt's
slope. SI units (the plots: µrad).
"""

import time
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import lidar_overlap as lo
from lidar_overlap.io.overlap_curves import read_overlap_curve
from lidar_overlap.views.plotting import plot_series

DATA = Path(__file__).resolve().parent / "data"
T = "internal_temperature_K"
INTERVAL = (100.0, 1000.0)
SIGMA, NORMALIZE = 0.004, (1000.0, 1500.0)

days = lo.read_overlap_series(DATA / "chm15k_payerne_daily_overlap.csv")
days = days.select(days.covariates["quality"] >= 1)
factory = read_overlap_curve(DATA / "chm15k_payerne_factory_overlap.csv").overlap

# 1. the empirical model: trained on the coolest 60 %, predicting the warmest 40 %
near = (days.ranges >= INTERVAL[0]) & (days.ranges <= INTERVAL[1])
warm = days.covariates[T] >= np.quantile(days.covariates[T], 0.6)
train, test = days.select(~warm), days.select(warm)
model = lo.empirical_drift(
    days.ranges[near], train.curves[:, near], train.covariates[T], factory[near]
)
measured = test.curves[:, near]
predictions = {
    f"empirical ({model.coefficients} coefficients)": model.predict(
        model.ranges, test.covariates[T]
    ),
    "training mean": np.tile(train.curves[:, near].mean(axis=0), (len(test), 1)),
    "factory curve": np.tile(factory[near], (len(test), 1)),
}

# the physical model: every second gate below 1 km (the curve is smooth there) up to 1520 m
z = days.ranges
fitted_gates = (z >= 30.0) & (z <= 1520.0) & ((np.arange(z.size) % 2 == 0) | (z > 1000.0))
options = dict(method="rt", tolerance=4e-4, normalize=NORMALIZE, allow_unconverged=True)
with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the ladder's and the fit's verdicts: in their summaries
    t0 = time.perf_counter()
    # the family and its start: a ladder on the factory curve (no day enters it)
    family = lo.fit(
        lo.instruments.chm15k(),
        z[fitted_gates],
        factory[fitted_gates],
        0.01,
        free="auto",
        seed=1,
        **options,
    ).chosen
    drift = lo.fit_drift(
        lo.parameters.replace(family.system, dict(family.parameters)),
        z[fitted_gates],
        train.curves[:, fitted_gates],
        train.covariates[T],
        sigma=0.01,  # the days' scatter about a temperature model (one day alone fits to 0.004)
        free=list(family.parameters),
        drifting="auto",
        reference=factory[fitted_gates],
        reference_offsets=["beam.offset[0]"],
        **options,
    )
    seconds = time.perf_counter() - t0
    # the warmest days lie above the training span: the prediction extrapolates (the test's point)
    relative = drift.predict(z[near], test.covariates[T], reference=factory[near])
scale = factory[(z >= NORMALIZE[0]) & (z <= NORMALIZE[1])].mean()  # relative -> the data's G
predictions = {
    f"physical drift ({drift.coefficients} coefficients)": relative * scale,
    **predictions,
}
print(f"physical drift model fitted in {seconds:.0f} s:")
for path, (slope, sd) in drift.drift.items():
    unit = lo.parameters.unit(path)  # m or rad: printed in µm or µrad
    print(f"  {path} drifts by {slope * 1e6:+.3f} ± {sd * 1e6:.3f} µ{unit}/K")
t_ref, t_sd = drift.reference_covariate
print(f"  the factory curve lies on the drift line at {t_ref:.1f} ± {t_sd:.1f} K")
print(f"{len(test)} warmest days held out ({test.covariates[T].min():.1f} K and above):")
for name, predicted in predictions.items():
    rms = np.sqrt(np.mean((predicted - measured) ** 2))
    print(f"  {name:34s} held-out RMS {rms:.4f} (100-1000 m)")

fig, axes = plt.subplots(1, 4, figsize=(13, 3.4), constrained_layout=True, sharey=True)
for ax, i in zip(axes, np.linspace(0, len(test) - 1, 4).astype(int)):
    ax.plot(model.ranges, measured[i], "k.", ms=3, label="measured")
    for (name, predicted), color in zip(predictions.items(), ("C3", "C1", "C0", "C2")):
        ax.plot(model.ranges, predicted[i], color=color, lw=1, label=name)
    ax.set_title(f"{str(test.dates[i])[:10]}, {test.covariates[T][i]:.1f} K")
    ax.set_xlabel("range (m)")
axes[0].set_ylabel("overlap G (relative)")
axes[0].legend(fontsize=7)
fig.savefig("payerne_empirical_held_out.png", dpi=120)

# 2. one free beam tilt per day, the family chosen once on the median curve
fitted = days.within(30.0, 1520.0)
settings = dict(method="rt", tolerance=SIGMA / 10, normalize=NORMALIZE)
with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the ladder's degeneracies are printed in its summary
    t0 = time.perf_counter()
    ladder = lo.fit(
        lo.instruments.chm15k(),
        fitted.ranges,
        np.median(fitted.curves, axis=0),
        SIGMA,
        free="auto",
        allow_unconverged=True,
        **settings,
    )
    t1 = time.perf_counter()
    ds = lo.fit_series(
        ladder.chosen.system,
        fitted.ranges,
        fitted.curves,
        coords={"date": fitted.dates, **fitted.covariates},
        sigma=SIGMA,
        free=["beam.tilt[0]"],
        **settings,
    )
    t2 = time.perf_counter()
print(f"\nmedian curve: {ladder.chosen_family.name!r} chosen in {t1 - t0:.0f} s")
print(
    f"{ds.sizes['date']} daily tilt fits in {t2 - t1:.0f} s: {int(ds.converged.sum())} converged, "
    f"median RMS {float(ds.rms.median()):.4f}"
)
tilt = ds.value.sel(parameter="beam.tilt[0]").values
slope, _ = np.polyfit(ds[T].values, tilt, 1)
print(f"beam tilt against the internal temperature: {slope * 1e6:+.2f} µrad/K")

fig, axes = plt.subplots(2, 1, figsize=(7, 6), constrained_layout=True)
plot_series(ds, axes=axes[:1])
plot_series(ds, against=T, axes=axes[1:])
fig.savefig("payerne_series_tilt.png", dpi=120)
