"""The opt-in tests and CI's seeded slice of them.

Fuzz campaigns (``fuzz``) and the mutant proofs (``mutant_proof``: a campaign
against a planted bug, until it is caught and its shrunk file replays) take
minutes each, so the default run leaves them out (pyproject's ``addopts``).
``-m fuzz`` or ``-m mutant_proof`` runs them all. ``--slice N`` keeps N
parametrizations of each opt-in test function, chosen by ``--slice-seed S``:
the same seed keeps the same items, and CI's seed (the commit count) moves the
slice along from commit to commit, so every mutant is proved now and then
while each run stays bounded.
"""

from __future__ import annotations

import hashlib
from collections import defaultdict

import pytest

__all__ = ["OPT_IN", "add_options", "keep_slice"]

#: The markers whose tests run only when asked for.
OPT_IN = ("fuzz", "mutant_proof")


def add_options(parser: pytest.Parser) -> None:
    group = parser.getgroup("opt-in slice")
    group.addoption(
        "--slice",
        type=int,
        metavar="N",
        help="keep N parametrizations of each opt-in (fuzz, mutant_proof) test function",
    )
    group.addoption(
        "--slice-seed",
        type=int,
        default=0,
        metavar="S",
        help="which N --slice keeps (default 0; the same seed keeps the same items)",
    )


def _rank(seed: int, nodeid: str) -> bytes:
    return hashlib.blake2b(f"{seed}:{nodeid}".encode(), digest_size=8).digest()


def keep_slice(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Deselects all but ``--slice`` items of each opt-in test function (by seeded rank)."""
    keep = config.getoption("slice")
    if keep is None:
        return
    seed = config.getoption("slice_seed")
    functions: dict[tuple[str, str], list[pytest.Item]] = defaultdict(list)
    for item in items:
        if any(item.get_closest_marker(marker) for marker in OPT_IN):
            function = getattr(item, "originalname", item.name)
            functions[(item.nodeid.split("::")[0], function)].append(item)
    dropped: set[str] = set()
    for group in functions.values():
        ranked = sorted(group, key=lambda item: _rank(seed, item.nodeid))
        dropped.update(item.nodeid for item in ranked[keep:])
    if dropped:
        config.hook.pytest_deselected(items=[i for i in items if i.nodeid in dropped])
        items[:] = [i for i in items if i.nodeid not in dropped]
