"""Bitmask collision filter groups, as RigidBodyTree had them (seed 001, Drake ≤ v0.22).

Each group is one bit of a 128-bit mask. Every element carries two masks:

- ``m_e``, its membership: bit 0 (the universal group, which every element
  belongs to) plus the bit of each group it is a member of;
- ``i_e``, its ignores: the union of the bits that its groups ignore.

A pair is filtered iff ``(m_a & i_b) | (m_b & i_a) ≠ 0`` (attic
``multibody/collision/element.cc``, ``Element::CanCollideWith``). The test
costs the same for any number of groups. Ignoring bit 0 makes an element
invisible: every other element has bit 0 in its membership.

Names are scoped to a *session* (one parse, in RBT terms up to ``compile()``):
``end_session()`` forgets them, so the same file can be read twice without
its groups merging, while the bits stay taken (all count against the 128).
An ignore target may be named before it is defined in the same session; one
still undefined at ``end_session()`` is dropped (RBT only logged a warning)
and listed in ``undefined_ignores``.

>>> groups = CollisionFilterGroups()
>>> a, b = groups.define_group("A"), groups.define_group("B")
>>> groups.add_member("A", "body1"); groups.add_member("B", "body3"); groups.ignore("A", "B")
>>> groups.is_filtered("body1", "body3"), groups.is_filtered("body1", "body2")
(True, False)
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable
from typing import Any, ClassVar, Generic, TypeVar

from reimpl.legacy._errors import (
    DuplicateGroupError,
    TooManyGroupsError,
    UniversalGroupError,
    UnknownGroupError,
)

__all__ = ["UNIVERSAL", "CollisionFilterGroups", "GroupRef", "format_mask", "mask_table"]

E = TypeVar("E", bound=Hashable)

#: The bit of the universal group: every element is a member of it.
UNIVERSAL = 0

#: A group is named (in its session) or given by its bit.
GroupRef = str | int


def format_mask(mask: int, width: int = 4) -> str:
    """The mask as seed 003 prints it: ``0...`` then the low ``width`` bits, rightmost bit 0.

    >>> format_mask(0b101)
    '0...0101'
    """
    if mask >> width:
        width = mask.bit_length()
    return f"0...{mask:0{width}b}"


def mask_table(groups: CollisionFilterGroups[Any], width: int = 4) -> list[tuple[str, str, str]]:
    """Seed 003's table: (group, ``membership``/``ignore``, mask) for each user group, in bit order.

    >>> groups = CollisionFilterGroups()
    >>> groups.define_group("A"), groups.define_group("B"), groups.ignore("A", "B")
    (1, 2, None)
    >>> mask_table(groups)[:2]
    [('A', 'membership', '0...0011'), ('A', 'ignore', '0...0100')]
    """
    rows = []
    for bit in groups.bits():
        membership, ignore = groups.group_masks(bit)
        name = groups.name_of(bit)
        rows += [
            (name, "membership", format_mask(membership, width)),
            (name, "ignore", format_mask(ignore, width)),
        ]
    return rows


class CollisionFilterGroups(Generic[E]):
    """Named groups as bits, their members and their ignores; masks per element.

    Conventions: ``a, b`` are elements (any hashable: geometry ids, names),
    ``m_a, i_a`` their membership and ignore masks, a *group* is a name in
    the current session or a bit.
    """

    #: The mask width: bit 0 (universal) and 127 user groups.
    MAX_GROUPS: ClassVar[int] = 128

    def __init__(self) -> None:
        self._next_bit = 1  # Bit 0 is consumed by the universal group.
        self._session: dict[str, int] = {}
        self._names: dict[int, str] = {UNIVERSAL: "universal"}
        self._members: dict[int, dict[E, None]] = {}  # an ordered set per bit
        self._ignores: dict[int, set[int]] = {}
        self._pending: dict[int, list[str]] = {}  # ignore targets not yet defined
        self._undefined: list[tuple[str, str]] = []
        self._masks: dict[E, tuple[int, int]] | None = None

    # ------------------------------------------------------------ building
    def define_group(self, name: str) -> int:
        """Defines ``name`` in this session and returns its bit (1, 2, ... in order).

        Raises:
            DuplicateGroupError: ``name`` is already defined in this session.
            TooManyGroupsError: all 127 user bits are taken (this would be the 129th group).
        """
        if name in self._session:
            raise DuplicateGroupError(
                f"Attempting to create duplicate collision filter group: {name}."
            )
        if self._next_bit >= self.MAX_GROUPS:
            raise TooManyGroupsError(
                f"Cannot define collision filter group '{name}': the mask has "
                f"{self.MAX_GROUPS} bits and bit 0 is the universal group, so only "
                f"{self.MAX_GROUPS - 1} groups can be defined (this would be group "
                f"{self.MAX_GROUPS + 1} counting the universal one)."
            )
        bit = self._next_bit
        self._next_bit += 1
        self._session[name] = bit
        self._names[bit] = name
        self._members[bit] = {}
        self._ignores[bit] = set()
        self._masks = None
        return bit

    def add_member(self, group: GroupRef, element: E) -> None:
        """Makes ``element`` a member of ``group``: ``m_element`` gains the group's bit.

        Raises:
            UnknownGroupError: the group is not defined.
            UniversalGroupError: ``group`` is bit 0 (every element is already a member).
        """
        bit = self._user_bit(group, "add a member to")
        self._members[bit][element] = None
        self._masks = None

    def ignore(self, group: GroupRef, ignored_group: GroupRef) -> None:
        """Makes every member of ``group`` ignore ``ignored_group`` (``group`` may ignore itself).

        An ``ignored_group`` name not defined yet is kept and resolved when the
        name is defined in this session; ``UNIVERSAL`` (0) makes the members
        invisible.

        Raises:
            UnknownGroupError: ``group``, or an ``ignored_group`` given as a bit, is not defined.
            UniversalGroupError: ``group`` is bit 0.
        """
        bit = self._user_bit(group, "add an ignore to")
        if isinstance(ignored_group, str) and ignored_group not in self._session:
            self._pending[bit] = [*self._pending.get(bit, []), ignored_group]
        else:
            self._ignores[bit].add(self._bit(ignored_group, "ignore"))
        self._masks = None

    def end_session(self) -> None:
        """Ends the session (the RBT's compile): resolves or drops pending ignores, forgets names.

        Bits stay taken and keep their members and ignores.
        """
        for bit, targets in self._pending.items():
            for target in targets:
                if target in self._session:
                    self._ignores[bit].add(self._session[target])
                else:
                    self._undefined.append((self._names[bit], target))
        self._pending.clear()
        self._session.clear()
        self._masks = None

    # ------------------------------------------------------------- reading
    @property
    def undefined_ignores(self) -> tuple[tuple[str, str], ...]:
        """(group, target) for every ignore target still undefined when its session ended."""
        return tuple(self._undefined)

    @property
    def num_groups(self) -> int:
        """The user groups defined so far (bit 0 not counted)."""
        return self._next_bit - 1

    def bits(self) -> tuple[int, ...]:
        """The user groups' bits, in definition order."""
        return tuple(range(1, self._next_bit))

    def name_of(self, bit: int) -> str:
        """The name the group with ``bit`` was defined with (``universal`` for bit 0)."""
        return self._names[self._bit(bit, "name")]

    def bit_of(self, group: GroupRef) -> int:
        """The bit of ``group`` (a name of this session, or a bit)."""
        return self._bit(group, "look up")

    def members(self, group: GroupRef) -> tuple[E, ...]:
        """The members added to ``group``, in order (bit 0's members are implicit: all)."""
        return tuple(self._members.get(self._bit(group, "list"), ()))

    def ignored_bits(self, group: GroupRef) -> tuple[int, ...]:
        """The bits ``group`` ignores (targets pending in this session included once defined)."""
        bit = self._bit(group, "list")
        return tuple(sorted(self._resolved_ignores(bit)))

    def group_masks(self, group: GroupRef) -> tuple[int, int]:
        """(membership, ignore) of a member of ``group`` alone: ``(1 | 1 << bit, ignores)``.

        These are the rows of seed 003's table.
        """
        bit = self._user_bit(group, "read the masks of")
        return 1 << UNIVERSAL | 1 << bit, self._ignore_bits(bit)

    def membership_mask(self, element: E) -> int:
        """``m_e``: bit 0 plus the bits of the groups ``element`` is a member of."""
        return self._element_masks().get(element, (1 << UNIVERSAL, 0))[0]

    def ignore_mask(self, element: E) -> int:
        """``i_e``: the union of the bits ignored by the groups ``element`` is a member of."""
        return self._element_masks().get(element, (1 << UNIVERSAL, 0))[1]

    def is_filtered(self, a: E, b: E) -> bool:
        """True iff ``(m_a & i_b) | (m_b & i_a) ≠ 0``: constant cost, whatever the groups."""
        masks = self._element_masks()
        m_a, i_a = masks.get(a, (1, 0))
        m_b, i_b = masks.get(b, (1, 0))
        return ((m_a & i_b) | (m_b & i_a)) != 0

    def filtered_pairs(self, elements: Iterable[E]) -> set[frozenset[E]]:
        """Every pair {a, b} of distinct ``elements`` that ``is_filtered``."""
        masks = self._element_masks()
        listed = list(dict.fromkeys(elements))
        pairs: set[frozenset[E]] = set()
        for i, a in enumerate(listed):
            m_a, i_a = masks.get(a, (1, 0))
            for b in listed[i + 1 :]:
                m_b, i_b = masks.get(b, (1, 0))
                if (m_a & i_b) | (m_b & i_a):
                    pairs.add(frozenset((a, b)))
        return pairs

    # ------------------------------------------------------------- helpers
    def _bit(self, group: GroupRef, verb: str) -> int:
        if isinstance(group, str):
            if group not in self._session:
                raise UnknownGroupError(
                    f"Cannot {verb} collision filter group '{group}': it is not defined in "
                    "this session."
                )
            return self._session[group]
        if not 0 <= group < self._next_bit:
            raise UnknownGroupError(
                f"Cannot {verb} collision filter group bit {group}: bits 0..{self._next_bit - 1} "
                "are defined."
            )
        return group

    def _user_bit(self, group: GroupRef, verb: str) -> int:
        bit = self._bit(group, verb)
        if bit == UNIVERSAL:
            raise UniversalGroupError(
                f"Cannot {verb} the universal group (bit 0): every element is a member of it "
                "and it ignores nothing."
            )
        return bit

    def _resolved_ignores(self, bit: int) -> set[int]:
        targets = self._pending.get(bit, ())
        return self._ignores[bit] | {self._session[t] for t in targets if t in self._session}

    def _ignore_bits(self, bit: int) -> int:
        mask = 0
        for target in self._resolved_ignores(bit):
            mask |= 1 << target
        return mask

    def _element_masks(self) -> dict[E, tuple[int, int]]:
        if self._masks is None:
            masks: dict[E, tuple[int, int]] = {}
            for bit, members in self._members.items():
                ignores = self._ignore_bits(bit)
                for element in members:
                    m, i = masks.get(element, (1 << UNIVERSAL, 0))
                    masks[element] = (m | 1 << bit, i | ignores)
            self._masks = masks
        return self._masks
