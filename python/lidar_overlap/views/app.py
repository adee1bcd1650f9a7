"""``lo.view(system)``: the lidar's digital twin in the browser, served on localhost with trame.

The page holds the 3-D scene (vtk.js: it turns and zooms in the browser, the server sends only moved
coordinates), the sliders of the twin's alignment and receiver (:func:`.twin.sliders_for`), G(z) by
ray tracing, the detector-plane image at a chosen range and, with a telecover mask, the sectors'
normalised deviations (plotly). A slider move recomputes all of it on the server and pushes it to
the page. The save button writes the scenario (TOML) and the curve (CSV) as they stand. Needs ``pip
install 'lidar-overlap[app]'``; trame serves its own client files, nothing is fetched from the
internet.
"""

from __future__ import annotations

import asyncio
import itertools
import math
import os
import pathlib
import time

import numpy as np

from .twin import Twin
from .twin_scene import MISSING, SECTOR_COLORS, TwinScene

#: Deviation band drawn on the telecover panel (the EARLINET ±5 %).
BAND = 0.05
_names = itertools.count()


def _trame():
    try:
        from trame.app import get_server
        from trame.ui.vuetify3 import SinglePageWithDrawerLayout
        from trame.widgets import html, plotly, vtk
        from trame.widgets import vuetify3 as v3
    except ImportError as exc:
        raise ImportError(MISSING) from exc
    return get_server, SinglePageWithDrawerLayout, html, plotly, vtk, v3


def _finite_list(values) -> list:
    """A list for the page's JSON, NaN (no signal) as null."""
    return [
        None if not math.isfinite(v) else v
        for v in np.asarray(values, dtype=float).ravel().tolist()
    ]


class App:
    """The served page of one :class:`~lidar_overlap.views.twin.Twin`: ``server`` (trame), ``twin``,
    ``scene`` (:class:`~lidar_overlap.views.twin_scene.TwinScene`), ``out`` (where the save button
    writes)."""

    def __init__(self, twin: Twin, *, exaggeration: float = 100.0, out="."):
        get_server, Layout, html, plotly, vtk, v3 = _trame()
        self.twin, self.out = twin, pathlib.Path(out)
        self.scene = TwinScene(twin, exaggeration)
        self.server = get_server(f"lidar_overlap_view_{next(_names)}", client_type="vue3")
        self.state, self.ctrl = self.server.state, self.server.controller
        self._positions = twin.positions()
        state = self.state
        for key in twin.sliders:
            state[key] = self._positions[key]
        state.update(dict(probe=twin.probe, error="", saved="", timing="", scene_version=0))
        self._publish()
        self._show_timing(0.0)
        self.state.change(*twin.sliders, "probe")(self._on_change)

        with Layout(self.server) as layout:
            self.layout = layout
            layout.title.set_text(f"lidar_overlap: {twin.name}")
            with layout.toolbar:
                v3.VSpacer()
                html.Div("{{ timing }}", id="timing", classes="text-caption mr-4")
                html.Div("{{ scene_version }}", id="scene-version", style="display: none")
                v3.VBtn(
                    "Save scenario and curve",
                    id="save",
                    click=self.save,
                    variant="tonal",
                    classes="mr-2",
                )
            with layout.drawer as drawer:
                drawer.width = 330
                for key, s in twin.sliders.items():
                    html.Div(
                        f"{s.label}: {{{{ text_{key} }}}}",
                        id=f"label-{key}",
                        classes="text-caption px-4 pt-1",
                    )
                    with html.Div(id=f"slider-{key}"):
                        v3.VSlider(
                            v_model=(key, self._positions[key]),
                            min=0,
                            max=s.n,
                            step=1,
                            hide_details=True,
                            density="compact",
                            classes="px-4",
                        )
                html.Div("detector image at z = {{ text_probe }}", classes="text-caption px-4 pt-3")
                with html.Div(id="slider-probe"):
                    v3.VSlider(
                        v_model=("probe", twin.probe),
                        min=0,
                        max=twin.ranges.size - 1,
                        step=1,
                        hide_details=True,
                        density="compact",
                        classes="px-4",
                    )
                html.Div("{{ saved }}", id="saved", classes="text-caption px-4 pt-3")
            with layout.content:
                with v3.VContainer(fluid=True, classes="pa-0 fill-height"):
                    with v3.VRow(no_gutters=True, classes="fill-height"):
                        with v3.VCol(cols=7, style="min-height: 600px"):
                            view = vtk.VtkLocalView(self.scene.plotter.render_window, id="scene")
                            self.ctrl.view_update = view.update
                        with v3.VCol(cols=5):
                            v3.VAlert(
                                v_if="error",
                                text=("error",),
                                type="warning",
                                density="compact",
                                id="error",
                            )
                            with html.Div(id="curve"):
                                plotly.Figure(
                                    state_variable_name="curve_figure",
                                    display_mode_bar=False,
                                    style="height: 280px",
                                )
                            with html.Div(id="image"):
                                plotly.Figure(
                                    state_variable_name="image_figure",
                                    display_mode_bar=False,
                                    style="height: 300px",
                                )
                            if twin.telecover is not None:
                                with html.Div(id="telecover"):
                                    plotly.Figure(
                                        state_variable_name="telecover_figure",
                                        display_mode_bar=False,
                                        style="height: 260px",
                                    )

    # ------------------------------------------------------------------------------------------
    # updates
    def _on_change(self, **state) -> None:
        moved = {k: int(state[k]) for k in self.twin.sliders if int(state[k]) != self._positions[k]}
        probe = int(state["probe"])
        if not moved and probe == self.twin.probe:
            return
        start = time.perf_counter()
        try:
            self.twin.update(moved, probe)
        except (
            ValueError
        ) as exc:  # a slider that makes an invalid system goes back; the page says why
            self.state.error = str(exc)
            self.state.update({k: self._positions[k] for k in moved})
            return
        self._positions.update(moved)
        t0 = time.perf_counter()
        self.scene.update()
        self.twin.timing["scene"] = time.perf_counter() - t0
        with self.state:  # the figures go out first: they are drawn faster than the scene
            self._publish()
        t1 = time.perf_counter()
        self.ctrl.view_update()  # the moved coordinates to vtk.js
        self.twin.timing["send"] = time.perf_counter() - t1
        self._show_timing(time.perf_counter() - start)

    def _publish(self) -> None:
        """Every figure and text of the twin's current state into the page's state."""
        twin, state = self.twin, self.state
        for key, s in twin.sliders.items():
            state[f"text_{key}"] = s.shown(twin.value(key))
        z = twin.ranges
        zp, g = float(z[twin.probe]), twin.result.overlap
        state.text_probe = f"{zp:.4g} m, G = {g[twin.probe]:.4f}"
        state.curve_figure = {
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
        state.image_figure = self._image_figure()
        if twin.deviation is not None:
            state.telecover_figure = self._telecover_figure()
        state.error = " ".join(f"warning: {w}" for w in twin.warnings)

    def _show_timing(self, elapsed: float) -> None:
        """The server's time for the last update, and its parts, on the page; counts the scene's
        updates."""
        twin, state = self.twin, self.state
        t = twin.timing
        parts = [
            ("G", "overlap"),
            ("image", "image"),
            ("telecover", "telecover"),
            ("scene", "scene"),
            ("scene sent", "send"),
        ]
        state.timing = (
            f"update {1e3 * elapsed:.0f} ms ("
            + ", ".join(
                f"{label} {1e3 * t[key]:.0f}"
                for label, key in parts
                if key in t and (key != "telecover" or twin.deviation is not None)
            )
            + ")"
        )
        state.scene_version = int(state.scene_version or 0) + 1

    def _image_figure(self) -> dict:
        im = self.twin.image
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

    def _telecover_figure(self) -> dict:
        tc, z = self.twin.deviation, self.twin.ranges.tolist()
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
                "margin": {"l": 55, "r": 10, "t": 10, "b": 45},
                "uirevision": "keep",
            },
        }

    def save(self) -> None:
        """Write ``<name>.toml`` and ``<name>.csv`` of the twin as it stands to ``out``; the page
        says where."""
        try:
            toml, csv = self.twin.save(self.out)
        except OSError as exc:
            self.state.saved = f"not saved: {exc.strerror or exc}"
            return
        self.state.saved = f"saved {toml} and {csv}"

    # ------------------------------------------------------------------------------------------
    # serving
    def start(
        self, port: int = 0, host: str = "127.0.0.1", open_browser: bool = True, timeout: float = 0
    ):
        """Serve the page and block until Ctrl-C, or until no browser has been connected for
        ``timeout`` seconds (0: never)."""
        os.environ.setdefault("TRAME_ARGS", "")  # trame must not read the caller's command line
        self.ctrl.on_server_ready.add(
            lambda **_: print(f"lidar-overlap view: http://{host}:{self.server.port}/", flush=True)
        )
        try:
            self.server.start(
                port=port,
                host=host,
                open_browser=open_browser,
                timeout=timeout,
                show_connection_info=False,
                disable_logging=True,
            )
        finally:
            self.scene.close()

    @property
    def ready(self):
        """In a running event loop (Jupyter): start the server as a task; await this before showing
        the page."""
        os.environ.setdefault("TRAME_ARGS", "")
        return self.layout.ready

    def _ipython_display_(self):
        if self.server.running:
            self.layout._ipython_display_()
        else:
            asyncio.ensure_future(self.layout.display_cell())


def _check(name, value, low, high, kind):
    if (
        isinstance(value, bool)
        or not isinstance(value, (int, float))
        or not low <= value <= high
        or (kind is int and not float(value).is_integer())
    ):
        raise ValueError(
            f"{name} = {value!r} is invalid: expected "
            f"{'an integer' if kind is int else 'a number'} from {low} to {high}"
        )
    return kind(value)


def view(
    system,
    ranges=None,
    *,
    telecover=None,
    exaggeration: float = 100.0,
    tolerance: float = 1e-4,
    name: str = "view",
    out=".",
    port: int = 0,
    host: str = "127.0.0.1",
    open_browser: bool = True,
    timeout: float = 0,
    block=None,
) -> App:
    """The digital twin of ``system`` in the browser: its 3-D scene, sliders for beam tilt and
    offset (rad, m), detector offset and defocus (m), field of view and divergence (rad), G(z) by
    ray tracing at ``ranges`` (m; default 200 log-spaced from 1 m to 1 km), the detector-plane image
    at a range chosen with a slider and, with ``telecover`` (``"quadrants"`` or an ApertureMask),
    the sectors' deviations G_i / mean G - 1.

    ``system`` needs a GaussianBeam. ``exaggeration``: factor on x and y in the scene (range to
    scale). ``tolerance``: of ray tracing. The save button writes ``<name>.toml`` (a scenario for
    ``lidar-overlap run``) and ``<name>.csv`` (the curve) to ``out``. Served on ``host``:``port``
    (0: a free port; the URL is printed), in the system browser if ``open_browser``; ``timeout``
    (s): stop once no page has been connected that long (0: run until Ctrl-C).

    ``block``: serve until stopped (the default outside a running event loop), or, in Jupyter (an
    event loop runs), start the server as a task and return at once: ``app = lo.view(system)`` then
    ``await app.ready`` and ``app`` shows the page in the notebook. Returns the :class:`App`. Needs
    ``pip install 'lidar-overlap[app]'``."""
    port = _check("port", port, 0, 65535, int)
    timeout = _check("timeout", timeout, 0, 1e9, float)
    exaggeration = _check("exaggeration", exaggeration, 1e-6, 1e6, float)
    if not isinstance(host, str) or not host:
        raise ValueError(
            f"host = {host!r} is invalid: expected a host name or address, e.g. '127.0.0.1'"
        )
    twin = Twin(system, ranges, telecover=telecover, tolerance=tolerance, name=name)
    app = App(twin, exaggeration=exaggeration, out=out)
    if block is None:
        try:
            asyncio.get_running_loop()
            block = False
        except RuntimeError:
            block = True
    if block:
        app.start(port=port, host=host, open_browser=open_browser, timeout=timeout)
    return app
