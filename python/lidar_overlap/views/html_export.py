"""A PyVista scene as one standalone HTML file: vtk.js's offline viewer (shipped with trame-vtk)
with the scene's meshes, colours and camera embedded, so it turns and zooms in any browser with no
server and no network. The scene is serialised by trame-vtk's own serialisers, the format its viewer
reads; no server is started. The page shows the meshes, their colours and one colour bar; the axes
grid is left out (vtk.js would label it in the displayed, exaggerated coordinates) and so are 2-D
text and point labels.
"""

from __future__ import annotations

import io
import json
import pathlib
import zipfile

FAVICON = "https://kitware.github.io/vtk-js/icon/favicon-"
MISSING = "save_scene(..., format='html') needs trame-vtk: pip install 'lidar-overlap[app]'"


def _serializers():
    try:
        from trame_vtk.modules.vtk.serializers import (
            SynchronizationContext,
            extract_array_hash,
            initialize_serializers,
            reference_id,
            serialize,
        )
        from trame_vtk.tools.vtksz2html import write_html
    except ImportError as exc:
        raise ImportError(MISSING) from exc
    return (
        SynchronizationContext,
        extract_array_hash,
        initialize_serializers,
        reference_id,
        serialize,
        write_html,
    )


def require() -> None:
    """An ImportError naming the extra when trame-vtk is missing."""
    _serializers()


def _left_out(renderer) -> list:
    """The props vtk.js would show wrongly: axes grids (vtk.js labels them in displayed, exaggerated
    coordinates, not the true ones the plotter gave) and every colour bar but the first (vtk.js
    stacks them all in one place)."""
    props = renderer.GetViewProps()
    props = [props.GetItemAsObject(i) for i in range(props.GetNumberOfItems())]
    bars = [p for p in props if p.IsA("vtkScalarBarActor")]
    return [p for p in props if p.IsA("vtkCubeAxesActor")] + bars[1:]


def scene_archive(plotter) -> bytes:
    """The plotter's render window as a vtk.js offline scene (zip of index.json: the scene and its
    arrays), without the props of :func:`_left_out` (removed while the scene is serialised, then put
    back)."""
    Context, extract_array_hash, initialize, reference_id, serialize, _ = _serializers()
    initialize()
    context = Context()
    window = plotter.render_window
    renderer = window.GetRenderers().GetFirstRenderer()
    camera = renderer.GetActiveCamera()
    left_out = _left_out(renderer)
    for prop in left_out:
        renderer.RemoveViewProp(prop)
    try:
        context.set_ignore_last_dependencies(True)  # a full scene, not a change to an earlier one
        scene = serialize(None, window, "1", context, 1)
        context.set_ignore_last_dependencies(False)
    finally:
        for prop in left_out:
            renderer.AddViewProp(prop)
    scene["extra"] = {
        "vtkRefId": reference_id(window),
        "centerOfRotation": camera.GetFocalPoint(),
        "camera": reference_id(camera),
    }
    hashes = {
        entry["hash"]: dict(**entry, content=context.get_cached_data_array(entry["hash"], False))
        for entry in extract_array_hash(scene)
    }
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        archive.writestr(
            "index.json",
            json.dumps({"hashes": hashes, "scene": scene}),
            compress_type=zipfile.ZIP_DEFLATED,
        )
    return buffer.getvalue()


def write_scene_html(plotter, path: pathlib.Path) -> None:
    """Write the plotter's scene to ``path`` as a standalone HTML page (the caller makes it appear
    atomically)."""
    *_, write_html = _serializers()
    page = io.StringIO()
    write_html(scene_archive(plotter), page)
    # The viewer's script links its favicons on the web; a data: URL keeps the page off the network.
    text = page.getvalue().replace(FAVICON, "data:,")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
