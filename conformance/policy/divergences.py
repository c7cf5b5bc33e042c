"""Known divergences, as data (``known_divergences.json``) with a small reader."""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

__all__ = ["Divergence", "known_divergences"]


@dataclass(frozen=True)
class Divergence:
    """One finding: what Drake documents, what it does, and where that is shown."""

    id: str
    kind: str  # doc_vs_drake | reimpl_vs_drake | drake_crash
    since: str | None
    until: str | None
    observed: str
    reason: str
    scenarios: tuple[str, ...]
    tests: tuple[str, ...]


@cache
def known_divergences() -> tuple[Divergence, ...]:
    data: dict[str, Any] = json.loads(
        resources.files("conformance.policy").joinpath("known_divergences.json").read_text()
    )
    return tuple(
        Divergence(
            id=e["id"],
            kind=e["kind"],
            since=e["drake"].get("since"),
            until=e["drake"].get("until"),
            observed=e["observed"],
            reason=e["reason"],
            scenarios=tuple(e["evidence"].get("scenarios", ())),
            tests=tuple(e["evidence"].get("tests", ())),
        )
        for e in data["entries"]
    )
