"""G(z) of every overlap path on fixed scenes, written to JSON and compared with an earlier
snapshot.

A refactoring that keeps the algorithms must keep these numbers: run it before the change (``--write
before.json``) and after (``--compare before.json``); the comparison prints the largest
|ΔG| of each case and fails (exit 1) above ``--tolerance`` (default 1e-12).

Cases: RT (coaxial, tilted with obstruction, biaxial with defocus and fibre NA), FO radial and 2-D,
a FieldBeam (annulus), aberrated RT (pupil form and ray fan) and FO, auto at two tolerances (plain
and aberrated), turbulent RT and FO, and single-scatterer couplings.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import warnings

import numpy as np
from _common import json_text

import lidar_overlap as lo

Z = np.geomspace(20.0, 2000.0, 12)
Z_SHORT = np.geomspace(100.0, 2000.0, 6)


def scenes():
    table1 = lo.paper_table1()
    tilted = lo.paper_table1(obstruction_radius=0.02, defocus=1e-3)
    tilted = lo.LidarSystem(
        beam=lo.GaussianBeam(
            wavelength=355e-9, waist_radius=1e-3, offset=(0.05, 0.0), tilt=(-1e-4, 0.0)
        ),
        telescope=tilted.telescope,
        detector=tilted.detector,
    )
    biaxial = lo.LidarSystem(
        beam=lo.GaussianBeam(
            wavelength=532e-9, waist_radius=2e-3, divergence=3e-4, offset=(0.12, 0.0)
        ),
        telescope=lo.Telescope(diameter=0.2, focal_length=0.8),
        detector=lo.Detector(
            radius=0.3e-3, defocus=2e-3, offset=(0.0, 2e-5), numerical_aperture=0.22
        ),
    )
    fibre = lo.LidarSystem(
        beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=1.5e-3),
        telescope=lo.Telescope(diameter=0.1, focal_length=0.5),
        detector=lo.Detector(radius=25e-6),
    )
    aberrated = lo.LidarSystem(
        beam=table1.beam,
        detector=table1.detector,
        telescope=lo.Telescope(
            diameter=0.15,
            focal_length=1.0,
            aberrations=lo.Aberrations(zernike={11: 0.3e-6, 5: 0.2e-6}),
        ),
    )
    seidel = lo.LidarSystem(
        beam=table1.beam,
        detector=table1.detector,
        telescope=lo.Telescope(
            diameter=0.15,
            focal_length=1.0,
            aberrations=lo.Aberrations(w131=0.5e-6, field_radius=1e-3),
        ),
    )
    annulus = lo.annular_field(355e-9, outer_radius=4e-3, inner_radius=1.5e-3, n=256, spacing=6e-5)
    field_beam = lo.LidarSystem(
        beam=lo.FieldBeam(annulus), telescope=table1.telescope, detector=table1.detector
    )
    return table1, tilted, biaxial, fibre, aberrated, seidel, field_beam


def cases():
    table1, tilted, biaxial, fibre, aberrated, seidel, field_beam = scenes()
    turbulence = lo.Turbulence(1e-14, inner_scale=0.01)

    def curve(system, z, *args, **kwargs):
        return lo.overlap(system, z, *args, **kwargs).overlap

    yield "rt table1", lambda: curve(table1, Z, "rt", tolerance=1e-7)
    yield "rt tilted obstructed", lambda: curve(tilted, Z, "rt", tolerance=1e-6)
    yield "rt biaxial na", lambda: curve(biaxial, Z, "rt", tolerance=1e-6)
    yield "rt linear law", lambda: curve(lo.paper_table1(width_law="linear"), Z, "rt")
    yield "fo radial table1", lambda: curve(table1, Z, "fo")
    yield "fo radial biaxial", lambda: curve(biaxial, Z, "fo", fo_path="radial")
    yield "fo 2d tilted", lambda: curve(tilted, Z_SHORT, "fo", fo_path="2d")
    yield "fo 2d fibre grid", lambda: curve(fibre, Z_SHORT, "fo", fo_path="2d", beam_grid=128)
    yield "fo field annulus", lambda: curve(field_beam, Z_SHORT, "fo")
    yield "auto table1 1e-3", lambda: curve(table1, Z, "auto", tolerance=1e-3)
    yield "auto fibre 1e-4", lambda: curve(fibre, Z, "auto", tolerance=1e-4)
    yield "auto biaxial 1e-2", lambda: curve(biaxial, Z, "auto", tolerance=1e-2)
    yield "rt aberrated pupil", lambda: curve(aberrated, Z, "rt", tolerance=1e-5)
    yield "rt aberrated fan", lambda: curve(seidel, Z_SHORT, "rt", tolerance=1e-3)
    yield "fo aberrated", lambda: curve(aberrated, Z_SHORT, "fo")
    yield "auto aberrated 1e-3", lambda: curve(aberrated, Z_SHORT, "auto", tolerance=1e-3)
    yield "auto aberrated 1e-5", lambda: curve(aberrated, Z_SHORT, "auto", tolerance=1e-5)
    yield "auto seidel 1e-2", lambda: curve(seidel, Z_SHORT, "auto", tolerance=1e-2)
    yield (
        "turbulent rt",
        lambda: curve(
            table1, Z_SHORT, "rt", turbulence=turbulence, realizations=6, seed=3, paths="transmit"
        ),
    )
    yield (
        "turbulent fo",
        lambda: curve(
            table1,
            Z_SHORT,
            "fo",
            turbulence=turbulence,
            realizations=4,
            seed=3,
            beam_grid=128,
            paths="transmit",
        ),
    )
    yield (
        "coupling rt",
        lambda: [lo.emitter_coupling(tilted, 50.0, (x, 0.0)) for x in (0.0, 0.01, 0.03)],
    )
    yield (
        "coupling fo",
        lambda: [lo.emitter_coupling(table1, 1000.0, (x, 0.0), method="fo") for x in (0.0, 0.3)],
    )
    yield (
        "coupling rt aberrated",
        lambda: [lo.emitter_coupling(aberrated, 500.0, (x, 0.0)) for x in (0.0, 0.2)],
    )


def snapshot() -> dict:
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name, compute in cases():
            out[name] = [float(g) for g in np.ravel(compute())]
            print(f"{name:26s} {len(out[name]):3d} values", flush=True)
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--write", help="write the snapshot to this JSON file")
    group.add_argument("--compare", help="compare with the snapshot in this JSON file")
    parser.add_argument("--tolerance", type=float, default=1e-12)
    args = parser.parse_args(argv)
    now = snapshot()
    if args.write:
        with open(args.write, "w") as f:
            f.write(json_text(now, indent=1, named_non_finite=True))
        return 0
    with open(args.compare) as f:
        before = json.load(f)
    worst = 0.0
    for name in sorted(set(before) | set(now)):
        if name not in before or name not in now or len(before[name]) != len(now[name]):
            print(f"{name:26s} missing or resized")
            worst = math.inf
            continue
        stored = np.asarray(before[name], float)  # "NaN" and "(-)Infinity" back to floats
        delta = float(np.max(np.abs(np.subtract(stored, now[name]))))
        worst = max(worst, delta)
        print(f"{name:26s} max |dG| = {delta:.3g}")
    print(f"largest |dG| {worst:.3g} (tolerance {args.tolerance:g})")
    return 0 if worst <= args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
