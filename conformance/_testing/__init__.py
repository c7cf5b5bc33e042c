"""Instruments for testing the harness itself (mutant backends). Not used by the harness."""
