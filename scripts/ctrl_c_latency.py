"""Ctrl-C latency of lidar_overlap's long calls: CPU and wall-clock seconds from SIGINT to the end.

Runs each long call of tests/_interrupted_run.py (LONG_CALLS: one per kind of loop) in a fresh
interpreter, sends SIGINT once it has spent the given CPU seconds in the call, and prints, per call
and signal point, the CPU seconds of all its threads and the wall-clock seconds it took to stop
(worst of ``--rounds`` runs), with the machine's load average before and after. The CPU figure is
what tests/test_ctrl_c.py bounds; the wall figure grows with the load.

    PYTHONPATH=python .venv/bin/python scripts/ctrl_c_latency.py [--rounds 3] [--call NAME ...]
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from _interrupted_run import INTERRUPT_CPU, LONG_CALLS, interrupted_run  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--rounds", type=int, default=1, help="runs per call and point (worst kept)"
    )
    parser.add_argument(
        "--call", choices=list(LONG_CALLS), action="append", help="only these calls (repeatable)"
    )
    args = parser.parse_args(argv)
    names = args.call or list(LONG_CALLS)
    print(f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print(f"{'call':30s} {'SIGINT at':>10s} {'CPU s':>7s} {'wall s':>7s}  stopped")
    worst = 0.0
    for name in names:
        setup, call, warms = LONG_CALLS[name]
        for warm in warms:
            runs = [interrupted_run(call, setup, warm_cpu=warm) for _ in range(args.rounds)]
            cpu, wall = max(r.cpu for r in runs), max(r.wall for r in runs)
            stopped = all("KeyboardInterrupt" in r.stderr and not r.finished for r in runs)
            worst = max(worst, cpu)
            print(
                f"{name:30s} {warm:8.1f} s {cpu:7.2f} {wall:7.2f}  {'yes' if stopped else 'NO'}",
                flush=True,
            )
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    print(
        f"worst CPU after SIGINT: {worst:.2f} s "
        f"(bound in tests/test_ctrl_c.py: {INTERRUPT_CPU:g} s)"
    )
    return 0 if worst < INTERRUPT_CPU else 1


if __name__ == "__main__":
    sys.exit(main())
