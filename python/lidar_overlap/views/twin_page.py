"""The page of ``lo.view``, laid out with trame's Vuetify widgets: the toolbar (progress of a
curve computed in the background, the server's timing, the save button), the drawer of the twin's
sliders and the image range, and the content: the 3-D scene (vtk.js) beside G(z), the detector-plane
image and, with a telecover mask, the sectors' deviations (plotly). The widgets show the page's
state by name (``text_<slider>``, ``curve_figure``, ``progress``, ...), which
:class:`~lidar_overlap.views.app.App` fills."""

from __future__ import annotations

from typing import Callable, Mapping

from .twin import Twin
from .twin_scene import MISSING


def _widgets():
    try:
        from trame.ui.vuetify3 import SinglePageWithDrawerLayout
        from trame.widgets import html, plotly, vtk
        from trame.widgets import vuetify3 as v3
    except ImportError as exc:
        raise ImportError(MISSING) from exc
    return SinglePageWithDrawerLayout, html, plotly, vtk, v3


def build(
    server, twin: Twin, positions: Mapping[str, int], render_window, save: Callable[[], None]
):
    """The page of ``twin`` on the trame ``server``: the sliders start at ``positions`` (steps),
    the scene shows ``render_window`` (the twin scene's; ``view_update`` on the server's
    controller sends its moved coordinates to vtk.js) and the save button calls ``save``. Returns
    the layout (what a notebook shows, and awaits before showing)."""
    Layout, html, plotly, vtk, v3 = _widgets()
    with Layout(server) as layout:
        layout.title.set_text(f"lidar_overlap: {twin.name}")
        with layout.toolbar:
            v3.VSpacer()
            html.Div(
                "computing G(z) ({{ progress }} %)",
                v_show="computing",
                id="status",
                classes="text-caption mr-2",
            )
            v3.VProgressLinear(
                v_show="computing",
                model_value=("progress",),
                id="progress",
                color="primary",
                height=6,
                style="max-width: 160px",
                classes="mr-4",
            )
            html.Div("{{ timing }}", id="timing", classes="text-caption mr-4")
            html.Div("{{ curve_version }}", id="curve-version", style="display: none")
            html.Div("{{ scene_version }}", id="scene-version", style="display: none")
            v3.VBtn(
                "Save scenario and curve",
                id="save",
                click=save,
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
                        v_model=(key, positions[key]),
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
                        view = vtk.VtkLocalView(render_window, id="scene")
                        server.controller.view_update = view.update
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
    return layout
