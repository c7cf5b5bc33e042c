"""The graph of bodies (links) and joints that Finalize reads.

Drake counterpart: drake/multibody/topology (LinkJointGraph). Bodies are
numbered by BodyIndex, 0 being the world; a joint is an edge from its parent
body to its child body. Three questions are asked of the graph:

- Does it have a loop? Finalize refuses a graph whose undirected form has a
  cycle (welds included).
- Which bodies are welded together? ``welded_subgraphs`` gives the connected
  components of the weld edges (the world's first).
- Which bodies float? Every body not connected to the world gets a floating
  joint to the world at the base of its tree; ``floating_bases`` says which
  body is the base, and in which order the trees get their joints.
- Which joints run backwards? Rooted at the world and at the floating
  bases, the trees reach some joints from their child; ``reversed_joints``
  lists them in the order Finalize models joints.

Conventions: ``n`` is the number of bodies; ``edges`` the joints, in
JointIndex order.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

__all__ = [
    "WORLD",
    "Edge",
    "Mobod",
    "floating_bases",
    "forest_mobods",
    "has_loop",
    "reversed_joints",
    "unrooted_bodies",
    "welded_subgraphs",
]

#: The world body's index.
WORLD = 0


@dataclass(frozen=True)
class Edge:
    """One joint: parent body → child body; ``is_weld`` for a WeldJoint."""

    parent: int
    child: int
    is_weld: bool


class _Partition:
    """Union-find over body indices."""

    def __init__(self, n: int) -> None:
        self._root = list(range(n))

    def find(self, body: int) -> int:
        while self._root[body] != body:
            self._root[body] = self._root[self._root[body]]
            body = self._root[body]
        return body

    def union(self, a: int, b: int) -> bool:
        """Joins the sets of a and b; False if they were already one set."""
        root_a, root_b = self.find(a), self.find(b)
        if root_a == root_b:
            return False
        self._root[max(root_a, root_b)] = min(root_a, root_b)
        return True

    def groups(self) -> list[list[int]]:
        """The sets, each sorted; ordered by their smallest body (the world's first)."""
        by_root: dict[int, list[int]] = {}
        for body in range(len(self._root)):
            by_root.setdefault(self.find(body), []).append(body)
        return sorted(by_root.values())


def _partition(n: int, edges: Iterable[Edge]) -> _Partition:
    partition = _Partition(n)
    for edge in edges:
        partition.union(edge.parent, edge.child)
    return partition


def has_loop(n: int, edges: Iterable[Edge]) -> bool:
    """True iff some joint joins two bodies already joined by other joints."""
    partition = _Partition(n)
    return not all(partition.union(edge.parent, edge.child) for edge in edges)


def welded_subgraphs(n: int, edges: Iterable[Edge]) -> list[list[int]]:
    """The bodies grouped by weld connectivity; a body with no weld is alone.

    >>> welded_subgraphs(3, [Edge(0, 2, is_weld=True), Edge(2, 1, is_weld=False)])
    [[0, 2], [1]]
    """
    return _partition(n, (edge for edge in edges if edge.is_weld)).groups()


def floating_bases(n: int, edges: Sequence[Edge]) -> list[int]:
    """The base body of each tree not connected to the world, in the order Finalize joins them.

    Measured on pydrake 1.51.1 (the policy Simbody documents for
    chooseNewBaseBody): while some tree is unjoined, take, among the bodies
    of unjoined trees that are no joint's child, the one that is the parent
    in the most joints, the lowest index on a tie. So a lone body (parent of
    nothing) comes after every tree with a joint, and bodies of a reversed
    chain C→B→A make C the base.

    >>> floating_bases(4, [Edge(2, 3, is_weld=False)])
    [2, 1]
    """
    partition = _partition(n, edges)
    parent_count = [0] * n
    is_child = [False] * n
    has_joint = [False] * n
    for edge in edges:
        parent_count[edge.parent] += 1
        is_child[edge.child] = True
        has_joint[edge.parent] = has_joint[edge.child] = True
    joined = {partition.find(WORLD)}
    bases: list[int] = []
    while True:
        unjoined = [b for b in range(n) if partition.find(b) not in joined]
        if not unjoined:
            return bases
        # Bodies with joints come before lone ones; a tree that is a loop has no
        # body that is no joint's child, and then any of its bodies may be the base
        # (measured on 1.40.0: a loop b→c→a→b beside a lone x makes a the first base).
        pool = [b for b in unjoined if has_joint[b]] or unjoined
        roots = [b for b in pool if not is_child[b]] or pool
        base = min(roots, key=lambda b: (-parent_count[b], b))
        bases.append(base)
        joined.add(partition.find(base))


def reversed_joints(n: int, edges: Sequence[Edge], bases: Sequence[int]) -> list[int]:
    """The joints (edge indices) a tree reaches from their child, in modeling order.

    The trees are rooted at the world, then at ``bases`` in order, and walked
    depth first, each body's joints taken in joint order whichever their
    direction. Measured on pydrake 1.51.1: with world→A (j0), A→B (j1),
    X→B (j2), Y→A (j3), Finalize reports j2 before j3, and with world→A (j0),
    Y→A (j1), A→B (j2), X→B (j3) it reports j1. Requires a graph without loops.

    >>> reversed_joints(3, [Edge(0, 1, is_weld=False), Edge(2, 1, is_weld=False)], [])
    [1]
    """
    incident: list[list[int]] = [[] for _ in range(n)]
    for index, edge in enumerate(edges):
        incident[edge.parent].append(index)
        incident[edge.child].append(index)
    used = [False] * len(edges)
    found: list[int] = []

    def walk(body: int) -> None:
        for index in incident[body]:
            if used[index]:
                continue
            used[index] = True
            edge = edges[index]
            if edge.child == body:
                found.append(index)
            walk(edge.parent if edge.child == body else edge.child)

    for root in (WORLD, *bases):
        walk(root)
    return found


@dataclass(frozen=True)
class Mobod:
    """A mobilized body of the forest Drake 1.33-1.40 builds: the body a joint moves,
    whether the joint is modeled reversed (child to parent), and whether the body had a
    mobilizer already (a loop closed here: Drake adds a second inboard joint)."""

    edge: int
    body: int
    reversed: bool
    again: bool


def forest_mobods(n: int, edges: Sequence[Edge], roots: Sequence[int]) -> list[Mobod]:
    """The mobods of the joints, in the depth-first order Drake 1.33-1.40 makes mobilizers.

    Each tree (rooted at ``roots`` in order) grows level by level: every body of a level
    takes its joints not yet used, in joint order, and each makes a mobod for the body at
    its other end, reversed if the body of the level is the joint's child; a body met
    again (a loop) gets a mobod again. The mobods are then visited depth first, each
    body's in the order they were made. Measured on 1.33.0 and 1.40.0 with loops
    (Finalize reports the first reversed mobod, else the first body met again).
    """
    incident: list[list[int]] = [[] for _ in range(n)]
    for index, edge in enumerate(edges):
        incident[edge.parent].append(index)
        incident[edge.child].append(index)
    used = [False] * len(edges)
    reached = [False] * n
    #: body -> its joints' (edge, other body, reversed, whether the other body is first
    #: reached here: its own outboard mobods hang under this one, not a loop's).
    outboard: dict[int, list[tuple[int, int, bool, bool]]] = {}
    for root in roots:
        reached[root] = True
        level = [root]
        while level:
            following: list[int] = []
            for body in level:
                for index in incident[body]:
                    if used[index]:
                        continue
                    used[index] = True
                    edge = edges[index]
                    reverse = edge.child == body
                    other = edge.parent if reverse else edge.child
                    outboard.setdefault(body, []).append(
                        (index, other, reverse, not reached[other])
                    )
                    if not reached[other]:
                        reached[other] = True
                        following.append(other)
            level = following
    mobods: list[Mobod] = []
    mobilized = [False] * n

    def visit(body: int) -> None:
        for index, other, reverse, first_reached in outboard.get(body, []):
            mobods.append(Mobod(index, other, reverse, mobilized[other]))
            mobilized[other] = True
            if first_reached:
                visit(other)

    for root in roots:
        visit(root)
    return mobods


def unrooted_bodies(n: int, edges: Sequence[Edge]) -> set[int]:
    """The bodies of the trees apart from the world in which every body is some joint's
    child (a loop with no way in: Drake up to 1.32 gives them no mobilizer)."""
    partition = _partition(n, edges)
    is_child = [False] * n
    for edge in edges:
        is_child[edge.child] = True
    world = partition.find(WORLD)
    rooted = {partition.find(b) for b in range(n) if not is_child[b]} | {world}
    return {b for b in range(n) if partition.find(b) not in rooted}
