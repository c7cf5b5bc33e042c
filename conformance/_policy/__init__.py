"""What the harness knows about releases: version ranges, known divergences, release guards."""
