"""Every number of a representative set of fits, written to JSON and compared with an earlier
snapshot.

A refactoring of the fit layer that keeps the algorithms must keep these numbers to the last bit:
run it before the change (``--write before.json``) and after (``--compare before.json``; without a
file, both use benchmarks/results/fit_snapshot.json); the comparison prints every value that
differs and fails (exit 1) unless all are exactly equal (floats are stored by ``repr``, which reads
back to the same double).

Cases: local fits of absolute data (given sigma, unit weights, a robust loss, a biaxial lidar), a
telecover fit, relative fits (interval, far, interval with the retrieval's extinction bias), global
searches (absolute, relative with the bias) and the model ladder of ``examples/fit_real_overlap.py``
on both real PollyXT curves with the example's settings. Stored per fit: the fitted parameters,
their uncertainties, chi-square, reduced chi-square, evaluation counts, and where present the
extinction bias, the search's minima and the ladder's scores. Takes a few minutes.
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings
from pathlib import Path

import numpy as np
from _common import json_text

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.io.overlap_curves import far_range_noise, read_overlap_curve
from lidar_overlap.model.instruments import pollyxt

DATA = Path(__file__).resolve().parent.parent / "examples" / "data"
RESULT = Path(__file__).resolve().parent / "results" / "fit_snapshot.json"
FAST = dict(method="rt", tolerance=1e-5, threads=1)
SIGMA = 0.01
Z = np.geomspace(30.0, 2000.0, 12)
Z_LONG = np.geomspace(60.0, 3000.0, 40)
TABLE1 = lo.paper_table1()
BIAXIAL = lo.LidarSystem(
    beam=lo.GaussianBeam(
        wavelength=355e-9, waist_radius=1e-3, offset=(0.15, 0.0), tilt=(-1e-4, 0.0)
    ),
    telescope=TABLE1.telescope,
    detector=TABLE1.detector,
)
TRUE = {"beam.tilt[0]": 3e-4, "detector.defocus": 2e-3}
START = {"beam.tilt[0]": 2e-4, "detector.defocus": 1e-3}
TRUE_BIAXIAL = {"beam.tilt[0]": -2.5e-4, "beam.offset[0]": 0.13}
#: Examples' real-curve settings (examples/fit_real_overlap.py).
REAL_BOUNDS = {"detector.numerical_aperture": (0.05, 0.5), "detector.defocus": (-0.01, 0.01)}
REAL_CURVES = [
    (
        "pollynet_default",
        "pollynet_default_overlap.txt",
        355e-9,
        (150, 1200),
        (600, 1200),
        (800, 1190),
    ),
    ("ift_532", "pollyxt_ift_overlap_532.txt", 532e-9, (100, 2500), (600, 2500), (1500, 2480)),
]


def _curve(system, values, z):
    return lo.overlap(parameters.replace(system, values), z, "rt", tolerance=1e-7).overlap


def _noisy(g, seed, sigma=SIGMA):
    return g + np.random.default_rng(seed).normal(0.0, sigma, g.size)


def _fit_numbers(f) -> dict:
    out = {
        "parameters": dict(f.parameters),
        "uncertainties": dict(f.uncertainties),
        "chi_square": f.chi_square,
        "reduced_chi_square": f.reduced_chi_square,
        "evaluations": f.evaluations,
        "jacobian_evaluations": f.jacobian_evaluations,
        "status": f.status,
        "converged": f.converged,
        "residuals": [float(r) for r in f.residuals],
        "covariance": [float(c) for c in np.ravel(f.covariance)],
    }
    for name in ("extinction_bias", "extinction_bias_uncertainty", "model_scale", "data_scale"):
        if getattr(f, name, None) is not None:
            out[name] = float(getattr(f, name))
    search = getattr(f, "search", None)
    if search is not None:
        out["search"] = {
            "generations": search.generations,
            "candidates": search.candidates,
            "core_calls": search.core_calls,
            "local_evaluations": search.local_evaluations,
            "minima": [
                [dict(m.parameters), m.chi_square, m.candidate_cost, m.evaluations]
                for m in search.minima
            ],
        }
    return out


def _ladder_numbers(ladder) -> dict:
    return {
        "chosen_family": ladder.chosen_family.name,
        "note": ladder.note,
        "scores": {
            s.family.name: {"bic": s.bic, "runs_p": s.runs_p, "fit": _fit_numbers(s.fit)}
            for s in ladder.scores
        },
    }


def cases():
    start = parameters.replace(TABLE1, START)
    g = _curve(TABLE1, TRUE, Z)
    y = _noisy(g, 1)
    yield "local sigma", lambda: lo.fit(start, Z, y, sigma=SIGMA, free=list(TRUE), **FAST)
    yield "local unit weights", lambda: lo.fit(start, Z, y, free=list(TRUE), **FAST)
    outliers = y.copy()
    outliers[[3, 8]] += 0.2
    yield (
        "local soft_l1",
        lambda: lo.fit(start, Z, outliers, sigma=SIGMA, free=list(TRUE), loss="soft_l1", **FAST),
    )
    gb = _curve(BIAXIAL, TRUE_BIAXIAL, Z_LONG)
    yb = _noisy(gb, 2)
    yield (
        "local biaxial",
        lambda: lo.fit(BIAXIAL, Z_LONG, yb, sigma=SIGMA, free=list(TRUE_BIAXIAL), **FAST),
    )
    tilted = parameters.replace(TABLE1, {"beam.tilt[1]": 2e-4})
    deviation = lo.telecover(tilted, Z, method="rt", tolerance=1e-7).deviation
    deviation = deviation + np.random.default_rng(3).normal(0.0, 0.005, deviation.shape)
    yield (
        "telecover",
        lambda: lo.fit_telecover(
            TABLE1, Z, deviation, sigma=0.005, free=["beam.tilt"], tolerance=1e-5, threads=1
        ),
    )
    relative = y / np.mean(y[(Z >= 500) & (Z <= 2000)])
    yield (
        "relative interval",
        lambda: lo.fit(
            start, Z, relative, sigma=SIGMA, free=list(TRUE), normalize=(500.0, 2000.0), **FAST
        ),
    )
    yield (
        "relative far",
        lambda: lo.fit(start, Z, y, sigma=SIGMA, free=list(TRUE), normalize="far", **FAST),
    )
    trended = yb * np.exp(-2.0 * 3e-5 * (Z_LONG - 1500.0))
    yield (
        "relative extinction bias",
        lambda: lo.fit(
            BIAXIAL, Z_LONG, trended, sigma=SIGMA, free=list(TRUE_BIAXIAL),
            normalize=(800.0, 3000.0), extinction_bias=True, **FAST,
        ),
    )  # fmt: skip
    far_start = parameters.replace(BIAXIAL, {"beam.tilt[0]": 1.5e-3, "beam.offset[0]": 0.1})
    yield (
        "global absolute",
        lambda: lo.fit(
            far_start, Z_LONG, yb, sigma=SIGMA, free=list(TRUE_BIAXIAL), search="global", seed=4,
            allow_unconverged=True, **FAST,
        ),
    )  # fmt: skip
    yield (
        "global relative bias",
        lambda: lo.fit(
            far_start, Z_LONG, trended, sigma=SIGMA, free=list(TRUE_BIAXIAL), search="global",
            normalize=(800.0, 3000.0), extinction_bias=True, allow_unconverged=True, **FAST,
        ),
    )  # fmt: skip
    for name, file, wavelength, fitted, noise_interval, interval in REAL_CURVES:
        yield f"ladder {name}", _real_ladder(file, wavelength, fitted, noise_interval, interval)


def _real_ladder(file, wavelength, fitted, noise_interval, interval):
    def run():
        curve = read_overlap_curve(DATA / file)
        noise = far_range_noise(curve.ranges, curve.overlap, noise_interval)
        data = curve.within(*fitted)
        start = pollyxt("far", wavelength, numerical_aperture=0.22)
        return lo.fit(
            start, data.ranges, data.overlap, sigma=noise, free="auto", bounds=REAL_BOUNDS,
            method="rt", tolerance=0.05 * noise, normalize=interval, seed=1,
            max_evaluations=300, allow_unconverged=True, extinction_bias=True,
        )  # fmt: skip

    return run


def snapshot() -> dict:
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name, compute in cases():
            f = compute()
            out[name] = _ladder_numbers(f) if hasattr(f, "scores") else _fit_numbers(f)
            print(f"{name:26s} done", flush=True)
    return out


def _differences(before, now, where="") -> list:
    if isinstance(before, dict) and isinstance(now, dict):
        out = []
        for key in sorted(set(before) | set(now)):
            if key not in before or key not in now:
                out.append(f"{where}/{key}: missing on one side")
            else:
                out += _differences(before[key], now[key], f"{where}/{key}")
        return out
    if isinstance(before, list) and isinstance(now, list) and len(before) == len(now):
        return [
            d
            for i, (a, b) in enumerate(zip(before, now))
            for d in _differences(a, b, f"{where}[{i}]")
        ]
    if before != now:
        return [f"{where}: {before!r} -> {now!r}"]
    return []


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--write", nargs="?", const=str(RESULT), help="write the snapshot")
    group.add_argument("--compare", nargs="?", const=str(RESULT), help="compare with a snapshot")
    args = parser.parse_args(argv)
    # The stored form: repr floats, lists for tuples, "NaN" and "(-)Infinity" as strings.
    now = json.loads(json_text(snapshot(), indent=None, named_non_finite=True))
    if args.write:
        with open(args.write, "w") as f:
            f.write(json_text(now, indent=1))
        return 0
    with open(args.compare) as f:
        before = json.load(f)
    differences = _differences(before, now)
    for line in differences:
        print(line)
    print(f"{len(differences)} values differ ({len(before)} cases compared)")
    return 0 if not differences else 1


if __name__ == "__main__":
    sys.exit(main())
