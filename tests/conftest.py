"""Fixtures shared by test files."""

import os

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


@pytest.fixture(scope="module")
def runner():
    """A worker process for hostile probes (tests/_probe_runner.py), one per test module: a probe
    that crashes or hangs fails its test, not the session."""
    with ProbeRunner() as r:
        yield r
