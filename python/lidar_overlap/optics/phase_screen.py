"""Random phase screens of atmospheric turbulence (the core's FFT method with subharmonics).

The screens follow the modified von Kármán phase spectrum Φ(f) = 0.0229 r0^(-5/3) exp(-(f/fm)²) /
(f² + 1/L0²)^(11/6), fm = 5.92 / (2π l0), in cycles per metre. High frequencies come from filtered
white noise on the FFT grid, low ones from three levels of 3 × 3 subharmonics whose weights carry
each cell's whole phase-gradient variance (see ``cpp/include/lidar_overlap/phase_screen.hpp``). For
Kolmogorov turbulence (L0 = ∞, l0 = 0) the mean structure function D(r) = <(φ(x + r) - φ(x))²> is
within 2 % of 6.88 (r / r0)^(5/3) from 4 samples to n/4.
"""

from __future__ import annotations

import math

import numpy as np

from .. import _checks, _core


def phase_screen(
    n: int,
    spacing: float,
    r0: float,
    outer_scale: float = math.inf,
    inner_scale: float = 0.0,
    seed: int = 0,
    index: int = 0,
) -> np.ndarray:
    """One phase screen (rad) as an (n, n) array; sample [iy, ix] sits at x = (ix - n/2) spacing, y
    = (iy - n/2) spacing, as in :class:`Field`.

    Parameters
    ----------
    n : samples per side, even, >= 8 (the grid is checked against the memory budget,
        ``max_memory``).
    spacing : m, sample spacing.
    r0 : m, Fried parameter of the layer (``inf``: no turbulence, a zero screen).
    outer_scale : m, von Kármán outer scale L0 (``inf``: Kolmogorov).
    inner_scale : m, inner scale l0 (0: none).
    seed, index : screen ``index`` of the stream ``seed``; the same pair gives the same screen, bit
        for bit, in any call order and from any thread. Screens of different indices are
        independent.
    """
    n = _checks.count("n", n, 8)
    return _core.phase_screen(
        n,
        _checks.real("spacing", spacing),
        _checks.real("r0", r0),
        _checks.real("outer_scale", outer_scale),
        _checks.real("inner_scale", inner_scale),
        _checks.count("seed", seed, 0, 2**64 - 1),
        _checks.count("index", index, 0, 2**63),
    )
