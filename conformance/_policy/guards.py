"""Release guards: calls the harness refuses because they crash some Drake releases.

Some calls end the process in some releases (a failed ``DRAKE_DEMAND``, an
abort in the proximity engine), which would lose a whole run. A guard names
such a call by the id of its crash row in the release table
(``release_facts.json``, kind ``crash``); the row's range says where it
crashes. A run *arms* a guard when
any of its backends has a release in that range, and then every backend of
the run refuses the call alike (``ErrorKind.REFUSED``), so the backends stay
comparable and the run survives.

A backend takes part by having ``arm_guards(ids)``; ``SceneGraphBackend``
does, and checks ``guard_armed(id)`` before the calls each guard covers.

A worker backend (``isolated``: its own process, replaced when it dies)
need not be protected: a crash there loses nothing. ``run`` and ``matrix``
therefore let a worker's release crash and record it (``crash_isolated``):
only the in-process backends' releases arm guards, and every backend, the
workers too, refuses the calls those arm, so all stay comparable. The
fuzzer, which needs every backend alive for the next step, arms them all.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from conformance._policy.release_facts import FactKind, release_fact
from conformance._policy.versions import VersionRange
from conformance.protocol import Backend

__all__ = ["GUARDS", "Guard", "arm_guards", "armed_guards"]


@dataclass(frozen=True)
class Guard:
    """A refused call: the crash row that records the crash, and what is refused."""

    fact: str
    refuses: str

    def __post_init__(self) -> None:
        if release_fact(self.fact).kind is not FactKind.CRASH:
            raise ValueError(f"a guard names a crash row; {self.fact!r} is not one")

    @property
    def releases(self) -> VersionRange:
        return release_fact(self.fact).releases

    def message(self) -> str:
        return f"refused ({self.fact}): {self.refuses} aborts pydrake {self.releases}"


#: Every guard, by the id of its crash row.
GUARDS: dict[str, Guard] = {
    guard.fact: guard
    for guard in (
        Guard("deactivate-anchored-aborts", "(de)activating anchored geometry"),
        Guard(
            "older-context-pose-port-aborts",
            "fixing the pose port of, or cloning, a context that predates its source's port",
        ),
    )
}


def armed_guards(releases: Iterable[str]) -> frozenset[str]:
    """The ids of the guards whose release range holds any of ``releases``."""
    releases = tuple(releases)
    return frozenset(
        key for key, guard in GUARDS.items() if any(r in guard.releases for r in releases)
    )


def arm_guards(backends: Iterable[Backend], *, crash_isolated: bool = False) -> frozenset[str]:
    """Arms, on every backend that takes part, the guards any backend's release needs.

    ``crash_isolated``: the releases of isolated backends (workers) arm nothing.
    """
    backends = tuple(backends)
    ids = armed_guards(
        b.version() for b in backends if not (crash_isolated and getattr(b, "isolated", False))
    )
    for backend in backends:
        arm = getattr(backend, "arm_guards", None)
        if arm is not None:
            arm(ids)
    return ids
