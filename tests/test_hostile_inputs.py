"""Hostile input never crashes, hangs or returns a silent wrong number: property-based probes of
every public entry point (hypothesis, fixed seed), run in a worker process so that a crash cannot
take the test session down (see tests/_probe_worker.py for the contract and tests/_hostile_probes.py
for what is drawn). All of an entry point's probes run; its test then fails with the table of
outcomes and the broken probes grouped by cause, with the shortest reproducer of each.

LIDAR_OVERLAP_PROBE_TIME_LIMIT (s, default 20) sets when a probe counts as a hang.
"""

import pytest
from _hostile_probes import PROBES
from _probe_runner import Campaign
from hypothesis import HealthCheck, Phase, given, settings


@pytest.mark.parametrize("entry", list(PROBES))
def test_hostile_inputs_end_in_a_clean_error_or_a_finite_result(entry, runner):
    strategy, examples = PROBES[entry]
    campaign = Campaign(runner)

    # Failures are collected rather than raised: every example runs, and no time goes into
    # shrinking.
    @settings(
        max_examples=examples,
        derandomize=True,
        database=None,
        deadline=None,
        phases=[Phase.explicit, Phase.generate],
        suppress_health_check=list(HealthCheck),
    )
    @given(probe=strategy)
    def probe_once(probe):
        campaign.run(probe)

    probe_once()
    if campaign.tally.broken or campaign.not_run:
        pytest.fail(campaign.failure_report(), pytrace=False)
