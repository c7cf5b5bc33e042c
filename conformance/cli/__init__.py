"""``python -m conformance``: the command line (``run``, ``fuzz``, ``schema``)."""
