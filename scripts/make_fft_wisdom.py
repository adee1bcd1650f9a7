"""Measure the plans of the library's 1-D block transforms, write them into the source as wisdom.

The transforms (cpp/src/fourier/fft.hpp) are made of FFTW plans for blocks of 8 rows and for single
rows, in place and out of place, in both directions. They are planned from the wisdom in
cpp/src/fourier/fft_wisdom.inc, so that every process gets the same plans (and the same bits) while
the plans are the fast ones FFTW_MEASURE finds. This script measures the wisdom anew, for the powers
of two from 16 to 4096 points (the grids propagate and the FO paths use most), with the FFTW the
library is built against, and writes it with the machine it was measured on. Run it on a quiet
machine, rebuild (make setup) and commit the file: every result of a transform whose plan changed
then differs from the last in its last bits (round-off of another algorithm), within the tests'
tolerances.

    PYTHONPATH=python .venv/bin/python scripts/make_fft_wisdom.py [--max-length 4096]
"""

from __future__ import annotations

import argparse
import datetime
import platform
import sys
from pathlib import Path

from lidar_overlap import _core

TARGET = Path(__file__).resolve().parent.parent / "cpp" / "src" / "fourier" / "fft_wisdom.inc"


def cpu_model() -> str:
    """The CPU's model name from /proc/cpuinfo, else the platform's processor string."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def choose(length: int, candidates: int, rounds: int) -> tuple[str, list[float]]:
    """The fastest of ``candidates`` wisdoms measured for ``length`` and of none (estimated plans),
    timed in alternating rounds as the library's 2-D transforms of length x length (least time of
    each): FFTW_MEASURE times each plan once, briefly, so its choice varies with the load."""
    options = [""] + [_core._measure_fft_wisdom([length])[1] for _ in range(candidates)]
    repeats = max(1, int(2e6 / (length * length)))  # ~0.1 s per timing at any length
    times = [float("inf")] * len(options)
    for _ in range(rounds):
        for k, wisdom in enumerate(options):
            times[k] = min(times[k], _core._block_transform_seconds(length, wisdom, repeats))
    best = min(range(len(options)), key=times.__getitem__)
    return options[best], times


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--max-length", type=int, default=4096, help="largest transform length (default 4096)"
    )
    parser.add_argument(
        "--candidates", type=int, default=3, help="measured wisdoms per length (default 3)"
    )
    parser.add_argument("--rounds", type=int, default=5, help="timing rounds (default 5)")
    args = parser.parse_args(argv)
    if not 16 <= args.max_length <= 4096:
        parser.error(f"--max-length = {args.max_length} is invalid: expected 16 to 4096")
    if not 1 <= args.candidates <= 20 or not 1 <= args.rounds <= 100:
        parser.error("--candidates and --rounds are invalid: expected 1 to 20 and 1 to 100")
    lengths = [1 << k for k in range(4, args.max_length.bit_length())]
    chosen = []
    for length in lengths:
        wisdom, times = choose(length, args.candidates, args.rounds)
        ms = ", ".join(f"{t * 1e3:.3f}" for t in times)
        print(f"{length}: estimated, measured x{args.candidates}: {ms} ms", flush=True)
        if wisdom:
            chosen.append(wisdom)
    fftw = _core._measure_fft_wisdom([])[0]
    wisdom = _core._merge_fft_wisdom(chosen)
    if any(c in text for text in (fftw, wisdom) for c in '"\\'):
        raise RuntimeError("FFTW's wisdom or version string holds a quote or a backslash")
    # A literal per line (adjacent literals join): compilers limit the length of one literal.
    lines = "\n".join(f'    "{line}\\n"' for line in wisdom.splitlines())
    stamp = datetime.date.today().isoformat()
    TARGET.write_text(
        f"// FFTW wisdom for the block transforms of lengths {lengths[0]} to {lengths[-1]}"
        " (fft_wisdom.hpp),\n"
        f"// measured with FFTW_MEASURE on {cpu_model()}, {stamp}, by scripts/make_fft_wisdom.py\n"
        f"// (per length the fastest of {args.candidates} measured plans and the estimated ones).\n"
        "// Generated: do not edit.\n"
        f'constexpr const char* kShippedWisdomFftw = "{fftw}";\n'
        f"constexpr const char* kShippedWisdom =\n{lines};\n"
    )
    print(f"wrote {TARGET} ({len(wisdom)} characters, {len(lengths)} lengths)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
