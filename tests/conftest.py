"""Fixtures shared by test files."""

import os
import sys
from pathlib import Path

import pytest
from _probe_runner import ProbeRunner

import lidar_overlap as lo


@pytest.fixture(scope="session")
def client():
    """A two-worker dask LocalCluster (processes) importing the package under test."""
    distributed = pytest.importorskip("distributed")
    package_root = os.path.dirname(os.path.dirname(os.path.abspath(lo.__file__)))
    old = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = os.pathsep.join(
        [package_root] + ([old] if old else [])
    )  # the workers' import
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    c = distributed.Client(cluster)
    try:
        yield c
    finally:
        c.close()
        cluster.close()
        if old is None:
            os.environ.pop("PYTHONPATH")
        else:
            os.environ["PYTHONPATH"] = old


@pytest.fixture
def no_scene(monkeypatch):
    """The command line's 3-D scene (pyvista) is slow to render and has tests of its own: the CLI
    test modules run as if pyvista were not installed (``pytestmark = usefixtures("no_scene")``)."""
    monkeypatch.setitem(sys.modules, "pyvista", None)


@pytest.fixture(scope="module")
def runner():
    """A worker process for hostile probes (tests/_probe_runner.py), one per test module: a probe
    that crashes or hangs fails its test, not the session."""
    with ProbeRunner() as r:
        yield r


@pytest.fixture
def fit_inputs(tmp_path):
    """Writes the command-line fit's inputs into tmp_path: the start, Table 1's scenario with its
    beam tilted by 0.2 mrad and its detector defocused by 1 mm, and the measured curve as CSV
    ``range_m,overlap``. Call it with (ranges, overlap); it returns (scenario, data) paths."""

    def write(ranges, overlap):
        scenario = tmp_path / "start.toml"
        table1 = Path(__file__).resolve().parents[1] / "examples" / "scenarios" / "table1.toml"
        scenario.write_text(
            table1.read_text()
            .replace("tilt = [0.0, 0.0]", "tilt = [2e-4, 0.0]")
            .replace("defocus = 0.0 ", "defocus = 1e-3 ")
        )
        data = tmp_path / "m.csv"
        data.write_text(
            "range_m,overlap\n"
            + "\n".join(f"{a!r},{b!r}" for a, b in zip(list(ranges), list(overlap)))
        )
        return scenario, data

    return write
