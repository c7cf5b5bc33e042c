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
    "floating_bases",
    "has_loop",
    "reversed_joints",
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
    for edge in edges:
        parent_count[edge.parent] += 1
        is_child[edge.child] = True
    joined = {partition.find(WORLD)}
    bases: list[int] = []
    while True:
        unjoined = [b for b in range(n) if partition.find(b) not in joined]
        if not unjoined:
            return bases
        # N.B. Without loops every tree has a body that is no joint's child.
        roots = [b for b in unjoined if not is_child[b]] or unjoined
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
