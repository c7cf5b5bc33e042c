"""Drake release numbers and ranges: since ≤ version ≤ until, by dotted release number."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["VersionRange", "parse_version", "version_in_range"]


def parse_version(text: str) -> tuple[int, ...]:
    """``"1.51.1"`` → ``(1, 51, 1)``; a local suffix and non-numeric parts are dropped."""
    return tuple(int(part) for part in text.split("+", maxsplit=1)[0].split(".") if part.isdigit())


def version_in_range(version: str, since: str | None, until: str | None) -> bool:
    """since ≤ version ≤ until, by dotted release number (``until`` "1.51" covers 1.51.x)."""
    v = parse_version(version)
    if not v:  # "unknown": no release claimed, so only the open range holds it
        return since is None and until is None
    if since is not None and v < parse_version(since):
        return False
    if until is None:
        return True
    bound = parse_version(until)
    return v[: len(bound)] <= bound


@dataclass(frozen=True)
class VersionRange:
    """The Drake releases ``since``..``until`` (inclusive; ``None`` is open)."""

    since: str | None = None
    until: str | None = None

    def __contains__(self, version: object) -> bool:
        return isinstance(version, str) and version_in_range(version, self.since, self.until)

    def before(self, version: str) -> bool:
        """``version`` < since (False without a ``since``, or for an unknown version)."""
        v = parse_version(version)
        return bool(v) and self.since is not None and v < parse_version(self.since)

    def after(self, version: str) -> bool:
        """``version`` > until (False without an ``until``, or for an unknown version)."""
        v = parse_version(version)
        return (
            bool(v) and self.until is not None and not version_in_range(version, None, self.until)
        )

    def __str__(self) -> str:
        if self.since and self.until:
            return f"{self.since}-{self.until}"
        if self.since:
            return f">= {self.since}"
        return f"<= {self.until}" if self.until else "every release"
