"""The package's layers hold: each module imports only its own layer and those below it, at module
level; within ``analysis``, each room (fitting, studies, design, bottom to top, above the shared
modules of ``analysis`` itself) imports only the shared modules, its own room and the rooms below;
only optional dependencies are imported inside functions; no module takes another's private names;
only the backends call the core's overlap computations; and the package imports with numpy and its
compiled core alone."""

import ast
import pathlib
import subprocess
import sys

import pytest

import lidar_overlap

PACKAGE = pathlib.Path(lidar_overlap.__file__).parent
#: Bottom to top; the private foundation modules (_core, _checks, _pickling, _files, _reading,
#: _interrupts, _values) are below all.
LAYERS = ("model", "optics", "forward", "analysis", "io", "views", "cli")
FOUNDATION = ("_core", "_checks", "_pickling", "_files", "_reading", "_interrupts", "_values")
#: The rooms of ``analysis``, bottom to top, above its shared modules (analysis/*.py).
ROOMS = ("fitting", "studies", "design")
#: Packages the library may import only inside the functions that need them.
OPTIONAL = (
    "scipy",
    "xarray",
    "matplotlib",
    "pyvista",
    "dask",
    "distributed",
    "h5netcdf",
    "h5py",
    "tqdm",
    "trame",
)
#: Package modules imported when first used: the results' .plot() methods import views.plotting
#: (matplotlib is optional), the one reference that runs up the layers (docs/architecture.md); the
#: package's own namespace loads views.app for lo.view (its asyncio and twin modules).
LATE = ("views.plotting", "views.app")


def _modules():
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE).with_suffix("")
        parts = [p for p in relative.parts if p != "__init__"]
        package = list(relative.parts[:-1])
        yield path, ".".join(parts), package


def _layer(dotted: str) -> int:
    head = dotted.split(".")[0]
    if head in FOUNDATION or head == "":
        return -1
    return LAYERS.index(head) if head in LAYERS else len(LAYERS)  # the top-level namespace


def _room(dotted: str) -> int:
    """0 for a shared module of ``analysis`` (or the package ``analysis`` itself), 1 + the room's
    place for a module in a room."""
    parts = dotted.split(".")
    return 1 + ROOMS.index(parts[1]) if len(parts) > 1 and parts[1] in ROOMS else 0


def _absolute(node: ast.ImportFrom, package: list) -> str:
    base = package[: len(package) - (node.level - 1)] if node.level else []
    return ".".join(base + ([node.module] if node.module else []))


def _imports(tree):
    """(node, inside a function) for every import of the module."""
    found = []

    def visit(node, inside):
        for child in ast.iter_child_nodes(node):
            nested = inside or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef))
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                found.append((child, inside))
            visit(child, nested)

    visit(tree, False)
    return found


def _package_targets(node, package):
    """The package modules (dotted, relative to the package) an import names."""
    if isinstance(node, ast.Import):
        return [
            a.name.removeprefix("lidar_overlap.")
            for a in node.names
            if a.name.startswith("lidar_overlap.")
        ]
    if node.level == 0:
        return (
            [node.module.removeprefix("lidar_overlap.")]
            if node.module.startswith("lidar_overlap.")
            else []
        )
    base = _absolute(node, package)
    return [f"{base}.{a.name}".strip(".") for a in node.names]


MODULES = list(_modules())


@pytest.mark.parametrize("path, dotted, package", MODULES, ids=[m[1] or "init" for m in MODULES])
def test_imports_run_downward_and_optional_ones_late(path, dotted, package):
    tree = ast.parse(path.read_text())
    own = _layer(dotted) if dotted else len(LAYERS)
    for node, inside in _imports(tree):
        if (
            isinstance(node, ast.ImportFrom)
            and node.level == 0
            and node.module.split(".")[0] in (OPTIONAL)
        ):
            assert inside, f"{dotted}: {node.module} (optional) imported at module level"
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] in OPTIONAL:
                    assert inside, f"{dotted}: {alias.name} (optional) imported at module level"
        for target in _package_targets(node, package):
            if inside and any(target == m or target.startswith(m + ".") for m in LATE):
                continue
            assert not inside, f"{dotted}: {target} imported inside a function"
            assert _layer(target) <= own, f"{dotted} (layer {own}) imports {target} from above"
            if dotted.startswith("analysis.") and target.startswith("analysis"):
                assert _room(target) <= _room(dotted), (
                    f"{dotted} (room {_room(dotted)}) imports {target} from a room above"
                )


def test_the_rooms_of_analysis_are_all_named():
    rooms = {p.parent.name for p in (PACKAGE / "analysis").glob("*/__init__.py")}
    assert rooms == set(ROOMS)


@pytest.mark.parametrize("path, dotted, package", MODULES, ids=[m[1] or "init" for m in MODULES])
def test_no_module_takes_another_modules_private_names(path, dotted, package):
    for node, _ in _imports(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level:
            for alias in node.names:
                dunder = alias.name.startswith("__") and alias.name.endswith("__")
                private = alias.name.startswith("_") and alias.name not in FOUNDATION and not dunder
                assert not private, f"{dotted} imports {alias.name} from {node.module}"


@pytest.mark.parametrize("path, dotted, package", MODULES, ids=[m[1] or "init" for m in MODULES])
def test_only_the_backends_call_the_cores_overlap_computations(path, dotted, package):
    if dotted.startswith("forward.backends"):
        return
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            if node.value.id == "_core":
                name = node.attr
                assert not (name.startswith("overlap_") or name == "alignment_map"), (
                    f"{dotted} calls _core.{name}: only forward/backends compute overlaps"
                )


def test_the_package_imports_with_numpy_and_its_core_alone():
    blocked = "; ".join(f"sys.modules[{name!r}] = None" for name in OPTIONAL)
    code = (
        f"import sys; {blocked}; import lidar_overlap as lo; s = lo.paper_table1(); "
        "print(lo.overlap(s, [100.0, 1000.0]).overlap[-1])"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert float(run.stdout) == pytest.approx(1.0, abs=1e-4)


def test_importing_the_package_loads_no_optional_dependency():
    code = f"import sys, lidar_overlap; print(sorted(m for m in {OPTIONAL!r} if m in sys.modules))"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "[]"


def test_an_optional_dependency_missing_names_its_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "scipy", None)
    monkeypatch.setitem(sys.modules, "scipy.special", None)
    with pytest.raises(ImportError, match=r"lidar-overlap\[fit\]"):
        lidar_overlap.laguerre_gauss_field(1e-6, 1e-3, 1, n=128, spacing=1e-4)
