"""The page's plotly figures of a :class:`~lidar_overlap.views.twin.Twin`'s state, as plain dicts
(trame-plotly draws them in the browser): G(z) with the image range marked, the detector-plane
image, the telecover deviations."""

from __future__ import annotations

import math

import numpy as np

from .twin_scene import SECTOR_COLORS

#: Deviation band drawn on the telecover panel (the EARLINET ±5 %).
BAND = 0.05


def _finite_list(values) -> list:
    """A list for the page's JSON, NaN (no signal) as null."""
    return [
        None if not math.isfinite(v) else v
        for v in np.asarray(values, dtype=float).ravel().tolist()
    ]


def curve_figure(twin) -> dict:
    """G(z) of the twin's last curve and its value at the image range."""
    z, zp, g = twin.ranges, float(twin.ranges[twin.probe]), twin.result.overlap
    return {
        "data": [
            {
                "x": z.tolist(),
                "y": g.tolist(),
                "type": "scatter",
                "mode": "lines",
                "name": "G(z)",
            },
            {
                "x": [zp],
                "y": [float(g[twin.probe])],
                "type": "scatter",
                "mode": "markers",
                "name": "image range",
            },
        ],
        "layout": {
            "xaxis": {"type": "log", "title": {"text": "range z (m)"}},
            "yaxis": {"title": {"text": "overlap G(z)"}, "range": [0, 1.05]},
            "margin": {"l": 55, "r": 10, "t": 10, "b": 45},
            "showlegend": False,
            "uirevision": "keep",
        },
    }


def image_figure(im) -> dict:
    """The detector-plane image (a DetectorImage) with the detector's outline, normalised to its
    peak; empty before the first."""
    if im is None:
        return {"data": [], "layout": {}}
    peak = float(im.image.max()) or 1.0
    ox, oy, r = (
        1e3 * im.detector_offset[0],
        1e3 * im.detector_offset[1],
        1e3 * im.detector_radius,
    )
    return {
        "data": [
            {
                "z": (im.image / peak).tolist(),
                "x": (1e3 * im.u).tolist(),
                "y": (1e3 * im.v).tolist(),
                "type": "heatmap",
                "colorscale": "Viridis",
                "showscale": False,
            }
        ],
        "layout": {
            "xaxis": {"title": {"text": "detector plane u (mm)"}},
            "yaxis": {"title": {"text": "v (mm)"}, "scaleanchor": "x"},
            "shapes": [
                {
                    "type": "circle",
                    "x0": ox - r,
                    "x1": ox + r,
                    "y0": oy - r,
                    "y1": oy + r,
                    "line": {"color": "cyan", "width": 2},
                }
            ],
            "title": {
                "text": f"z = {im.range:.4g} m: {100 * im.fraction:.1f} % on the detector",
                "font": {"size": 12},
            },
            "margin": {"l": 55, "r": 10, "t": 30, "b": 45},
        },
    }


def telecover_figure(tc, note: str = "") -> dict:
    """The sectors' deviations G_i / mean G - 1 (a TelecoverResult) with the ±BAND lines; ``note``
    titles the panel (how the sectors were computed)."""
    z = tc.ranges.tolist()
    data = [
        {
            "x": z,
            "y": _finite_list(dev),
            "type": "scatter",
            "mode": "lines",
            "name": name,
            "line": {"color": SECTOR_COLORS[i % len(SECTOR_COLORS)]},
        }
        for i, (name, dev) in enumerate(zip(tc.names, tc.deviation))
    ]
    data += [
        {
            "x": [z[0], z[-1]],
            "y": [b, b],
            "type": "scatter",
            "mode": "lines",
            "showlegend": False,
            "line": {"color": "grey", "dash": "dot"},
        }
        for b in (-BAND, BAND)
    ]
    return {
        "data": data,
        "layout": {
            "xaxis": {"type": "log", "title": {"text": "range z (m)"}},
            "yaxis": {"title": {"text": "G_i / mean G - 1"}, "range": [-1, 1]},
            "margin": {"l": 55, "r": 10, "t": 30 if note else 10, "b": 45},
            "title": {"text": note, "font": {"size": 11}},
            "uirevision": "keep",
        },
    }
