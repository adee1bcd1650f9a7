"""Files: scenario TOML files (a system, ranges and a method) and measured curves."""
