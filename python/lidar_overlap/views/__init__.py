"""Pictures: matplotlib figures of results, PyVista 3-D scenes and the interactive digital twin in
the browser (:mod:`.app`); optional dependencies, imported when used.

Files: app.py, headless.py, html_export.py, plotting.py, scene.py, scene_meshes.py, twin.py,
twin_page.py, twin_scene.py.
"""

__all__ = [
    "app",
    "headless",
    "html_export",
    "plotting",
    "scene",
    "scene_meshes",
    "twin",
    "twin_page",
    "twin_scene",
]
