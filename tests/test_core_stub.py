"""The typed stub lidar_overlap/_core.pyi matches the compiled module: mypy's stubtest, run on the
package that is imported (source tree or installed), fails on any name, class, property or signature
it gets wrong."""

import os
import pathlib
import subprocess
import sys

import pytest

import lidar_overlap

pytest.importorskip("mypy")

PACKAGE = pathlib.Path(lidar_overlap.__file__).parent
CONFIG = pathlib.Path(__file__).with_name("stubtest_mypy.ini")


def test_stub_ships_next_to_the_module():
    assert (PACKAGE / "_core.pyi").is_file() and (PACKAGE / "py.typed").is_file()


def test_stub_matches_the_module(tmp_path):
    # Stub and module from the same tree, seen alone: from an installed package's site-packages mypy
    # would also see every other module there (and refuse those that shadow its own library).
    (tmp_path / "lidar_overlap").symlink_to(PACKAGE, target_is_directory=True)
    root = str(tmp_path)
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")])),
    }
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy.stubtest",
            "lidar_overlap._core",
            "--mypy-config-file",
            str(CONFIG),
        ],
        cwd=root,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stdout + run.stderr
