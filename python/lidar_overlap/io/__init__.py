"""Files: scenario TOML files (a system, ranges and a method), measured curves and series of them,
and a measured curve's range-resolved noise.

Files: noise_profile.py, overlap_curves.py, overlap_series.py, scenario.py, scenario_schema.py,
scenario_sections.py, scenario_writer.py.
"""

__all__ = [
    "noise_profile",
    "overlap_curves",
    "overlap_series",
    "scenario",
    "scenario_schema",
    "scenario_sections",
    "scenario_writer",
]
