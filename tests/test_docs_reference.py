"""The API reference (docs/api.rst) lists every public name of ``lidar_overlap.__all__``, and
nothing else.

The documentation build checks the same on the built site (docs/_ext/api_coverage.py); this reads
the page itself, so a name added to ``__all__`` without its entry fails here without Sphinx.
"""

import re
import sys
import types
from pathlib import Path

import pytest

import lidar_overlap

API_PAGE = Path(__file__).resolve().parents[1] / "docs" / "api.rst"


def listed_names() -> list[str]:
    """Entries of the page's autosummary tables and its ``py:data`` directives, as written."""
    names: list[str] = []
    in_table = False
    for line in API_PAGE.read_text(encoding="utf-8").splitlines():
        if line.startswith(".. autosummary::"):
            in_table = True
        elif in_table and line.startswith("   ") and not line.strip().startswith(":"):
            names.append(line.strip().lstrip("~"))
        elif in_table and line.strip() and not line.startswith("   "):
            in_table = False
        match = re.match(r"\.\. py:data:: (\S+)", line)
        if match:
            names.append(match.group(1))
    return names


def exported_as(entry: str) -> str:
    """The name of ``lidar_overlap.__all__`` that an entry documents (modules by their own name,
    relative to the package as the page's ``currentmodule`` makes them)."""
    for name in lidar_overlap.__all__:
        obj = getattr(lidar_overlap, name)
        module = isinstance(obj, types.ModuleType)
        if entry == name or (module and obj.__name__ == f"lidar_overlap.{entry}"):
            return name
    raise AssertionError(f"docs/api.rst lists {entry!r}, which lidar_overlap does not export")


def test_every_public_name_is_listed_once():
    entries = listed_names()
    documented = [exported_as(e) for e in entries]
    assert len(documented) == len(set(documented)), "a name is listed twice in docs/api.rst"
    missing = sorted(set(lidar_overlap.__all__) - set(documented))
    assert not missing, f"docs/api.rst lacks {missing}"


def test_the_page_is_read():
    # The parser must see the tables: the page lists well over half of the package's names.
    assert len(listed_names()) == len(lidar_overlap.__all__) > 50


def test_the_build_check_names_what_is_missing():
    # docs/_ext/api_coverage.py, run on the built site's objects; modules count by their own name.
    pytest.importorskip("sphinx")
    sys.path.insert(0, str(API_PAGE.parent / "_ext"))
    try:
        import api_coverage
    finally:
        sys.path.pop(0)
    every = {f"lidar_overlap.{n}" for n in lidar_overlap.__all__}
    assert api_coverage.missing_names(every) == []
    by_module_name = (every - {"lidar_overlap.plotting"}) | {"lidar_overlap.views.plotting"}
    assert api_coverage.missing_names(by_module_name) == []
    assert api_coverage.missing_names(every - {"lidar_overlap.overlap"}) == ["overlap"]
