"""Random hostile-input campaign against lidar_overlap, through the same worker as the test suite.

Draws N probes across the public API (the strategies of tests/_hostile_probes.py, shared between
entry points in the proportions of the test suite), runs each in a worker process, and prints the
probe table: tried / clean error / finite result / bad error / crash / hang / silent wrong, per
entry point and in total, then the probes that broke the contract grouped by cause, with the
shortest reproducer of each.

    PYTHONPATH=python .venv/bin/python scripts/probe_table.py [-n 3000] [--seed 1] [--time-limit 20]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from _hostile_probes import PROBES  # noqa: E402
from _probe_runner import Campaign, ProbeRunner, render  # noqa: E402
from hypothesis import HealthCheck, Phase, given, settings  # noqa: E402
from hypothesis import seed as hypothesis_seed  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "-n", "--probes", type=int, default=3000, help="probes in all (default 3000)"
    )
    parser.add_argument("--seed", type=int, default=1, help="random seed of the draw (default 1)")
    parser.add_argument(
        "--time-limit", type=float, default=20.0, help="seconds before a probe counts as a hang"
    )
    parser.add_argument(
        "--entry",
        choices=list(PROBES),
        action="append",
        help="only these entry points (repeatable)",
    )
    parser.add_argument(
        "--show", type=int, default=200, help="causes of broken probes to print (default 200)"
    )
    parser.add_argument(
        "--slowest", type=int, default=0, help="also print the N slowest probes (hangs included)"
    )
    args = parser.parse_args(argv)

    entries = args.entry or list(PROBES)
    total_share = sum(PROBES[e][1] for e in entries)
    start = time.monotonic()
    with ProbeRunner(time_limit=args.time_limit) as runner:
        # No budget on hangs or crashes: the campaign counts every one of them.
        campaign = Campaign(runner, max_hangs=10**9, max_crashes=10**9)
        timings = []
        for entry in entries:
            strategy, share = PROBES[entry]
            count = max(1, round(args.probes * share / total_share))

            @hypothesis_seed(args.seed)
            @settings(
                max_examples=count,
                database=None,
                deadline=None,
                phases=[Phase.generate],
                suppress_health_check=list(HealthCheck),
            )
            @given(probe=strategy)
            def probe_once(probe):
                before = time.monotonic()
                campaign.run(probe)
                timings.append((time.monotonic() - before, probe))

            probe_once()
            print(
                f"{entry}: {count} probes drawn, {time.monotonic() - start:.1f} s so far",
                file=sys.stderr,
            )
    tally = campaign.tally
    print(tally.table())
    print(
        f"\n{time.monotonic() - start:.1f} s in all, {campaign.seconds:.1f} s inside probes, "
        f"{runner.restarts} worker restarts"
    )
    if tally.broken:
        print(
            f"\n{len(tally.broken)} probes broke the contract; {len(tally.causes)} causes, most "
            "frequent first:"
        )
        print(tally.report(limit=args.show))
    if args.slowest:
        print("\nslowest probes:")
        for seconds, probe in sorted(timings, key=lambda t: -t[0])[: args.slowest]:
            print(f"{seconds:7.2f} s  {render(probe)[:300]}")
    return 1 if tally.broken else 0


if __name__ == "__main__":
    sys.exit(main())
