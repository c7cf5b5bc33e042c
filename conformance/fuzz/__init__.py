"""Differential fuzzing: strategies, the lockstep state machine, campaigns, findings as files."""
