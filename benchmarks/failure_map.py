"""Failure map: where RT and the 2-D FO path err by more than 1e-3 against the radial FO reference
on the coaxial Table 1 telescope (range x detector radius in Airy radii), and the 2-D path against
its grid and window. Part of speed_accuracy.py, which runs it and writes failure_map.png;
tests/test_failure_map.py checks its boundary points."""

from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from _speed_common import (
    FO_2D_WINDOW,
    RADIAL_DEFAULT,
    REFERENCE_RADIAL_PERIODS,
    TABLE1,
    airy_radius,  # noqa: E402
    radial,
    with_detector_radius,
)
from matplotlib.colors import Normalize  # noqa: E402

import lidar_overlap as lo  # noqa: E402

FAILURE_TOLERANCE = 1e-3
MAP_RANGES = np.geomspace(5.0, 3000.0, 12)  # m
MAP_AIRY = np.geomspace(1.0, 1000.0, 10)  # detector radius / Airy radius
MAP_RT_RANGES = np.geomspace(5.0, 3000.0, 30)  # RT is cheap: a finer map for its boundary
MAP_RT_AIRY = np.geomspace(1.0, 1000.0, 25)
MAP_2D_GRIDS = (128, 256)
MAP_GRID_SWEEP = (16, 32, 64, 128, 256, 512)  # FO 2-D at window 10
MAP_WINDOW_SWEEP = (3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0)  # FO 2-D at N = 64
MAP_WINDOW_GRID = 64
CUT_RANGE = 1000.0  # m, RT error against detector radius at this range
CUT_AIRY = np.geomspace(1.0, 1000.0, 40)
MAP_TEST_POINTS = (
    (50.0, True),
    (12.0, False),
    (400.0, False),
)  # (Airy radii, RT fails) at CUT_RANGE, as tested


def fo_2d_errors(system, z, g_ref, **kw):
    """|G_2D - G_ref| at each range; NaN where the 2-D path refuses the range (spectrum grid
    cap)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return np.abs(lo.overlap(system, z, method="fo", fo_path="2d", **kw).overlap - g_ref)
        except ValueError:
            out = np.full(z.size, np.nan)
            for i, zi in enumerate(z):
                try:
                    out[i] = abs(
                        lo.overlap(system, [zi], method="fo", fo_path="2d", **kw).overlap[0]
                        - g_ref[i]
                    )
                except ValueError:
                    pass
            return out


def rt_errors(system, z, g_ref):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the validity warnings are the point here
        return np.abs(lo.overlap(system, z, method="rt", tolerance=1e-7).overlap - g_ref)


def boundary(errors, axis_values, tolerance=FAILURE_TOLERANCE):
    """Intervals of axis_values (log-interpolated) where errors exceed the tolerance."""
    bad = errors > tolerance
    spans, start = [], None
    for i, b in enumerate(bad):
        if b and start is None:
            start = i
        if (not b or i == len(bad) - 1) and start is not None:
            end = i if b else i - 1
            lo_edge = (
                axis_values[start]
                if start == 0
                else crossing(axis_values, errors, start - 1, start, tolerance)
            )
            hi_edge = (
                axis_values[end]
                if end == len(bad) - 1
                else crossing(axis_values, errors, end, end + 1, tolerance)
            )
            spans.append([float(lo_edge), float(hi_edge)])
            start = None
    return spans


def crossing(x, e, i, j, tol):
    lx, le = np.log(x[[i, j]]), np.log(np.maximum(e[[i, j]], 1e-300))
    return float(np.exp(lx[0] + (np.log(tol) - le[0]) * (lx[1] - lx[0]) / (le[1] - le[0])))


def failure_map():
    base = TABLE1
    airy = airy_radius(base)
    t0 = time.perf_counter()
    rt_map = np.empty((MAP_RT_AIRY.size, MAP_RT_RANGES.size))
    for i, a in enumerate(MAP_RT_AIRY):
        s = with_detector_radius(base, a * airy)
        rt_map[i] = rt_errors(s, MAP_RT_RANGES, radial(s, MAP_RT_RANGES, REFERENCE_RADIAL_PERIODS))
    t_rt = time.perf_counter() - t0
    fo_maps = {n: np.empty((MAP_AIRY.size, MAP_RANGES.size)) for n in MAP_2D_GRIDS}
    t0 = time.perf_counter()
    for i, a in enumerate(MAP_AIRY):
        s = with_detector_radius(base, a * airy)
        g_ref = radial(s, MAP_RANGES, REFERENCE_RADIAL_PERIODS)
        for n in MAP_2D_GRIDS:
            fo_maps[n][i] = fo_2d_errors(
                s, MAP_RANGES, g_ref, beam_grid=n, beam_window=FO_2D_WINDOW
            )
    t_fo = time.perf_counter() - t0
    g_ref = radial(base, MAP_RANGES, REFERENCE_RADIAL_PERIODS)
    grid_map = np.array(
        [
            fo_2d_errors(base, MAP_RANGES, g_ref, beam_grid=n, beam_window=FO_2D_WINDOW)
            for n in MAP_GRID_SWEEP
        ]
    )
    window_map = np.array(
        [
            fo_2d_errors(base, MAP_RANGES, g_ref, beam_grid=MAP_WINDOW_GRID, beam_window=w)
            for w in MAP_WINDOW_SWEEP
        ]
    )
    cut = np.array(
        [
            rt_errors(
                with_detector_radius(base, a * airy),
                np.array([CUT_RANGE]),
                radial(
                    with_detector_radius(base, a * airy),
                    np.array([CUT_RANGE]),
                    REFERENCE_RADIAL_PERIODS,
                ),
            )[0]
            for a in CUT_AIRY
        ]
    )
    cut_g = np.array(
        [
            radial(with_detector_radius(base, a * airy), np.array([CUT_RANGE]), RADIAL_DEFAULT)[0]
            for a in CUT_AIRY
        ]
    )
    tail = (
        2
        * base.beam.wavelength
        * base.telescope.focal_length
        / (np.pi**2 * base.telescope.diameter * CUT_AIRY * airy)
    )
    table1_airy = base.detector.radius / airy
    return {
        "system": "Table 1 telescope and beam, coaxial, detector radius varied",
        "airy_radius_m": airy,
        "table1_detector_in_airy_radii": table1_airy,
        "tolerance": FAILURE_TOLERANCE,
        "rt": {
            "ranges_m": MAP_RT_RANGES.tolist(),
            "detector_airy_radii": MAP_RT_AIRY.tolist(),
            "error": rt_map.tolist(),
            "seconds": t_rt,
            "failing_airy_radii_at_range": {
                f"{z:.0f}": boundary(rt_map[:, j], MAP_RT_AIRY) for j, z in enumerate(MAP_RT_RANGES)
            },
            "failing_ranges_at_airy_radii": {
                f"{a:.3g}": boundary(rt_map[i], MAP_RT_RANGES) for i, a in enumerate(MAP_RT_AIRY)
            },
        },
        "fo_2d": {
            "ranges_m": MAP_RANGES.tolist(),
            "detector_airy_radii": MAP_AIRY.tolist(),
            "beam_window_w0": FO_2D_WINDOW,
            "seconds": t_fo,
            "error": {str(n): m.tolist() for n, m in fo_maps.items()},
            "max_error": {str(n): float(np.nanmax(m)) for n, m in fo_maps.items()},
            "refused_points": {str(n): int(np.isnan(m).sum()) for n, m in fo_maps.items()},
        },
        "fo_2d_grid_sweep": {
            "beam_window_w0": FO_2D_WINDOW,
            "beam_grid": list(MAP_GRID_SWEEP),
            "ranges_m": MAP_RANGES.tolist(),
            "error": grid_map.tolist(),
            "max_error_per_grid": dict(
                zip(map(str, MAP_GRID_SWEEP), np.nanmax(grid_map, axis=1).tolist())
            ),
        },
        "fo_2d_window_sweep": {
            "beam_grid": MAP_WINDOW_GRID,
            "beam_window_w0": list(MAP_WINDOW_SWEEP),
            "ranges_m": MAP_RANGES.tolist(),
            "error": window_map.tolist(),
            "failing_ranges_per_window": {
                f"{w:g}": boundary(window_map[k], MAP_RANGES)
                for k, w in enumerate(MAP_WINDOW_SWEEP)
            },
        },
        "rt_cut": {
            "range_m": CUT_RANGE,
            "detector_airy_radii": CUT_AIRY.tolist(),
            "error": cut.tolist(),
            "G_fo": cut_g.tolist(),
            "airy_tail_estimate": tail.tolist(),
            "failing_airy_radii": boundary(cut, CUT_AIRY),
        },
    }


def plot_failure_map(fm, path):
    norm = Normalize(-10, -1)
    cmap = plt.get_cmap("viridis")
    fig = plt.figure(figsize=(17, 10.5))
    grid = fig.add_gridspec(2, 4, width_ratios=(1, 1, 1, 0.05), hspace=0.42, wspace=0.3)
    axes = np.array([[fig.add_subplot(grid[r, c]) for c in range(3)] for r in range(2)])
    table1 = fm["table1_detector_in_airy_radii"]

    def panel(ax, x, y, err, title, ylabel, yline=None, yticks=None):
        e = np.log10(np.maximum(np.asarray(err, dtype=float), 1e-16))
        m = ax.pcolormesh(x, y, np.ma.masked_invalid(e), shading="nearest", cmap=cmap, norm=norm)
        if np.nanmax(err) > FAILURE_TOLERANCE:
            ax.contour(
                x,
                y,
                np.nan_to_num(e, nan=-16),
                levels=[np.log10(FAILURE_TOLERANCE)],
                colors="r",
                linewidths=2,
            )
        else:
            ax.text(
                0.5,
                0.5,
                f"max error {np.nanmax(err):.1e}\n< {FAILURE_TOLERANCE:g} everywhere",
                transform=ax.transAxes,
                ha="center",
                va="center",
                color="w",
                fontsize=10,
            )
        if yline:
            ax.axhline(yline, color="w", ls="--", lw=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        if yticks is not None:
            ax.set_yticks(yticks, [f"{v:g}" for v in yticks])
            ax.minorticks_off()
        ax.set_xlabel("range (m)")
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=9)
        return m

    airy_label = "detector radius / Airy radius 1.22 λf/D"
    rt = fm["rt"]
    m = panel(
        axes[0, 0],
        rt["ranges_m"],
        rt["detector_airy_radii"],
        rt["error"],
        f"RT against FO radial; red: |error| = {FAILURE_TOLERANCE:g}\ndashed: Table 1 detector "
        f"({table1:.0f} Airy radii); x, o: tested points",
        airy_label,
        table1,
    )
    for a, inside in MAP_TEST_POINTS:
        axes[0, 0].plot(
            CUT_RANGE,
            a,
            "x" if inside else "o",
            color="r" if inside else "w",
            ms=9,
            mew=2,
            mfc="none",
        )
    for k, n in enumerate(MAP_2D_GRIDS):
        f = fm["fo_2d"]
        panel(
            axes[0, k + 1],
            f["ranges_m"],
            f["detector_airy_radii"],
            f["error"][str(n)],
            f"FO 2-D, beam_grid {n}, window {FO_2D_WINDOW:g} w0,\nagainst FO radial",
            airy_label,
            table1,
        )
    g = fm["fo_2d_grid_sweep"]
    panel(
        axes[1, 0],
        g["ranges_m"],
        g["beam_grid"],
        g["error"],
        f"FO 2-D on Table 1: grid size N at window {FO_2D_WINDOW:g} w0",
        "beam_grid N",
        yticks=g["beam_grid"],
    )
    w = fm["fo_2d_window_sweep"]
    ax = axes[1, 1]
    panel(
        ax,
        w["ranges_m"],
        w["beam_window_w0"],
        w["error"],
        f"FO 2-D on Table 1: window at N = {MAP_WINDOW_GRID}\n(the field is cut at ± window/2 w0)",
        "beam_window (waist radii, full width)",
        yticks=w["beam_window_w0"],
    )
    lam, w0 = TABLE1.beam.wavelength, TABLE1.beam.waist_radius
    top = ax.secondary_xaxis(
        "top",
        functions=(
            lambda z: w0**2 / (lam * np.maximum(z, 1e-9)),
            lambda nf: w0**2 / (lam * np.maximum(nf, 1e-12)),
        ),
    )
    top.set_xlabel("beam Fresnel number w0²/(λz)", fontsize=8)
    c = fm["rt_cut"]
    ax = axes[1, 2]
    ax.loglog(c["detector_airy_radii"], c["error"], "o-", color="C0", ms=4, label="|G_RT − G_FO|")
    ax.loglog(
        c["detector_airy_radii"],
        c["airy_tail_estimate"],
        "--",
        color="C1",
        label="Airy tail 2λf/(π²D r_d)",
    )
    ax.loglog(c["detector_airy_radii"], c["G_fo"], ":", color="0.4", label="G (FO)")
    for a, inside in MAP_TEST_POINTS:
        ax.plot(
            a,
            np.interp(np.log(a), np.log(c["detector_airy_radii"]), c["error"]),
            "x" if inside else "o",
            color="r",
            ms=9,
            mew=2,
            mfc="none",
        )
    ax.axhline(FAILURE_TOLERANCE, color="r", lw=1)
    ax.axvline(table1, color="k", ls="--", lw=0.8)
    ax.set_xlabel(airy_label)
    ax.set_ylabel(f"at {CUT_RANGE:g} m")
    ax.set_ylim(1e-8, 2)
    ax.set_title(f"RT against FO at {CUT_RANGE:g} m; dashed: Table 1 detector", fontsize=9)
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(True, alpha=0.3)
    fig.colorbar(m, cax=fig.add_subplot(grid[:, 3]), label="log10 |G − G_ref| (maps)")
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
