"""Receiver aberrations: the point image of an aberrated pupil against poppy, hcipy and LightPipes,
the aberrated overlap curve by its three paths (RT pupil form, RT ray fan, FO), and field-dependent
Seidel coma.

1. Point image: Table 1 telescope (D = 0.15 m, 355 nm) with 0.05, 0.03, 0.05 um RMS of Noll Z6, Z8,
Z11,
   the detector in the image plane (defocus 1 mm, z = z_opt), 512 x 512 samples at lambda d / (2D),
   256 pupil samples across D. Time per PSF (warm, best of N), Strehl ratio (central intensity over
   the ideal one's) against |<exp(2 pi i W / lambda)>|^2 by a polar Gauss rule, and the largest
   difference of the PSFs, each in units of its own ideal peak. Every peer's wavefront is checked
   against closed-form Zernike polynomials on its own pupil samples, in lo's sign (exp(+2 pi i W /
   lambda), +Z2 images at +x).
2. Overlap curve, Table 1 with 0.5 um RMS each of Z6 and Z11, 20 ranges 150-3000 m.
3. Seidel coma W131 (ray fan per scatterer), alone (radial) and with Z6 (a 2-D beam integral over
directions).

The point image's scene, its closed forms and the peers are in _psf_references.py.

Runs in ~45 s on 2 cores at load 1.5, ~2 min at load 4 (most of it the FO and ray-fan curves).
Writes results/bench_aberrations.json.
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np
from _common import best_time, load_average, run_meta, source_commit, write_result
from _psf_references import (
    ACROSS,
    DEFOCUS,
    PEERS,
    PSF_TERMS,
    SPACING,
    WAVELENGTH,
    C,
    D,
    F,
    N,
    R,
    convention_error,
    exact_strehl,
)

import lidar_overlap as lo
from lidar_overlap import with_aberrations

CURVE_TERMS = {6: 0.5e-6, 11: 0.5e-6}
RANGES = np.geomspace(150.0, 3000.0, 20)
REFINED = (0, 3, 6)  # ranges (indices) where the fan's ray count shows: 150, 240, 380 m
REFINED_FAN = (96, 256)  # rings x rays per ring (default 48 x 128)
SEIDEL = dict(w131=0.2e-6, field_radius=0.45e-3)
# lo's cap on the beam integral's directions (from 8, doubled until two trapezoid rules agree)
DIRECTIONS = 64


# ---- the point image by each code: (ideal PSF, aberrated PSF builder, W check) ----


def lo_psf():
    system = lo.paper_table1(defocus=DEFOCUS)
    z = lo.optimal_focus_range(F, DEFOCUS)
    aberrated = with_aberrations(system, lo.Aberrations(zernike=PSF_TERMS))
    psf = lambda s: np.abs(lo.point_image(s, z, n=N, spacing=SPACING).values) ** 2  # noqa: E731
    delta = D / ACROSS
    y, x = np.mgrid[-ACROSS // 2 : ACROSS // 2 + 1, -ACROSS // 2 : ACROSS // 2 + 1] * delta
    w = lo.Aberrations(zernike=PSF_TERMS).wavefront(x / R, y / R)
    return psf(system), lambda: psf(aberrated), convention_error(w, x, y, PSF_TERMS)


REPEATS = {"lo": 10, "poppy": 5, "poppy (hard edge)": 5, "hcipy": 10, "LightPipes": 5}


def point_image_section():
    exact = exact_strehl(PSF_TERMS)
    rows, ref = {}, None
    for name, make in [("lo", lo_psf)] + list(PEERS.items()):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                ideal, aberrated, w_error = make()
                t, psf = best_time(aberrated, REPEATS[name])
        except ImportError as e:
            rows[name] = {"status": f"not installed ({e})"}
            continue
        peak = ideal[C, C]
        row = {
            "ms": 1e3 * t,
            "strehl": float(psf[C, C] / peak),
            "strehl_minus_exact": float(psf[C, C] / peak - exact),
            "wavefront_max_error_m": w_error,
            "ideal_peak_on_axis": bool(np.argmax(ideal) == C * N + C),
        }
        if ref is None:
            ref = (ideal / peak, psf / peak)
        else:
            row["psf_max_diff_vs_lo"] = float(np.max(np.abs(psf / peak - ref[1])))
            row["ideal_psf_max_diff_vs_lo"] = float(np.max(np.abs(ideal / peak - ref[0])))
            row["x_lo_time"] = t / (1e-3 * rows["lo"]["ms"])
        rows[name] = row
    sigma = math.sqrt(sum(c * c for c in PSF_TERMS.values()))
    return {
        "exact_strehl": exact,
        "marechal": math.exp(-((2 * math.pi * sigma / WAVELENGTH) ** 2)),
        "codes": rows,
    }


# ---- 2 and 3: overlap curves ----


def timed(fn):
    """One timed call, for calls of seconds (no plans or caches to warm: FO plans with
    FFTW_ESTIMATE)."""
    t0 = time.perf_counter()
    result = fn()
    return time.perf_counter() - t0, result


def fan_system(system):
    # An NA of 0.99 filters no ray of this lidar but makes lo trace every scatterer's ray fan.
    return dataclasses.replace(
        system, detector=dataclasses.replace(system.detector, numerical_aperture=0.99)
    )


def curve_section():
    ab = lo.Aberrations(zernike=CURVE_TERMS)
    system = with_aberrations(lo.paper_table1(), ab)
    fan = fan_system(system)
    t_rt, rt = best_time(lambda: lo.overlap(system, RANGES, "rt").overlap, 5)
    t_fo, fo = timed(lambda: lo.overlap(system, RANGES, "fo").overlap)
    t_fo5, fo5 = timed(
        lambda: lo._core.overlap_fo_aberrated(
            system._native, ab._native, RANGES, lo._core.FoAberratedOptions(tail_error=1e-5)
        )
    )
    t_fan, fn = timed(lambda: lo.overlap(fan, RANGES, "rt").overlap)
    zr = RANGES[list(REFINED)]
    refined_fan = lo._core.RtAberratedOptions(
        rings=REFINED_FAN[0], ring_rays=REFINED_FAN[1], directions=DIRECTIONS
    )
    t_ref, refined = timed(
        lambda: lo._core.overlap_rt_aberrated(fan._native, ab._native, zr, refined_fan).overlap
    )
    fo5_g = fo5.overlap
    worst = int(np.argmax(np.abs(fo - fo5_g)))  # one more decade there: is tail 1e-5 converged?
    t_fo6, fo6 = timed(
        lambda: lo._core.overlap_fo_aberrated(
            system._native,
            ab._native,
            RANGES[worst : worst + 1],
            lo._core.FoAberratedOptions(max_grid=8192, tail_error=1e-6),
        )
    )
    ideal = lo.overlap(lo.paper_table1(), RANGES, "fo").overlap
    return {
        "ranges_m": RANGES.tolist(),
        "ideal_fo": ideal.tolist(),
        "rt": rt.tolist(),
        "fo": fo.tolist(),
        "fan": fn.tolist(),
        "fo_tail_1e-5": fo5_g.tolist(),
        "fo_grid_tail_1e-5": fo5.grid.tolist(),
        "refined_ranges_m": zr.tolist(),
        "refined_fan": refined.tolist(),
        "fo_worst_range_m": RANGES[worst],
        "fo_worst_tail_1e-4_1e-5_1e-6": [fo[worst], fo5_g[worst], fo6.overlap[0]],
        "fo_worst_grid_tail_1e-6": int(fo6.grid[0]),
        "s": {
            "rt": t_rt,
            "fo": t_fo,
            "fo_tail_1e-5": t_fo5,
            "fan": t_fan,
            "refined_fan": t_ref,
            "fo_tail_1e-6_one_range": t_fo6,
        },
        "rt_minus_fan_max": float(np.max(np.abs(rt - fn))),
        "rt_minus_refined_fan": (rt[list(REFINED)] - refined).tolist(),
        "fan_minus_refined_fan": (fn[list(REFINED)] - refined).tolist(),
        "fo_minus_fo_tail_1e-5_max": float(np.max(np.abs(fo - fo5_g))),
        "rt_minus_fo_max": float(np.max(np.abs(rt - fo))),
        "rt_minus_fo_far": float(rt[-1] - fo[-1]),
        "aberrations_effect_max": float(np.max(np.abs(fo - ideal))),
    }


def seidel_section():
    out = {}
    for label, ab in (
        ("w131", lo.Aberrations(**SEIDEL)),
        ("w131+z6", lo.Aberrations(**SEIDEL, zernike={6: 0.3e-6})),
    ):
        system = with_aberrations(lo.paper_table1(), ab)
        # which beam integral lo chose (radial or over directions), asked at the cheapest range
        raw = lo._core.overlap_rt_aberrated(
            system._native,
            ab._native,
            RANGES[-1:],
            lo._core.RtAberratedOptions(directions=DIRECTIONS),
        )
        curve = lambda system=system: lo.overlap(system, RANGES, "rt").overlap  # noqa: E731
        t, g = best_time(curve, 3) if label == "w131" else timed(curve)  # ~0.5 s against ~18 s
        out[label] = {
            "s": t,
            "s_per_range": t / RANGES.size,
            "radial": raw.rotationally_symmetric,
            "overlap": g.tolist(),
        }
    out["ideal_rt"] = lo.overlap(lo.paper_table1(), RANGES, "rt").overlap.tolist()
    return out


def main():
    load0 = load_average()
    peers = {}
    for mod in ("poppy", "hcipy", "LightPipes", "astropy"):
        try:
            peers[mod] = __import__(mod).__version__
        except ImportError:
            peers[mod] = None
    print(f"lidar_overlap {lo.__version__} | load {load0:.2f} | commit {source_commit()}")
    t0 = time.perf_counter()
    psf = point_image_section()
    print(
        f"\n1. Point image {N}^2, Z6/Z8/Z11 = 0.05/0.03/0.05 um RMS: exact Strehl "
        f"{psf['exact_strehl']:.6f} (Marechal {psf['marechal']:.4f})"
    )
    print(
        f"{'code':18s} {'ms':>7s} {'x lo':>6s} {'Strehl':>9s} {'- exact':>9s} {'PSF diff':>9s} "
        f"{'ideal diff':>10s} {'W err (m)':>9s}"
    )
    for name, r in psf["codes"].items():
        if "ms" not in r:
            print(f"{name:18s} {r['status']}")
            continue
        print(
            f"{name:18s} {r['ms']:7.1f} {r.get('x_lo_time', 1.0):6.2f} {r['strehl']:9.6f} "
            f"{r['strehl_minus_exact']:9.1e} {r.get('psf_max_diff_vs_lo', 0.0):9.1e} "
            f"{r.get('ideal_psf_max_diff_vs_lo', 0.0):10.1e} {r['wavefront_max_error_m']:9.1e}"
        )
    curve = curve_section()
    s = curve["s"]
    print(
        f"\n2. Overlap, Z6 = Z11 = 0.5 um RMS, {RANGES.size} ranges "
        f"{RANGES[0]:.0f}-{RANGES[-1]:.0f} m"
    )
    print(
        f"  rt (pupil form) {s['rt']:.3f} s | fo {s['fo']:.2f} s | fo tail 1e-5 "
        f"{s['fo_tail_1e-5']:.2f} s | ray fan 48x128 {s['fan']:.2f} s | fan "
        f"{REFINED_FAN[0]}x{REFINED_FAN[1]} at {len(REFINED)} ranges {s['refined_fan']:.2f} s"
    )
    print(
        f"  |rt - fan| max {curve['rt_minus_fan_max']:.1e}; rt - fan "
        f"{REFINED_FAN[0]}x{REFINED_FAN[1]} at {np.round(curve['refined_ranges_m'])} m: "
        f"{np.array2string(np.array(curve['rt_minus_refined_fan']), precision=1)}"
    )
    print(
        f"  |fo - fo(tail 1e-5)| max {curve['fo_minus_fo_tail_1e-5_max']:.1e}; |rt - fo| max "
        f"{curve['rt_minus_fo_max']:.1e} (at {RANGES[-1]:.0f} m {curve['rt_minus_fo_far']:.1e}); "
        f"aberrations move G by up to {curve['aberrations_effect_max']:.3f}"
    )
    g = curve["fo_worst_tail_1e-4_1e-5_1e-6"]
    print(
        f"  fo at {curve['fo_worst_range_m']:.0f} m, tail_error 1e-4 / 1e-5 / 1e-6: {g[0]:.8f} / "
        f"{g[1]:.8f} / {g[2]:.8f} (1e-6: {s['fo_tail_1e-6_one_range']:.1f} s, grid "
        f"{curve['fo_worst_grid_tail_1e-6']})"
    )
    seidel = seidel_section()
    print("\n3. Seidel coma W131 = 0.2 um at 0.45 mrad (ray fan per scatterer)")
    for label in ("w131", "w131+z6"):
        r = seidel[label]
        kind = "radial" if r["radial"] else "directions"
        print(f"  {label:8s} {kind:14s} {r['s']:.2f} s, {r['s_per_range']:.3f} s per range")
    run_s, load1 = time.perf_counter() - t0, load_average()
    print(f"\nrun {run_s:.0f} s, load {load0:.2f} -> {load1:.2f}")
    meta = {
        **run_meta(load0),
        "peer_versions": peers,
        "run_s": run_s,
        "wavelength_m": WAVELENGTH,
        "n": N,
        "spacing_m": SPACING,
        "pupil_samples_across": ACROSS,
        "psf_zernike_m_rms": PSF_TERMS,
        "curve_zernike_m_rms": CURVE_TERMS,
        "seidel": SEIDEL,
        "refined_fan": REFINED_FAN,
    }
    write_result(
        "bench_aberrations", {"meta": meta, "point_image": psf, "curve": curve, "seidel": seidel}
    )


if __name__ == "__main__":
    main()
