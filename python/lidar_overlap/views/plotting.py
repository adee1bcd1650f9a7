"""matplotlib helpers (optional dependency: ``pip install lidar-overlap[plot]``)."""

from __future__ import annotations

import numpy as np

from .. import _checks
from ..analysis.studies.signals import LidarSignal
from ..analysis.studies.telecover import TelecoverResult
from ..forward.result import OverlapResult
from ..optics.detector_image import detector_image


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as exc:  # pragma: no cover - exercised only without matplotlib
        raise ImportError("plotting needs matplotlib: pip install 'lidar-overlap[plot]'") from exc
    return plt


def _checked_axes(name: str, ax, count: int = 1):
    """``ax`` (one matplotlib Axes, or a sequence of ``count`` of them when count > 1) as given, or
    None; anything else refused naming ``name``."""
    from matplotlib.axes import Axes

    if ax is None:
        return None
    if count == 1:
        if not isinstance(ax, Axes):
            raise _checks.refused(name, ax, "a matplotlib Axes, or None for a new figure")
        return ax
    many = list(ax) if isinstance(ax, (tuple, list, np.ndarray)) else []
    if len(many) != count or not all(isinstance(a, Axes) for a in many):
        raise _checks.refused(name, ax, f"{count} matplotlib Axes, or None for a new figure")
    return ax


def _checked_kind(name: str, value, kind: type, made_by: str) -> None:
    if not isinstance(value, kind):
        raise _checks.refused(name, value, f"the {kind.__name__} of {made_by}")


def plot_overlap(result, ax=None, label=None, mark_ranges=True, **line_kwargs):
    """Draw one overlap curve G(z) on a log range axis; mark the full-overlap (G >= 0.99 max G, only
    where the curve shows its far-range limit) and first-signal (G >= 1e-3) ranges. Returns the
    Axes."""
    plt = _pyplot()
    _checked_kind("result", result, OverlapResult, "lo.overlap")
    if _checked_axes("ax", ax) is None:
        _, ax = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
    (line,) = ax.plot(result.ranges, result.overlap, label=label or result.method, **line_kwargs)
    if mark_ranges:
        z_full = result.full_overlap_range() if result.reaches_far_range() else float("nan")
        for z, style in ((z_full, "--"), (result.first_signal_range(), ":")):
            if np.isfinite(z):
                ax.axvline(z, color=line.get_color(), linestyle=style, linewidth=0.8, alpha=0.7)
    ax.set_xscale("log")
    ax.set_xlabel("range z (m)")
    ax.set_ylabel("overlap G(z)")
    ax.set_ylim(-0.02, 1.05)
    ax.grid(True, which="both", alpha=0.3)
    if label is not None:
        ax.legend()
    return ax


def plot_detector_image(system, z, ax=None, n=192):
    """Draw the geometric detector-plane image at range ``z`` (m) (:func:`detector_image`) with the
    detector disc outlined and the fraction it collects in the title. Returns the Axes."""
    plt = _pyplot()
    img = detector_image(system, z, n)
    if _checked_axes("ax", ax) is None:
        _, ax = plt.subplots(figsize=(4.8, 4.2), constrained_layout=True)
    mm = 1e3
    extent = (img.u[-1] * mm, img.u[0] * mm, img.v[-1] * mm, img.v[0] * mm)
    ax.imshow(img.image[::-1, ::-1], extent=extent, origin="lower", cmap="inferno")
    phi = np.linspace(0, 2 * np.pi, 200)
    ax.plot(
        (img.detector_offset[0] + img.detector_radius * np.cos(phi)) * mm,
        (img.detector_offset[1] + img.detector_radius * np.sin(phi)) * mm,
        color="cyan",
        linewidth=1,
    )
    ax.set_xlabel("detector plane x (mm)")
    ax.set_ylabel("detector plane y (mm)")
    ax.set_title(f"z = {z:g} m: {img.fraction:.3f} of the image on the detector")
    return ax


def plot_signal(sig, ax=None):
    """The dynamic-range view of a :class:`LidarSignal` on log axes: expected photons per bin and
    shot with the overlap and without it (G = 1), the background, the noise level (its standard
    deviation over the shots) and, where positive, the noisy realisation. Returns the Axes."""
    plt = _pyplot()
    _checked_kind("sig", sig, LidarSignal, "lo.signal")
    if _checked_axes("ax", ax) is None:
        _, ax = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
    z = sig.ranges
    if sig.noisy is not None:
        shown = np.where(
            sig.noisy > 0, sig.noisy, np.nan
        )  # a log axis cannot show the negative draws
        ax.plot(
            z,
            shown,
            color="0.6",
            linewidth=0.6,
            label=f"noisy, {sig.shots} shots (background subtracted)",
        )
    ax.plot(
        z,
        sig.range_corrected_full_overlap / z**2,
        "--",
        color="tab:blue",
        label="without overlap (G = 1)",
    )
    ax.plot(z, sig.photons, color="tab:blue", label="with overlap G(z)")
    ax.plot(z, sig.std, color="tab:red", linewidth=1, label="noise standard deviation")
    if sig.background > 0:
        ax.axhline(sig.background, color="tab:green", linestyle=":", label="background")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("range z (m)")
    ax.set_ylabel("photons per bin and shot")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_telecover(result, band=0.05, axes=None):
    """The conventional telecover figure of a :class:`TelecoverResult`: top, the range-corrected
    signal of each sector (∝ its G, the atmosphere being common) and the full aperture's over 4 (the
    mean of four quadrants); bottom, the normalised deviations G_i / mean G - 1 in % with the
    ±``band`` lines. Returns the two Axes."""
    plt = _pyplot()
    _checked_kind("result", result, TelecoverResult, "lo.telecover")
    band = _checks.positive("band", band)
    if _checked_axes("axes", axes, count=2) is None:
        _, axes = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True, constrained_layout=True)
    top, bottom = axes
    n = len(result.names)
    for name, g, dev in zip(result.names, result.overlap, result.deviation):
        (line,) = top.plot(result.ranges, g, label=name)
        bottom.plot(result.ranges, 100.0 * dev, color=line.get_color(), label=name)
    top.plot(
        result.ranges,
        result.full.overlap / n,
        color="black",
        linestyle="--",
        linewidth=0.8,
        label=f"full aperture / {n}",
    )
    top.set_ylabel("range-corrected signal ∝ G (a.u.)")
    top.legend(fontsize="small")
    for sign in (-1.0, 1.0):
        bottom.axhline(100.0 * sign * band, color="grey", linestyle=":", linewidth=1)
    bottom.axhline(0.0, color="black", linewidth=0.6)
    bottom.set_ylabel("normalised deviation (%)")
    bottom.set_xlabel("range z (m)")
    finite = result.deviation[np.isfinite(result.deviation)]
    limit = 110.0 * max(2.0 * band, float(np.max(np.abs(finite))) if finite.size else 0.0)
    bottom.set_ylim(-min(limit, 100.0), min(limit, 100.0))
    for ax in axes:
        ax.set_xscale("log")
        ax.grid(True, which="both", alpha=0.3)
    return axes


_READABLE = {"rad": (1e3, "mrad"), "m": (1e3, "mm")}


def plot_alignment_map(ds, range=None, ax=None, cmap="viridis"):
    """Draw an alignment map (:func:`lidar_overlap.alignment_map`) at each chosen range (m; the
    nearest range of the map, all of them when None): a heat map of G with a colorbar for two axes,
    G against the axis for one. Axes are labelled with their names and units (angles in mrad,
    lengths in mm). Returns the Axes, or an array of Axes (one per range) when several ranges are
    drawn."""
    plt = _pyplot()
    names = _alignment_axes(ds)
    if range is None:
        chosen = ds["range"].values
    else:
        chosen = _checks.real_array("range", np.atleast_1d(range), ndim=1)
        if not np.isfinite(chosen).all():
            raise _checks.refused("range", range, "finite ranges of the map in m")
    _checked_axes("ax", ax)
    if ax is not None and len(names) == 2 and chosen.size != 1:
        raise ValueError(f"range = {range!r}: one Axes given, so choose one range")
    if ax is None:
        count = chosen.size if len(names) == 2 else 1
        _, axes = plt.subplots(
            1, count, figsize=(4.2 * count, 3.6), constrained_layout=True, squeeze=False
        )
        axes = axes[0]
    else:
        axes = np.array([ax])
    scaled = []
    for name in names:
        factor, unit = _READABLE.get(
            ds[name].attrs.get("units", ""), (1.0, ds[name].attrs.get("units", ""))
        )
        scaled.append((ds[name].values * factor, f"{name} ({unit})"))
    for i, z in enumerate(chosen):
        g = ds["overlap"].sel(range=z, method="nearest")
        z_shown = float(g["range"])
        if len(names) == 2:
            a = axes[i]
            mesh = a.pcolormesh(scaled[1][0], scaled[0][0], g.values, shading="nearest", cmap=cmap)
            a.figure.colorbar(mesh, ax=a, label="overlap G")
            a.set_xlabel(scaled[1][1])
            a.set_ylabel(scaled[0][1])
            a.set_title(f"z = {z_shown:g} m")
        else:
            axes[0].plot(scaled[0][0], g.values, label=f"z = {z_shown:g} m")
    if len(names) == 1:
        axes[0].set_xlabel(scaled[0][1])
        axes[0].set_ylabel("overlap G")
        axes[0].legend()
        return axes[0]
    return axes[0] if axes.size == 1 else axes


#: Angles of a series in µrad (a day's tilt moves by µrad), lengths in mm.
_SERIES_UNITS = {"rad": (1e6, "µrad"), "m": (1e3, "mm")}


def plot_series(ds, against=None, axes=None):
    """Draw each fitted parameter of a :func:`lidar_overlap.fit_series` dataset with its 1-sigma
    bars, one panel per parameter, against the series' dimension (``against=None``: the date, say)
    or a numeric coordinate named by ``against`` (e.g. ``"internal_temperature_K"``), the latter
    with the straight line weighted by the uncertainties and its slope in the legend (angles in
    µrad, lengths in mm). Unconverged fits are drawn hollow. Returns the array of Axes."""
    plt = _pyplot()
    try:
        dimension = ds["value"].dims[0]
        paths = [str(p) for p in ds["parameter"].values]
        ds["uncertainty"], ds["converged"], ds["unit"]
    except (KeyError, TypeError, IndexError, AttributeError):
        raise _checks.refused("ds", ds, "the dataset of lo.fit_series") from None
    name = dimension if against is None else against
    if name not in ds.coords or ds[name].dims != (dimension,):
        raise ValueError(
            f"against = {against!r} is invalid: expected None or a coordinate along "
            f"{dimension!r}: {[c for c in ds.coords if ds[c].dims == (dimension,)]}"
        )
    x = ds[name].values
    if axes is None:
        _, axes = plt.subplots(
            len(paths), 1, figsize=(6.4, 2.6 * len(paths)), constrained_layout=True, squeeze=False
        )
        axes = axes[:, 0]
    axes = np.atleast_1d(axes)
    converged = ds["converged"].values.astype(bool)
    for ax, path, unit in zip(axes, paths, ds["unit"].values):
        factor, shown = _SERIES_UNITS.get(str(unit), (1.0, str(unit)))
        y = ds["value"].sel(parameter=path).values * factor
        dy = ds["uncertainty"].sel(parameter=path).values * factor
        for keep, face in ((converged, None), (~converged, "none")):
            if keep.any():
                ax.errorbar(x[keep], y[keep], dy[keep], fmt="o", ms=3, mfc=face, color="C0", lw=0.8)
        if against is not None and converged.sum() > 2 and np.all(dy[converged] > 0):
            slope, intercept = np.polyfit(x[converged], y[converged], 1, w=1 / dy[converged])
            line = np.linspace(x.min(), x.max(), 2)
            ax.plot(
                line,
                slope * line + intercept,
                color="C1",
                label=f"slope {slope:.3g} {shown}/{_unit_of(name)}",
            )
            ax.legend()
        ax.set_ylabel(f"{path} ({shown})")
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(name)
    return axes


def _unit_of(name: str) -> str:
    """The unit a coordinate's name ends with (``internal_temperature_K``: K), else 'unit'."""
    tail = name.rsplit("_", 1)[-1]
    return tail if "_" in name and tail in ("K", "C", "s", "m", "Pa", "hPa") else "unit"


def _alignment_axes(ds) -> list:
    """The axes of an alignment map other than range, ``ds`` refused naming ``ds`` unless it is one
    (a dataset whose ``overlap`` has a ``range`` dimension and one or two others)."""
    expected = (
        "an alignment map (lo.alignment_map: a dataset with overlap over range and 1 or 2 axes)"
    )
    try:
        dims, _ = list(ds["overlap"].dims), ds["range"].values
    except (KeyError, TypeError, IndexError, AttributeError):
        raise _checks.refused("ds", ds, expected) from None
    names = [d for d in dims if d != "range"]
    if "range" not in dims or len(names) not in (1, 2):
        raise _checks.refused("ds", ds, expected)
    return names
