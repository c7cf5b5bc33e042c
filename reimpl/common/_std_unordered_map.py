"""The iteration order of libstdc++'s ``std::unordered_map`` (64-bit).

Drake keeps geometry properties in ``unordered_map<std::string, T>``, so
pydrake prints groups and lists a group's properties in this order, and keeps
its sources in ``unordered_map<SourceId, T>``, so of several sources whose
poses are missing it names the one this order walks first. The order is
deterministic: it depends on the keys' hashes, the bucket count (grown by the
prime rehash policy, maximum load factor 1), and the insertion history.

========================  ====================================================
key                        hash, as measured against pydrake 1.51.1 and 1.58
========================  ====================================================
``str``                    ``std::hash<std::string>``: a MurmurHash2 variant
                           seeded with 0xc70f6907, over the UTF-8 bytes
                           (tests/upstream/test_common_upstream.py)
an Identifier              FNV-1a (64-bit) over the 8 little-endian bytes of
(``SourceId``,             its value (250 of 250 random source sets, with
``FrameId``)               SceneGraph's own source as the first key; 100 of
                           100 random frame sets of one source; in
                           tests/test_query_object.py)
========================  ====================================================

The order rules, as observed: a key whose bucket already holds keys goes in
front of them; a key in an empty bucket goes to the front of the whole list.
A rehash re-inserts every key, in the current order, by the same rule. An
erase removes the key and leaves the others in place. A copy keeps the order.
"""

from __future__ import annotations

import bisect
import functools
from collections.abc import Iterable, Iterator, MutableMapping
from typing import Generic, Protocol, Self, TypeVar

from reimpl._release import release

__all__ = [
    "MAP_AT_MESSAGE",
    "IdentifierUnorderedMap",
    "StdUnorderedMap",
    "fnv1a_int64_hash",
    "identifier_set_order",
    "std_string_hash",
]


class _Identifier(Protocol):
    def get_value(self) -> int: ...


K = TypeVar("K")
I = TypeVar("I", bound=_Identifier)  # noqa: E741
V = TypeVar("V")

_MASK = (1 << 64) - 1
_MUL = (0xC6A4A793 << 32) + 0x5BD1E995
_SEED = 0xC70F6907


def _shift_mix(v: int) -> int:
    return v ^ (v >> 47)


@functools.lru_cache(maxsize=1 << 14)
def std_string_hash(key: str) -> int:
    """``std::hash<std::string>`` of the UTF-8 bytes of ``key``."""
    data = key.encode()
    length = len(data)
    aligned = length & ~0x7
    h = (_SEED ^ (length * _MUL)) & _MASK
    for i in range(0, aligned, 8):
        word = int.from_bytes(data[i : i + 8], "little")
        h ^= (_shift_mix((word * _MUL) & _MASK) * _MUL) & _MASK
        h = (h * _MUL) & _MASK
    if length & 0x7:
        h ^= int.from_bytes(data[aligned:], "little")
        h = (h * _MUL) & _MASK
    h = (_shift_mix(h) * _MUL) & _MASK
    return _shift_mix(h)


_FNV_OFFSET = 0xCBF29CE484222325
_FNV_PRIME = 0x100000001B3


@functools.lru_cache(maxsize=1 << 14)
def fnv1a_int64_hash(value: int) -> int:
    """FNV-1a (64-bit) of ``value`` as 8 little-endian bytes: how Drake hashes an Identifier."""
    h = _FNV_OFFSET
    for byte in (value & _MASK).to_bytes(8, "little"):
        h = ((h ^ byte) * _FNV_PRIME) & _MASK
    return h


# The bucket counts the policy picks from: small requests through a fast table,
# larger ones from libstdc++'s list of primes.
_FAST_BUCKETS = (2, 2, 2, 3, 5, 5, 7, 7, 11, 11, 11, 11, 13, 13)
_PRIMES = (
    17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89, 97, 103, 109,
    113, 127, 137, 139, 149, 157, 167, 179, 193, 199, 211, 227, 241, 257, 277, 293, 313,
    337, 359, 383, 409, 439, 467, 503, 541, 577, 619, 661, 709, 761, 823, 887, 953, 1031,
    1109, 1187, 1277, 1361, 1459, 1567, 1693, 1823, 1949, 2087, 2237, 2399, 2579, 2767,
    2963, 3187, 3407, 3659, 3923, 4201, 4513, 4831, 5189, 5573, 5981, 6421, 6883, 7393,
    7919, 8513, 9127, 9791,
)  # fmt: skip


def _next_bucket_count(n: int) -> int:
    if n < len(_FAST_BUCKETS):
        return 1 if n == 0 else _FAST_BUCKETS[n]
    return _PRIMES[min(bisect.bisect_left(_PRIMES, n), len(_PRIMES) - 1)]


class _UnorderedMap(MutableMapping[K, V], Generic[K, V]):
    """A mapping that iterates in libstdc++'s unordered_map order for ``_hash``."""

    def __init__(self) -> None:
        self._values: dict[K, V] = {}
        self._order: list[K] = []
        self._buckets = 1
        self._next_resize = 0

    @staticmethod
    def _hash(key: K) -> int:
        raise NotImplementedError

    def copy(self) -> Self:
        other = object.__new__(type(self))
        other._values = dict(self._values)
        other._order = list(self._order)
        other._buckets = self._buckets
        other._next_resize = self._next_resize
        return other

    def _link(self, order: list[K], key: K, buckets: int) -> None:
        hash_of = self._hash  # memoised: each key's hash is computed once
        bucket = hash_of(key) % buckets
        for i, other in enumerate(order):
            if hash_of(other) % buckets == bucket:
                order.insert(i, key)
                return
        order.insert(0, key)

    def _grow_for(self, count: int) -> None:
        """The prime rehash policy, asked before ``count``-th element is inserted."""
        if count <= self._next_resize:
            return
        # N.B. The first insertion asks for at least 11 buckets.
        wanted = max(count, 11 if self._next_resize == 0 else 0)
        if wanted >= self._buckets:
            buckets = _next_bucket_count(max(wanted + 1, self._buckets * 2))
            self._next_resize = buckets
            order: list[K] = []
            for key in self._order:
                self._link(order, key, buckets)
            self._order = order
            self._buckets = buckets
        else:
            self._next_resize = self._buckets

    def __setitem__(self, key: K, value: V) -> None:
        if key not in self._values:
            self._grow_for(len(self._values) + 1)
            self._link(self._order, key, self._buckets)
        self._values[key] = value

    def __getitem__(self, key: K) -> V:
        return self._values[key]

    def __contains__(self, key: object) -> bool:
        return key in self._values

    def __delitem__(self, key: K) -> None:
        del self._values[key]
        self._order.remove(key)

    def __iter__(self) -> Iterator[K]:
        return iter(list(self._order))

    def __len__(self) -> int:
        return len(self._values)

    def __repr__(self) -> str:
        items = ", ".join(f"{k!r}: {self._values[k]!r}" for k in self._order)
        return f"{type(self).__name__}({{{items}}})"


class StdUnorderedMap(_UnorderedMap[str, V]):
    """A str-keyed mapping in the order of ``std::unordered_map<std::string, T>``."""

    @staticmethod
    def _hash(key: str) -> int:
        return std_string_hash(key)


class IdentifierUnorderedMap(_UnorderedMap[I, V]):
    """An Identifier-keyed mapping in the order of ``std::unordered_map<SourceId, T>``."""

    @staticmethod
    def _hash(key: I) -> int:
        return fnv1a_int64_hash(key.get_value())


def identifier_set_order(keys: Iterable[I]) -> list[I]:
    """The order of an ``unordered_set`` of Identifiers after inserting ``keys`` in order."""
    walk: IdentifierUnorderedMap[I, None] = IdentifierUnorderedMap()
    for key in keys:
        walk[key] = None
    return list(walk)


#: What ``std::unordered_map::at`` says of a missing key (pydrake: IndexError): the C++
#: standard library of Drake's wheels words it '_Map_base::at' up to 1.51.1 and
#: 'unordered_map::at' since 1.52 (the release fact clone-error-wording-since-1.52).
MAP_AT_MESSAGE = (
    "unordered_map::at" if release.has("clone-error-wording-since-1.52") else "_Map_base::at"
)
