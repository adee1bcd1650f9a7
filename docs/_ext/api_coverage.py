"""Fails the build (a warning under ``-W``) when a name of ``lidar_overlap.__all__`` has no entry.

An entry is an object of the Python domain named ``lidar_overlap.<name>`` (a page of the API
reference, api.rst, or a ``py:data`` directive there) or, for an exported module, the module under
its own name (``lo.plotting`` is ``lidar_overlap.views.plotting``).
"""

from __future__ import annotations

import types

from sphinx.application import Sphinx
from sphinx.environment import BuildEnvironment
from sphinx.util import logging

import lidar_overlap

logger = logging.getLogger(__name__)


def missing_names(documented: set[str]) -> list[str]:
    """Names of ``lidar_overlap.__all__`` whose ``lidar_overlap.<name>`` is not documented."""
    missing = []
    for name in lidar_overlap.__all__:
        obj = getattr(lidar_overlap, name)
        names = {f"lidar_overlap.{name}"}
        if isinstance(obj, types.ModuleType):
            names.add(obj.__name__)
        if not names & documented:
            missing.append(name)
    return sorted(missing)


def _check(app: Sphinx, env: BuildEnvironment) -> None:
    documented = set(env.get_domain("py").objects) | set(env.get_domain("py").modules)
    missing = missing_names(documented)
    if missing:
        logger.warning(
            "the API reference lacks %d public name(s) of lidar_overlap.__all__: %s (add them to "
            "docs/api.rst)",
            len(missing),
            ", ".join(missing),
        )


def setup(app: Sphinx) -> dict[str, object]:
    app.connect("env-check-consistency", _check)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
