"""``lo.view(system)``: the lidar's digital twin in the browser, served on localhost with trame.

The page holds the 3-D scene (vtk.js: it turns and zooms in the browser, the server sends only moved
coordinates), the sliders of the twin's alignment and receiver (:func:`.twin.sliders_for`), G(z),
the detector-plane image at a chosen range and, with a telecover mask, the sectors' normalised
deviations (plotly). A slider move recomputes all of it on the server and pushes it to the page: at
once for ray tracing (a Gaussian beam, milliseconds), else in a worker thread (the model auto
chooses for a field beam or a mixture, seconds), the scene moved and the last curve kept on the
page, with a progress bar, until the new curve arrives; a newer move stops a computation under way
at its next chunk of ranges and its result is never shown. The save button writes the scenario
(TOML) and the curve (CSV) as they stand. Needs ``pip install 'lidar-overlap[app]'``; trame serves
its own client files, nothing is fetched from the internet.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import itertools
import os
import pathlib
import time

from . import twin_page
from .twin import Twin
from .twin_figures import curve_figure, image_figure, telecover_figure
from .twin_scene import MISSING, TwinScene

_names = itertools.count()


def _trame():
    try:
        from trame.app import get_server
    except ImportError as exc:
        raise ImportError(MISSING) from exc
    return get_server


class App:
    """The served page of one :class:`~lidar_overlap.views.twin.Twin`: ``server`` (trame), ``twin``,
    ``scene`` (:class:`~lidar_overlap.views.twin_scene.TwinScene`), ``out`` (where the save button
    writes)."""

    def __init__(self, twin: Twin, *, exaggeration: float = 100.0, out="."):
        get_server = _trame()
        self.twin, self.out = twin, pathlib.Path(out)
        self.scene = TwinScene(twin, exaggeration)
        self.server = get_server(f"lidar_overlap_view_{next(_names)}", client_type="vue3")
        self.state, self.ctrl = self.server.state, self.server.controller
        self._positions = twin.positions()
        # One worker computes the curves that are not ray traced; ``_generation`` counts the
        # settings asked for, so a computation for an older one stops or is dropped.
        self._worker = concurrent.futures.ThreadPoolExecutor(1, "lidar_overlap_view")
        self._generation = 0
        self.computed = 0  # curves computed in the worker and shown
        state = self.state
        for key in twin.sliders:
            state[key] = self._positions[key]
        state.update(
            dict(
                probe=twin.probe,
                error="",
                saved="",
                timing="",
                scene_version=0,
                computing=False,
                progress=0,
                curve_version=0,
                trame__title=f"{twin.name} · lidar_overlap",  # the browser tab
            )
        )
        self._publish()
        self._show_timing(0.0)
        self.state.change(*twin.sliders, "probe")(self._on_change)
        if twin.result is None:  # the first curve is computed once the server runs
            self.ctrl.on_server_ready.add(lambda **_: self._compute_in_background())

        self.layout = twin_page.build(
            self.server, twin, self._positions, self.scene.plotter.render_window, self.save
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
            if self.twin.background:
                self.twin.move(moved, probe)
            else:
                self.twin.update(moved, probe)
        except ValueError as exc:  # a slider that makes an invalid system goes back; said why
            self.state.error = str(exc)
            self.state.update({k: self._positions[k] for k in moved})
            return
        self._positions.update(moved)
        if self.twin.background:  # the scene moves now, the curve follows from the worker
            self._compute_in_background()
        self._show_update(start)

    def _compute_in_background(self) -> None:
        """Start computing the twin's current setting in the worker; a computation under way for
        an older setting stops at its next chunk of ranges, and what it returns is dropped."""
        self._generation += 1
        generation = self._generation
        with self.state:
            self.state.computing, self.state.progress = True, 0
        loop = asyncio.get_running_loop()

        def progress(fraction: float) -> None:  # in the worker: the page is updated in the loop
            loop.call_soon_threadsafe(self._show_progress, generation, fraction)

        def cancelled() -> bool:
            return generation != self._generation

        async def compute() -> None:
            start = time.perf_counter()
            try:
                outcome = await loop.run_in_executor(
                    self._worker, lambda: self.twin.compute(cancelled, progress)
                )
            except (ValueError, RuntimeError) as exc:  # refused, or not converged: said on the page
                if generation == self._generation:
                    with self.state:
                        self.state.error, self.state.computing = str(exc), False
                return
            if outcome is None or generation != self._generation:
                return  # a newer setting is under way
            self.twin.accept(outcome)
            self.computed += 1
            self._show_update(start)
            with self.state:
                self.state.computing = False
                self.state.curve_version = self.computed

        asyncio.ensure_future(compute())

    def _show_progress(self, generation: int, fraction: float) -> None:
        if generation == self._generation:
            with self.state:
                self.state.progress = round(100 * fraction)

    def _show_update(self, start: float) -> None:
        """The twin's current state to the page: scene, figures and the time since ``start``."""
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
        zp = float(twin.ranges[twin.probe])
        if twin.result is None:  # the first curve is on its way: empty plots until it arrives
            state.text_probe = f"{zp:.4g} m"
            state.curve_figure = state.image_figure = {"data": [], "layout": {}}
            return
        g = twin.result.overlap
        state.text_probe = f"{zp:.4g} m, G = {g[twin.probe]:.4f}"
        state.curve_figure = curve_figure(twin)
        state.image_figure = image_figure(twin.image)
        if twin.deviation is not None:
            note = "estimate: obstruction's shadow centred" if twin.telecover_estimated else ""
            state.telecover_figure = telecover_figure(twin.deviation, note)
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

    def save(self) -> None:
        """Write ``<name>.toml`` and ``<name>.csv`` of the twin as it stands to ``out``; the page
        says where."""
        try:
            toml, csv = self.twin.save(self.out)
        except OSError as exc:
            self.state.saved = f"not saved: {exc.strerror or exc}"
            return
        except ValueError as exc:  # no curve yet
            self.state.saved = f"not saved: {exc}"
            return
        self.state.saved = (
            f"saved {toml} and {csv}"
            if toml is not None
            else f"saved {csv} (a scenario file holds a Gaussian beam only)"
        )

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
            self.close()

    def close(self) -> None:
        """Stop the worker (a computation under way stops at its next chunk) and free the scene."""
        self._generation += 1
        self._worker.shutdown(wait=False, cancel_futures=True)
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
    """The digital twin of ``system`` in the browser (the tab titled ``name``): its 3-D scene,
    sliders for beam tilt and offset (rad, m), detector offset and defocus (m), field of view and,
    for a Gaussian beam, divergence (rad), G(z) at ``ranges`` (m; default 200 log-spaced from 1 m to
    1 km, 40 for a curve that is not ray traced), the detector-plane image at a range chosen with a
    slider and, with ``telecover`` (``"quadrants"`` or an ApertureMask), the sectors' deviations
    G_i / mean G - 1.

    A GaussianBeam is ray traced as the sliders move; any other beam the library computes (a
    FieldBeam, FlatTopBeam, GaussianMixtureBeam) gets the model ``lo.plan(system, ranges, "auto")``
    chooses, computed in the background with a progress bar, the last curve kept on the page until
    the new one arrives (:class:`~lidar_overlap.views.twin.Twin`). ``exaggeration``: factor on x
    and y in the scene (range to scale). ``tolerance``: of ray tracing, and auto's. The save button
    writes ``<name>.toml`` (a scenario for ``lidar-overlap run``; Gaussian beams) and ``<name>.csv``
    (the curve) to ``out``. Served on ``host``:``port``
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
    twin = Twin(system, ranges, telecover=telecover, tolerance=tolerance, name=name, compute=False)
    if not twin.background:  # ray tracing: the first curve at once
        twin.update({})
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
