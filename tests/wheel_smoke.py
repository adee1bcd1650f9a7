"""Smoke run of an installed lidar_overlap, for a wheel in a fresh environment
(tests/test_wheel.py; cibuildwheel's test-command): needs only numpy and the package. One RT, one
FO and one propagate call against closed forms, the command line's --help and a small `run` whose
CSV must hold RT's numbers, and the shared libraries of FFTW and OpenMP that the process loaded
(from /proc/self/maps, Linux).

Usage: python wheel_smoke.py OUTDIR. Exits non-zero on a failed check; prints one JSON object (the
numbers, which tests/test_wheel.py compares with the developer's install, and the loaded
libraries).
"""

import json
import math
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import numpy as np

import lidar_overlap as lo

RANGES = [5.0, 20.0, 100.0, 300.0, 1000.0]  # m
RT_TOLERANCE = 1e-4  # absolute error asked of RT on G
#: Table 1 (f = 1 m, FFOV 0.9 mrad, divergence 0.113 mrad) is in full overlap at 1 km: RT gives 1
#: within its tolerance.
FAR_ATOL = RT_TOLERANCE
#: FO keeps the diffraction tail that RT leaves out: 1 - G_FO ~ lambda / (pi^2 D theta) ~ 1e-3 for
#: D = 0.15 m, theta = 0.45 mrad, 355 nm (paper Section 5); 5e-3 leaves room for the Airy rings.
FO_FAR_ATOL = 5e-3
#: Gaussian beam radius after propagation against D1, w0 sqrt(1 + (z / zR)^2): the project's 0.01 %.
RADIUS_RTOL = 1e-4
#: Power after the angular spectrum (unitary when the window and band limit cut nothing).
POWER_RTOL = 1e-10

SCENARIO = """name = "smoke"
[beam]
type = "gaussian"
wavelength = 355e-9
waist_radius = 1e-3
[telescope]
diameter = 0.15
focal_length = 1.0
obstruction_radius = 0.0
obstruction_distance = 0.7
[detector]
fov = 0.9e-3
defocus = 0.0
[ranges]
values = {ranges}
[run]
method = "rt"
tolerance = {tolerance}
[output]
csv = true
netcdf = false
plot = false
scene = false
"""


def check(condition: bool, message: str) -> None:
    if not condition:
        sys.exit(f"wheel smoke: {message}")


def loaded_libraries() -> list:
    """Files of FFTW and of an OpenMP runtime mapped into this process (empty where /proc is
    absent)."""
    maps = Path("/proc/self/maps")
    if not maps.exists():
        return []
    paths = {line.split()[-1] for line in maps.read_text().splitlines() if "/" in line}
    names = ("fftw", "gomp", "libomp", "libiomp")
    return sorted(p for p in paths if any(n in Path(p).name for n in names))


def main(out: Path) -> dict:
    system = lo.paper_table1()
    rt = lo.overlap(system, RANGES, method=lo.RT(tolerance=RT_TOLERANCE))
    check(abs(rt.overlap[-1] - 1.0) <= FAR_ATOL, f"RT G(1 km) = {rt.overlap[-1]!r}, expected 1")
    check(bool(np.all(np.diff(rt.overlap) >= -RT_TOLERANCE)), "RT G(z) is not rising")
    fo = lo.overlap(system, RANGES[-2:], method=lo.FO())
    check(
        bool(np.all(np.abs(fo.overlap - rt.overlap[-2:]) <= FO_FAR_ATOL)),
        f"FO {fo.overlap.tolist()} against RT {rt.overlap[-2:].tolist()}",
    )

    wavelength, w0, n = 355e-9, 5e-3, 256
    field = lo.Field.gaussian(wavelength, w0, n, 10.0 * w0 / n)
    z = 10.0  # m, inside the angular spectrum's region n dx^2 / lambda = 27.5 m
    moved = lo.propagate(field, z)
    expected = w0 * math.sqrt(1.0 + (wavelength * z / (math.pi * w0**2)) ** 2)
    check(
        abs(moved.beam_radius / expected - 1.0) <= RADIUS_RTOL,
        f"propagated radius {moved.beam_radius!r} m, D1 gives {expected!r} m",
    )
    check(
        abs(moved.power / field.power - 1.0) <= POWER_RTOL,
        f"power {field.power!r} -> {moved.power!r} W",
    )

    cli = shutil.which("lidar-overlap", path=sysconfig.get_path("scripts"))
    check(cli is not None, f"no lidar-overlap in {sysconfig.get_path('scripts')}")
    helped = subprocess.run([str(cli), "--help"], capture_output=True, text=True, timeout=120)
    check(helped.returncode == 0 and "run" in helped.stdout, f"--help: {helped.stderr}")
    scenario = out / "smoke.toml"
    scenario.write_text(SCENARIO.format(ranges=RANGES, tolerance=RT_TOLERANCE))
    ran = subprocess.run(
        [str(cli), "run", str(scenario), "--out", str(out), "--quiet"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    check(ran.returncode == 0, f"lidar-overlap run exited {ran.returncode}: {ran.stderr}")
    rows = [
        line.split(",")
        for line in (out / "smoke.csv").read_text().splitlines()
        if line and not line.startswith("#")
    ][1:]
    csv = np.array([[float(v) for v in row[:2]] for row in rows])
    check(np.array_equal(csv[:, 1], rt.overlap), "the CLI's CSV differs from lo.overlap")

    return {
        "version": lo.__version__,
        "package": str(Path(lo.__file__).resolve().parent),
        "rt": rt.overlap.tolist(),
        "fo": fo.overlap.tolist(),
        "radius": moved.beam_radius,
        "power": moved.power,
        "libraries": loaded_libraries(),
    }


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path.cwd()
    out.mkdir(parents=True, exist_ok=True)
    print(json.dumps(main(out)))
