"""The package namespace: every public name resolves to the object of its module, the names type
checkers see are the names the namespace serves, and ``import lidar_overlap`` loads no layer until a
name of it is used."""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

import lidar_overlap

INIT = Path(lidar_overlap.__file__)


def _type_checking_names() -> dict:
    """{name: module} of the imports under ``if TYPE_CHECKING:`` in the package's __init__."""
    for node in ast.parse(INIT.read_text()).body:
        if isinstance(node, ast.If) and getattr(node.test, "id", None) == "TYPE_CHECKING":
            names = {}
            for imp in node.body:
                assert isinstance(imp, ast.ImportFrom) and imp.level == 1, ast.dump(imp)
                for alias in imp.names:
                    names[alias.asname or alias.name] = (imp.module, alias.name)
            return names
    raise AssertionError("no TYPE_CHECKING block in lidar_overlap/__init__.py")


def test_type_checkers_see_the_names_the_namespace_serves():
    seen = _type_checking_names()
    home = lidar_overlap._HOME
    assert set(seen) == set(home)
    for name, (module, attribute) in seen.items():
        # ``from .model import parameters`` names the module model.parameters
        assert home[name] in (module, f"{module}.{attribute}"), (name, module, home[name])


@pytest.mark.parametrize("name", sorted(lidar_overlap.__all__))
def test_every_public_name_is_its_modules_object(name):
    value = getattr(lidar_overlap, name)
    module = lidar_overlap._HOME.get(name)
    if module is None:  # the eager names of the foundation
        return
    home = sys.modules[f"lidar_overlap.{module}"]
    assert value is (home if name in lidar_overlap._MODULES else getattr(home, name))
    assert name in dir(lidar_overlap)


def test_an_unknown_name_is_an_attribute_error_naming_it():
    with pytest.raises(AttributeError, match="'no_such_name'"):
        lidar_overlap.no_such_name  # noqa: B018
    assert not hasattr(lidar_overlap, "__wrapped__")


def test_importing_the_package_loads_no_layer_until_a_name_is_used():
    code = (
        "import sys, lidar_overlap as lo\n"
        "layers = ('model', 'optics', 'forward', 'analysis', 'io', 'views', 'cli')\n"
        "loaded = lambda: sorted(l for l in layers if f'lidar_overlap.{l}' in sys.modules)\n"
        "print(loaded()); lo.RT; print(loaded()); lo.fit; print(loaded())\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    before, after_rt, after_fit = (eval(line) for line in run.stdout.splitlines())
    assert before == []
    assert "forward" in after_rt and "analysis" not in after_rt
    assert "analysis" in after_fit and "views" not in after_fit
