"""PairBits: a symmetric relation on slots, one bit set (a Python int) per slot.

Bit b of ``rows[a]`` is set iff the pair (a, b) is in the relation, and then
bit a of ``rows[b]`` is set too. The diagonal may be set (a *Within statement
writes it); no reader looks at it.

Rows are immutable ints, so ``copy()`` copies references: two copies share
every row until one of them writes it (copy-on-write, one row at a time).
A row write ``rows[a] | mask`` costs O(w), w = ⌈width/64⌉ machine words.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
import numpy.typing as npt

__all__ = ["PairBits", "bits_of", "mask_of"]


#: Up to this many slots a mask is built by shifts, each O(w); above, through a buffer.
_SHIFTED = 64


def mask_of(slots: Sequence[int]) -> int:
    """The bit set {slots}, in O(|slots| + w).

    >>> bin(mask_of([0, 3]))
    '0b1001'
    """
    if len(slots) <= _SHIFTED:
        mask = 0
        for slot in slots:
            mask |= 1 << slot
        return mask
    buffer = bytearray((max(slots) >> 3) + 1)
    for slot in slots:
        buffer[slot >> 3] |= 1 << (slot & 7)
    return int.from_bytes(buffer, "little")


def bits_of(mask: int) -> npt.NDArray[np.intp]:
    """The set bits of ``mask``, ascending: O(width) in C, not per bit in Python.

    >>> bits_of(0b1001).tolist()
    [0, 3]
    """
    raw = np.frombuffer(mask.to_bytes((mask.bit_length() + 7) >> 3, "little"), dtype=np.uint8)
    return np.flatnonzero(np.unpackbits(raw, bitorder="little"))


class PairBits:
    """A symmetric relation on slots; see the module doc."""

    __slots__ = ("rows",)

    def __init__(self, rows: list[int] | None = None) -> None:
        self.rows: list[int] = [] if rows is None else rows

    def copy(self) -> PairBits:
        """O(n) references; the rows themselves are shared until written."""
        return PairBits(list(self.rows))

    def add_slot(self) -> None:
        """Appends an empty row for a new slot (len(rows))."""
        self.rows.append(0)

    def contains(self, a: int, b: int) -> bool:
        return bool(self.rows[a] >> b & 1)

    def any(self) -> bool:
        """True iff some pair is in the relation."""
        return any(self.rows)

    def write(
        self,
        own: Iterable[int],
        other_mask: int,
        value: bool,
        only: frozenset[int] | None = None,
    ) -> None:
        """Sets (value True) or clears the pairs own × other on the rows of ``own``.

        ``only`` restricts the write to those rows. The caller writes other × own
        as well, so that the relation stays symmetric.
        """
        rows = self.rows
        for slot in own:
            if only is None or slot in only:
                rows[slot] = rows[slot] | other_mask if value else rows[slot] & ~other_mask

    def clear_slot(self, slot: int) -> None:
        """Removes every pair with ``slot``: its row, and its bit in its partners' rows.

        By symmetry the partners are the bits of its row: O(degree · w).
        """
        rows = self.rows
        bit = 1 << slot
        for partner in bits_of(rows[slot]).tolist():
            rows[partner] &= ~bit
        rows[slot] = 0
