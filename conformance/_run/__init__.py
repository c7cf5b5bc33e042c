"""Running cases: the runner (expectations and agreement per step), reports, the pytest plugin."""
