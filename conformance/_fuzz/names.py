"""The names a fuzz run has made, and how an operation's picks read them.

``NameBook`` is the part of a ``operations.Machine`` that is not the
backends: the bundles of names (sources, frames, geometries, filter_ids,
contexts) in the order they were made, fresh names, and the ``CHOICES``
table by which a pick (one byte) stands for a name. The lockstep machine
(``conformance._fuzz.lockstep``) and the sequence recorder
(``conformance._fuzz.sequences``) are both NameBooks, so they read one drawn
step the same way.

``register_scene`` is the start of every fuzzed sequence: a drawn scene's
frames and geometries, registered under fresh names.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from conformance._fuzz import strategies as cs
from conformance.protocol import Result

__all__ = [
    "BUNDLES",
    "CHOICES",
    "DEFAULT_SOURCE",
    "Choice",
    "NameBook",
    "register_scene",
]

DEFAULT_SOURCE = "source"

#: The bundles of names, as the scenario grammar uses them.
BUNDLES = ("sources", "frames", "geometries", "filter_ids", "contexts")


@dataclass(frozen=True)
class Choice:
    """How a name argument reads a pick: ``strategies.pick(names[bundle], pick, ...)``."""

    bundle: str
    #: Picks below this leave the argument out (it shrinks to being left out).
    none_below: int = 0
    #: Names drawn one time in eight (always, while the bundle is empty).
    rare: tuple[str, ...] = ()


_SPECIAL = (cs.UNKNOWN, cs.FOREIGN)

#: Every kind of name argument the operations take (picks are 0-255).
CHOICES: dict[str, Choice] = {
    "context": Choice("contexts", none_below=128),  # the model half the time
    "owner": Choice("sources", none_below=128),  # the implicit source half the time
    "parent": Choice("frames", none_below=128),  # the world half the time
    "reused_frame": Choice("frames", none_below=192),  # a duplicate name one time in four
    "reused_geometry": Choice("geometries", none_below=192),
    "frame": Choice("frames"),
    "geometry": Choice("geometries"),
    "any_geometry": Choice("geometries", rare=_SPECIAL),  # now and then @unknown/@foreign
    "any_frame": Choice("frames", rare=_SPECIAL),
    "label": Choice("filter_ids", rare=(cs.UNKNOWN,)),
    "origin": Choice("contexts"),
}


class NameBook:
    """Names made so far, by bundle, in the order made; see the module doc.

    ``special`` False drops the rare names (``@unknown``, ``@foreign``) from
    every choice: a pick that would name one names an ordinary name, or
    nothing while the bundle is empty.
    """

    #: Both sides have Activate/Deactivate (a subclass decides).
    activation: bool = False
    special: bool = True

    def __init__(self) -> None:
        super().__init__()  # cooperative: the lockstep machine is also a state machine
        self.names: dict[str, list[str]] = {bundle: [] for bundle in BUNDLES}
        #: Sources (with the implicit one) and contexts made so far.
        self.sources_made = 1
        self.contexts_made = 0
        self._counter = 0

    def fresh(self, prefix: str) -> str:
        self._counter += 1
        return f"{prefix}{self._counter}"

    def keep(self, bundle: str, *names: str) -> None:
        """Files ``names`` in ``self.names[bundle]``."""
        self.names[bundle].extend(names)

    def keep_if_made(self, bundle: str, name: str, result: Result) -> None:
        """``keep(bundle, name)`` if the command that made ``name`` succeeded."""
        if result.error is None:
            self.keep(bundle, name)

    def name(self, kind: str, pick: int) -> str | None:
        """The name a pick stands for, as ``CHOICES[kind]`` reads it."""
        choice = CHOICES[kind]
        return cs.pick(
            self.names[choice.bundle],
            pick,
            rare=choice.rare if self.special else (),
            none_below=choice.none_below,
        )

    def _any_geometry(self, pick: int) -> str | None:
        return self.name("any_geometry", pick)

    def _any_frame(self, pick: int) -> str | None:
        return self.name("any_frame", pick)

    def declaration(self, template: cs.DeclarationTemplate) -> dict[str, Any]:
        """A drawn declaration, resolved against the names so far."""
        return template.resolve(self._any_geometry, self._any_frame)

    def geometry_set(self, template: cs.SetTemplate) -> dict[str, list[str]]:
        """A drawn geometry set, resolved against the names so far."""
        return template.resolve(self._any_geometry, self._any_frame)

    def step(self, op: str, **args: Any) -> Result:
        raise NotImplementedError


def register_scene(book: NameBook, scene: cs.Scene) -> None:
    """Registers ``scene`` under fresh names and keeps them (with the implicit source and world).

    Frames become ``f<n>``, geometries ``g<n>``; a geometry is kept if its
    registration succeeded.
    """
    book.keep("sources", DEFAULT_SOURCE)
    frames: dict[str, str] = {}
    for name, parent in scene.frames:
        frames[name] = book.fresh("f")
        book.step("register_frame", name=frames[name], parent=frames.get(parent or ""))
    book.keep("frames", cs.WORLD, *frames.values())
    geometries = []
    for geometry in scene.geometries:
        name = book.fresh("g")
        frame = frames.get(geometry.frame, cs.WORLD)
        result = book.step("register_geometry", name=name, frame=frame, roles=[*geometry.roles])
        if result.error is None:
            geometries.append(name)
    book.keep("geometries", *geometries)
