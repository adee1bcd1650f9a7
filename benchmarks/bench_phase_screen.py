"""Phase screens: one 512 x 512 modified von Karman screen with subharmonics, lo against aotools'
`ft_sh_phase_screen` (benchmark-only dependency), in one process, with the structure function of
both against 6.88 (r/r0)^(5/3) so that the comparison is at equal quality.

lo: `_core.phase_screen(n, spacing, r0, L0, l0, seed, index)` (C++, FFT screen plus three levels of
subharmonics, one screen per call; `generate_pair` in C++ gives two per FFT). aotools: the same
method in
NumPy. Timing: best of 7 after one untimed call. Writes results/bench_phase_screen.json.
"""

from __future__ import annotations

import numpy as np
from _common import best_time, load_average, run_meta, source_commit, write_result

import lidar_overlap as lo

N, SPACING, R0, L0, L0_INNER = 512, 0.01, 0.1, 1e6, 1e-6  # aotools needs l0 > 0; 1 um is none here
SCREENS_FOR_D = 60  # screens averaged for the structure function
SEPARATIONS = (4, 8, 16, 32, 64, 128)


def structure_function(screens):
    d = []
    for s in SEPARATIONS:
        d.append(np.mean([np.mean((x[:, s:] - x[:, :-s]) ** 2) for x in screens]))
    return np.array(d) / (6.88 * (np.array(SEPARATIONS) * SPACING / R0) ** (5 / 3))


def main():
    load = load_average()
    print(f"lidar_overlap {lo.__version__} | load {load:.2f} | commit {source_commit()}")

    def lo_screen(i=0):
        return lo._core.phase_screen(N, SPACING, R0, L0, L0_INNER, 1, i)

    lo_screen()
    t_lo, _ = best_time(lo_screen, 7)
    row = {
        "lo_ms": 1e3 * t_lo,
        "lo_D_over_kolmogorov": structure_function(
            [lo_screen(i) for i in range(SCREENS_FOR_D)]
        ).tolist(),
    }
    try:
        from aotools.turbulence.phasescreen import ft_sh_phase_screen

        def peer():
            return ft_sh_phase_screen(R0, N, SPACING, L0, L0_INNER)

        peer()
        t_peer, _ = best_time(peer, 7)
        row.update(
            aotools_ms=1e3 * t_peer,
            speedup=t_peer / t_lo,
            aotools_D_over_kolmogorov=structure_function(
                [peer() for _ in range(SCREENS_FOR_D)]
            ).tolist(),
        )
        print(
            f"{N}^2 screen with subharmonics: lo {1e3 * t_lo:.1f} ms, aotools {1e3 * t_peer:.1f} "
            f"ms: lo {t_peer / t_lo:.1f}x faster (target >= 5x)"
        )
    except ImportError:
        print(f"{N}^2 screen with subharmonics: lo {1e3 * t_lo:.1f} ms (aotools not installed)")
    for name in ("lo", "aotools"):
        if f"{name}_D_over_kolmogorov" in row:
            ratios = " ".join(f"{r:.3f}" for r in row[f"{name}_D_over_kolmogorov"])
            print(f"  {name}: D(r) / 6.88 (r/r0)^(5/3) at {SEPARATIONS} samples: {ratios}")
    write_result(
        "bench_phase_screen",
        {
            "meta": {
                **run_meta(load),
                "n": N,
                "spacing_m": SPACING,
                "r0_m": R0,
                "outer_scale_m": L0,
                "separations": SEPARATIONS,
                "screens_for_structure_function": SCREENS_FOR_D,
            },
            "result": row,
        },
    )


if __name__ == "__main__":
    main()
