"""Exact mappings between pairwise filters, bitmask groups and cliques (seed 003).

Every mapping here is *exact*: the pair set it filters over ``elements`` is
the pair set it was given, ``F``. Conventions: ``F`` is a set of unordered
pairs ``{a, b}`` (``a ≠ b``) over ``elements``; ``N(a)`` is a's neighbours in
the graph whose edges are ``F``.

- A clique ``Q`` filters ``{(a, b) : a, b ∈ Q, a ≠ b}``, so cliques are an
  *edge clique cover* of F: every clique must lie inside F and every pair of
  F inside some clique.
- A group pair (G ignores H) filters ``G × H``, so groups are a cover of F by
  bicliques ``G × H`` (and cliques ``G × G``), named by at most 127 bits.

``groups_to_cliques(method="greedy")`` is seed 003's Cartesian product: for G
ignoring H, one clique per member a of G holding a and H. N.B. Read
literally that over-filters: the clique ``{a} ∪ H`` also filters the pairs
*inside* H, which G ignoring H does not (in the seed's example, body3 and
body4). The exact greedy mapping uses ``{a} ∪ H`` only when H's own pairs are
in F anyway (or ``{h} ∪ G`` per member of H when G's are), and otherwise one
clique ``{a, h}`` per pair of the product. ``method="cover"`` computes a
small edge clique cover of F instead (greedy growth from each uncovered pair,
then redundant cliques dropped); ``clique_cover_lower_bound`` bounds the
optimum from below (pairs no two of which fit in one clique; the
independence of a neighbourhood), so a cover's distance from optimal is
known.

``to_groups`` takes the smaller of two exact encodings: one group per class
of twins (elements with the same neighbourhood filter the same pairs), and a
greedy cover of the twin classes by cliques (one self-ignoring group) and
bicliques (two groups); elements filtered against every other element share
one group that ignores bit 0 when that is smaller. ``group_lower_bound``
bounds the groups any encoding needs (a fooling set of F's matrix, minus the
universal bit).
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable, Iterator, Sequence
from typing import Any, Literal, TypeVar

from reimpl.legacy._errors import MappingInputError, TooManyGroupsError
from reimpl.legacy.collision_cliques import CollisionCliques
from reimpl.legacy.collision_filter_groups import UNIVERSAL, CollisionFilterGroups

__all__ = [
    "METHODS",
    "Method",
    "clique_cover_lower_bound",
    "group_lower_bound",
    "groups_to_cliques",
    "to_cliques",
    "to_groups",
]

E = TypeVar("E", bound=Hashable)

Method = Literal["greedy", "cover"]
METHODS: tuple[Method, ...] = ("greedy", "cover")

#: The user groups a 128-bit mask holds (bit 0 is the universal group).
USER_GROUPS = CollisionFilterGroups.MAX_GROUPS - 1


# ----------------------------------------------------------------- the graph
def _bits(mask: int) -> Iterator[int]:
    """The indices of the set bits of ``mask``, lowest first."""
    while mask:
        low = mask & -mask
        yield low.bit_length() - 1
        mask ^= low


class _Graph:
    """``elements`` as indices 0..n-1 and F as adjacency bitsets (``adj[i]`` = N(i))."""

    def __init__(self, pairs: Iterable[Iterable[Any]], elements: Iterable[Any]) -> None:
        self.elements = list(dict.fromkeys(elements))
        index = {e: i for i, e in enumerate(self.elements)}
        self.adj = [0] * len(self.elements)
        for pair in pairs:
            items = tuple(pair)
            if len(items) != 2 or items[0] == items[1]:
                raise MappingInputError(f"a filtered pair must be two distinct elements: {items!r}")
            missing = [e for e in items if e not in index]
            if missing:
                raise MappingInputError(
                    f"the pair {items!r} names {missing[0]!r}, which is not among the elements"
                )
            i, j = index[items[0]], index[items[1]]
            self.adj[i] |= 1 << j
            self.adj[j] |= 1 << i

    @property
    def n(self) -> int:
        return len(self.elements)

    def edges(self) -> list[tuple[int, int]]:
        return [(i, j) for i in range(self.n) for j in _bits(self.adj[i] >> i << i) if j > i]

    def is_clique(self, mask: int) -> bool:
        return all(mask & ~(1 << x) & ~self.adj[x] == 0 for x in _bits(mask))


def _check_method(method: str) -> None:
    if method not in METHODS:
        raise MappingInputError(f"unknown method {method!r}: use one of {', '.join(METHODS)}")


def _cliques_from_masks(graph: _Graph, masks: Iterable[int]) -> CollisionCliques[Any]:
    cliques: CollisionCliques[Any] = CollisionCliques()
    for mask in masks:
        clique = cliques.new_clique()
        for i in _bits(mask):
            cliques.add_to_clique(graph.elements[i], clique)
    return cliques


# --------------------------------------------------------------- to cliques
def _clique_cover(graph: _Graph) -> list[int]:
    """A small edge clique cover of F, as vertex bitmasks.

    From the first vertex with an uncovered pair (i, j), grow {i, j} by the
    common neighbour that covers the most uncovered pairs with the clique so
    far (ties: the one with the most neighbours among the candidates, then the
    lowest index); a vertex that would cover nothing new is not added (it would
    only lengthen its clique list). Then drop cliques, smallest first, whose
    pairs all lie in other cliques.
    """
    uncovered = graph.adj[:]
    cliques: list[int] = []
    for i in range(graph.n):
        while uncovered[i]:
            j = (uncovered[i] & -uncovered[i]).bit_length() - 1
            clique = 1 << i | 1 << j
            candidates = graph.adj[i] & graph.adj[j]
            while candidates:
                best, best_key = -1, (0, 0)
                for w in _bits(candidates):
                    gain = (uncovered[w] & clique).bit_count()
                    if gain == 0:
                        continue
                    key = (gain, (graph.adj[w] & candidates).bit_count())
                    if key > best_key:
                        best, best_key = w, key
                if best < 0:
                    break
                clique |= 1 << best
                candidates &= graph.adj[best]
            for v in _bits(clique):
                uncovered[v] &= ~clique
            cliques.append(clique)
    return _drop_redundant(cliques)


def _pairs_of(mask: int) -> list[tuple[int, int]]:
    members = list(_bits(mask))
    return [(a, b) for k, a in enumerate(members) for b in members[k + 1 :]]


def _drop_redundant(cliques: list[int]) -> list[int]:
    count: dict[tuple[int, int], int] = {}
    for clique in cliques:
        for pair in _pairs_of(clique):
            count[pair] = count.get(pair, 0) + 1
    keep = [True] * len(cliques)
    for k in sorted(range(len(cliques)), key=lambda k: (cliques[k].bit_count(), k)):
        pairs = _pairs_of(cliques[k])
        if all(count[p] > 1 for p in pairs):
            keep[k] = False
            for p in pairs:
                count[p] -= 1
    return [c for c, kept in zip(cliques, keep, strict=True) if kept]


def to_cliques(
    filtered_pairs: Iterable[Iterable[E]], elements: Iterable[E], method: Method = "cover"
) -> CollisionCliques[E]:
    """Cliques whose filtered pairs over ``elements`` are exactly ``filtered_pairs``.

    ``greedy``: the Cartesian product pair by pair, one clique {a, b} per pair
    (|F| cliques; an element is in deg(a) of them). ``cover``: the edge clique
    cover of the module doc.

    Raises:
        MappingInputError: a pair is not two distinct elements of ``elements``,
            or ``method`` is unknown.

    >>> to_cliques([{1, 2}, {2, 3}, {1, 3}], [1, 2, 3]).num_cliques
    1
    """
    _check_method(method)
    graph = _Graph(filtered_pairs, elements)
    if method == "greedy":
        return _cliques_from_masks(graph, (1 << i | 1 << j for i, j in graph.edges()))
    return _cliques_from_masks(graph, _clique_cover(graph))


def groups_to_cliques(
    groups: CollisionFilterGroups[E], elements: Iterable[E], method: Method = "greedy"
) -> CollisionCliques[E]:
    """Cliques that filter exactly the pairs ``groups`` filters over ``elements``.

    ``greedy`` is seed 003's Cartesian product, made exact (module doc); a
    group ignoring itself is one clique of its members, and a group ignoring
    bit 0 pairs its members with every element. ``cover`` maps the groups'
    pair set with ``to_cliques(..., "cover")``.
    """
    _check_method(method)
    listed = list(dict.fromkeys(elements))
    if method == "cover":
        return to_cliques(groups.filtered_pairs(listed), listed, "cover")
    graph = _Graph(groups.filtered_pairs(listed), listed)
    index = {e: i for i, e in enumerate(listed)}
    everyone = (1 << len(listed)) - 1

    def members(bit: int) -> int:
        if bit == UNIVERSAL:
            return everyone
        mask = 0
        for e in groups.members(bit):
            if e in index:
                mask |= 1 << index[e]
        return mask

    masks: dict[int, None] = {}  # ordered, deduplicated
    done: set[frozenset[int]] = set()
    for g in groups.bits():
        for h in groups.ignored_bits(g):
            if frozenset((g, h)) in done:
                continue
            done.add(frozenset((g, h)))
            for clique in _product_cliques(graph, members(g), members(h), same=g == h):
                masks[clique] = None
    return _cliques_from_masks(graph, masks)


def _product_cliques(graph: _Graph, a: int, b: int, *, same: bool) -> list[int]:
    """Cliques covering A × B: stars {a} ∪ B when B's own pairs are filtered, else
    {b} ∪ A when A's are, else one clique per pair."""
    if same:
        return [a] if a.bit_count() > 1 else []
    if graph.is_clique(b):
        stars = [1 << x | b for x in _bits(a)]
    elif graph.is_clique(a):
        stars = [1 << y | a for y in _bits(b)]
    else:
        stars = [1 << x | 1 << y for x in _bits(a) for y in _bits(b) if x != y]
    return [s for s in stars if s.bit_count() > 1]


def clique_cover_lower_bound(filtered_pairs: Iterable[Iterable[E]], elements: Iterable[E]) -> int:
    """A lower bound on the cliques any exact mapping of ``filtered_pairs`` needs.

    The larger of: a set of pairs no two of which fit in one clique (greedy,
    pairs with the fewest common neighbours first: a pair in no triangle needs
    a clique of its own), and, for any element a, an independent set of N(a)
    (each clique through a holds at most one of them).
    """
    graph = _Graph(filtered_pairs, elements)
    edges = graph.edges()
    closed = {(i, j): graph.adj[i] & graph.adj[j] | 1 << i | 1 << j for i, j in edges}
    chosen: list[tuple[int, int]] = []
    for e in sorted(edges, key=lambda e: (closed[e].bit_count(), e)):
        mask = 1 << e[0] | 1 << e[1]
        if all(
            not (mask & ~closed[f] == 0 and (1 << f[0] | 1 << f[1]) & ~closed[e] == 0)
            for f in chosen
        ):
            chosen.append(e)
    independent = max((_independent_set(graph, graph.adj[v]) for v in range(graph.n)), default=0)
    return max(len(chosen), independent)


def _independent_set(graph: _Graph, within: int) -> int:
    """The size of a greedy independent set of ``within`` (fewest neighbours first)."""
    size = 0
    while within:
        v = min(_bits(within), key=lambda x: ((graph.adj[x] & within).bit_count(), x))
        within &= ~(graph.adj[v] | 1 << v)
        size += 1
    return size


# ---------------------------------------------------------------- to groups
#: An encoding: the member mask of each group, and unordered ignore pairs of group
#: slots (a slot ``-1`` is the universal group).
_Encoding = tuple[list[int], set[tuple[int, int]]]


def _twin_classes(graph: _Graph, adj: Sequence[int]) -> list[int]:
    """Classes of elements with an edge: same open neighbourhood (not adjacent to each
    other), then same closed neighbourhood (all adjacent), in element order."""
    by_open: dict[int, int] = {}
    for v in range(graph.n):
        if adj[v]:
            by_open[adj[v]] = by_open.get(adj[v], 0) | 1 << v
    classes = [m for m in by_open.values() if m.bit_count() > 1]
    by_closed: dict[int, int] = {}
    for m in by_open.values():
        if m.bit_count() == 1:
            v = m.bit_length() - 1
            key = adj[v] | 1 << v
            by_closed[key] = by_closed.get(key, 0) | m
    classes.extend(by_closed.values())
    return sorted(classes, key=lambda m: m & -m)


def _quotient_encoding(graph: _Graph, adj: Sequence[int], classes: list[int]) -> _Encoding:
    """One group per twin class; classes joined by F ignore each other; a class of
    mutually filtered twins ignores itself."""
    reps = [m.bit_length() - 1 for m in classes]
    relation: set[tuple[int, int]] = set()
    for x, rx in enumerate(reps):
        if classes[x].bit_count() > 1 and adj[rx] & classes[x]:
            relation.add((x, x))
        for y in range(x + 1, len(reps)):
            if adj[rx] >> reps[y] & 1:
                relation.add((x, y))
    return list(classes), relation


class _ClassCover:
    """A greedy cover of the twin classes' graph by cliques (one self-ignoring group)
    and bicliques (two groups), scored by pairs covered per group.

    ``cadj[x]``: the classes joined to class x by F; ``loop[x]``: x's members are
    filtered among themselves; ``uncovered[x]``: the joined classes (and x itself,
    for a loop) whose pairs no chosen group covers yet.
    """

    def __init__(self, adj: Sequence[int], classes: list[int]) -> None:
        k = len(classes)
        reps = [m.bit_length() - 1 for m in classes]
        self.classes = classes
        self.cadj = [
            sum(1 << y for y in range(k) if y != x and adj[reps[x]] >> reps[y] & 1)
            for x in range(k)
        ]
        self.loop = [
            classes[x].bit_count() > 1 and bool(adj[reps[x]] & classes[x]) for x in range(k)
        ]
        self.cliqueable = sum(
            1 << x for x in range(k) if self.loop[x] or classes[x].bit_count() == 1
        )
        self.uncovered = [self.cadj[x] | (1 << x if self.loop[x] else 0) for x in range(k)]
        self.groups: list[int] = []
        self.relation: set[tuple[int, int]] = set()

    def encoding(self) -> _Encoding:
        for x in range(len(self.classes)):
            while self.uncovered[x]:
                y = (self.uncovered[x] & -self.uncovered[x]).bit_length() - 1
                clique = self._grow_clique(x, y)
                biclique = self._grow_biclique(x, y) if x != y else None
                clique_gain = self._clique_gain(clique) if clique else 0
                if biclique is not None and (
                    not clique or 2 * clique_gain < self._biclique_gain(*biclique)
                ):
                    self._take_biclique(*biclique)
                else:
                    self._take_clique(clique)
        return self.groups, self.relation

    def _slot(self, class_mask: int) -> int:
        members = 0
        for x in _bits(class_mask):
            members |= self.classes[x]
        if members not in self.groups:
            self.groups.append(members)
        return self.groups.index(members)

    def _take_clique(self, clique: int) -> None:
        s = self._slot(clique)
        self.relation.add((s, s))
        for v in _bits(clique):
            self.uncovered[v] &= ~clique

    def _take_biclique(self, p: int, q: int) -> None:
        first, second = sorted((self._slot(p), self._slot(q)))
        self.relation.add((first, second))
        for v in _bits(p):
            self.uncovered[v] &= ~q
        for v in _bits(q):
            self.uncovered[v] &= ~p

    def _own(self, w: int) -> int:
        """1 if w's own pairs are filtered and not yet covered."""
        return 1 if self.loop[w] and self.uncovered[w] >> w & 1 else 0

    def _clique_gain(self, clique: int) -> int:
        pairs = sum((self.uncovered[v] & clique & ~(1 << v)).bit_count() for v in _bits(clique))
        return pairs // 2 + sum(self._own(v) for v in _bits(clique))

    def _biclique_gain(self, p: int, q: int) -> int:
        return sum((self.uncovered[v] & q).bit_count() for v in _bits(p))

    def _grow_clique(self, x: int, y: int) -> int:
        """A clique of classes holding x and y (0 if they cannot share a self-ignoring group)."""
        if not (self.cliqueable >> x & 1 and self.cliqueable >> y & 1):
            return 0
        clique = 1 << x | 1 << y
        candidates = self.cadj[x] & (self.cadj[y] if x != y else -1) & self.cliqueable
        while candidates:
            best, best_gain = -1, 0
            for w in _bits(candidates):
                gain = (self.uncovered[w] & clique).bit_count() + self._own(w)
                if gain > best_gain:
                    best, best_gain = w, gain
            if best < 0:
                break
            clique |= 1 << best
            candidates &= self.cadj[best]
        return clique

    def _grow_biclique(self, x: int, y: int) -> tuple[int, int]:
        """A biclique P × Q of classes with x ∈ P, y ∈ Q, grown by the best uncovered gain."""
        p, q = 1 << x, 1 << y
        while True:
            best, best_gain, to_p = -1, 0, True
            for side, other in ((True, q), (False, p)):  # P grows by classes joined to all Q.
                for w in _bits(self._common(other) & ~p & ~q):
                    gain = (self.uncovered[w] & other).bit_count()
                    if gain > best_gain:
                        best, best_gain, to_p = w, gain, side
            if best < 0:
                return p, q
            if to_p:
                p |= 1 << best
            else:
                q |= 1 << best

    def _common(self, mask: int) -> int:
        """The classes joined to every class of ``mask``."""
        common = -1
        for v in _bits(mask):
            common &= self.cadj[v]
        return 0 if common == -1 else common


def _encodings(graph: _Graph) -> list[_Encoding]:
    """The candidate encodings: twin classes and the cover, with and without an
    invisible group for the elements filtered against all others."""
    n = graph.n
    everyone = (1 << n) - 1
    invisible = 0
    if n > 1:
        for v in range(n):
            if graph.adj[v] == everyone & ~(1 << v):
                invisible |= 1 << v
    options: list[tuple[int, list[int]]] = [(0, graph.adj)]
    if invisible:
        rest = everyone & ~invisible
        options.append((invisible, [graph.adj[v] & rest if rest >> v & 1 else 0 for v in range(n)]))
    encodings: list[_Encoding] = []
    for hidden, adj in options:
        classes = _twin_classes(graph, adj)
        for groups, relation in (
            _quotient_encoding(graph, adj, classes),
            _ClassCover(adj, classes).encoding(),
        ):
            if hidden:
                encodings.append(([*groups, hidden], {*relation, (len(groups), -1)}))
            else:
                encodings.append((groups, relation))
    return encodings


def to_groups(
    filtered_pairs: Iterable[Iterable[E]], elements: Iterable[E]
) -> CollisionFilterGroups[E]:
    """Groups whose filtered pairs over ``elements`` are exactly ``filtered_pairs``.

    The smaller of the module doc's encodings; groups are named ``g1``, ``g2``
    ... (bits 1, 2, ...; ``invisible`` for a group ignoring bit 0), each group
    of a filtered pair of groups ignores the other (as seed 003 sets both
    ignores), and the session stays open.

    Raises:
        TooManyGroupsError: the encoding needs more than 127 user groups
            (the message gives ``group_lower_bound`` too).
        MappingInputError: a pair is not two distinct elements of ``elements``.

    >>> to_groups([{1, 3}, {1, 4}, {2, 3}, {2, 4}], [1, 2, 3, 4]).num_groups
    2
    """
    graph = _Graph(filtered_pairs, elements)
    groups, relation = min(_encodings(graph), key=lambda enc: len(enc[0]))
    if len(groups) > USER_GROUPS:
        bound = _group_lower_bound(graph)
        raise TooManyGroupsError(
            f"to_groups: this pair set needs {len(groups)} user groups with the best "
            f"encoding found (any encoding needs at least {bound}), but a "
            f"{CollisionFilterGroups.MAX_GROUPS}-bit mask holds {USER_GROUPS} besides the "
            "universal bit 0; map it to cliques (to_cliques) instead."
        )
    result: CollisionFilterGroups[E] = CollisionFilterGroups()
    invisible = {s for s, t in relation if t == -1}  # At most one: the last slot.
    names = ["invisible" if s in invisible else f"g{s + 1}" for s in range(len(groups))]
    bits = [result.define_group(name) for name in names]
    for s, members in enumerate(groups):
        for v in _bits(members):
            result.add_member(bits[s], graph.elements[v])
    for s, t in sorted(relation):
        if t == -1:
            result.ignore(bits[s], UNIVERSAL)
        else:
            result.ignore(bits[s], bits[t])
            result.ignore(bits[t], bits[s])
    return result


def group_lower_bound(filtered_pairs: Iterable[Iterable[E]], elements: Iterable[E]) -> int:
    """A lower bound on the user groups any exact bitmask encoding needs.

    With membership vectors x_a (bit 0 set for all), the filtered-pair matrix
    is the Boolean product X R Xᵀ, so its Boolean rank is at most the groups
    plus one; a fooling set of its 1-entries bounds that rank from below (the
    diagonal, self pairs, counts as 1).
    """
    return _group_lower_bound(_Graph(filtered_pairs, elements))


def _group_lower_bound(graph: _Graph) -> int:
    entries = sorted(
        ((r, c) for r in range(graph.n) for c in _bits(graph.adj[r])),
        key=lambda rc: ((graph.adj[rc[0]] | graph.adj[rc[1]]).bit_count(), rc),
    )

    def one(r: int, c: int) -> bool:
        return r == c or bool(graph.adj[r] >> c & 1)

    chosen: list[tuple[int, int]] = []
    for r, c in entries:
        if all(not one(r, c2) or not one(r2, c) for r2, c2 in chosen):
            chosen.append((r, c))
    if not chosen:
        return 0
    return max(1, len(chosen) - 1)
