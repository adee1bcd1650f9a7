"""Off-screen OpenGL for VTK on a machine without a display.

VTK's Linux wheels try an X window first and print "bad X server connection" when there is no
display, before falling back to EGL or OSMesa. Choosing the headless window up front
(``VTK_DEFAULT_OPENGL_WINDOW``, read when a render window is made) skips that attempt and its
message. Mesa's EGL is preferred (its surfaceless platform needs no device), OSMesa is the fallback;
``scripts/setup_system.sh`` installs one.
"""

from __future__ import annotations

import ctypes.util
import functools
import os
import sys

VARIABLE = "VTK_DEFAULT_OPENGL_WINDOW"


@functools.lru_cache(maxsize=None)
def _headless_window() -> str:
    if ctypes.util.find_library("EGL"):
        return "vtkEGLRenderWindow"
    return "vtkOSOpenGLRenderWindow" if ctypes.util.find_library("OSMesa") else ""


def use_headless_gl() -> str:
    """On Linux without DISPLAY or WAYLAND_DISPLAY, and unless the user has chosen one, make
    VTK's render windows EGL (or OSMesa) ones. Returns the window class in force ("" for VTK's
    default)."""
    chosen = os.environ.get(VARIABLE, "")
    if (
        chosen
        or not sys.platform.startswith("linux")
        or os.environ.get("DISPLAY")
        or os.environ.get("WAYLAND_DISPLAY")
    ):
        return chosen
    window = _headless_window()
    if window:
        os.environ[VARIABLE] = window
    return window
