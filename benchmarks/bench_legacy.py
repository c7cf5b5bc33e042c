"""Seed 003's claims, measured: per-pair test cost of masks vs cliques, and clique counts.

Table 1: ns per pair test in CPython for the bitmask formula
``(m_a & i_b) | (m_b & i_a)`` on 128-bit ints and for
``sorted_vectors_have_intersection`` as both elements' clique lists grow (n
each): the worst case (interleaved ids, no common one: a full walk), a common
id found at the end, and the short-circuit (ranges apart).

Table 2: cliques needed to filter a scenario's pairs F exactly: ``greedy``
(RBT's auto cliques plus seed 003's Cartesian product for groups, made
exact), ``cover`` (``to_cliques(F, "cover")``), the lower bound, the largest
clique list of one element (the n of the test above) and the bitmask groups
``to_groups(F)`` needs (``>127`` when it cannot fit). Scenarios: k-link
chains and trees (two collision elements per link, auto cliques) and several
7-link robots on a table whose grippers ignore every other robot's arm
(cross-robot groups).

Table 3: random pair sets over 60 elements: the cover against the lower
bounds (greedy cliques are |F|, one per pair).

Usage: python benchmarks/bench_legacy.py [--quick] [--json FILE]

``--json FILE`` writes the three tables' Markdown rows too (the committed one is
``docs/reports/bench_legacy.json``, whose tables docs/legacy-representations.md renders).
"""

from __future__ import annotations

import json
import platform
import random
import sys
import timeit
from collections.abc import Callable, Sequence
from pathlib import Path

from reimpl.legacy import (
    BodyGraph,
    CollisionCliques,
    CollisionFilterGroups,
    JointEdge,
    LegacyFilter,
    TooManyGroupsError,
    auto_cliques,
    clique_cover_lower_bound,
    group_lower_bound,
    groups_to_cliques,
    sorted_vectors_have_intersection,
    to_cliques,
    to_groups,
)

SIZES = (1, 2, 4, 8, 16, 32, 64, 128)


def ns_per_call(fn: Callable[[], object], number: int) -> float:
    return min(timeit.repeat(fn, number=number, repeat=5)) / number * 1e9


def intersection(a: list[int], b: list[int]) -> Callable[[], bool]:
    return lambda: sorted_vectors_have_intersection(a, b)


def pair_cost_table(quick: bool) -> list[str]:
    number = 20_000 if quick else 200_000
    m_a, i_a = 1 | 1 << 5 | 1 << 90, 1 << 7 | 1 << 127
    m_b, i_b = 1 | 1 << 64, 1 << 3
    mask = ns_per_call(lambda: (m_a & i_b) | (m_b & i_a), number)
    call = ns_per_call(lambda: None, number)
    rows = [
        f"(Each figure includes a Python call, {call:.0f} ns alone on this machine.)",
        "",
        "| clique ids per element (n = m) | masks (any width ≤ 128) | cliques, worst case "
        "(interleaved, no hit) | cliques, hit at the end | cliques, ranges apart |",
        "|---:|---:|---:|---:|---:|",
    ]
    for n in SIZES:
        even = list(range(0, 2 * n, 2))
        odd = list(range(1, 2 * n, 2))
        hit = [*odd[:-1], even[-1]]
        apart = list(range(2 * n, 3 * n))
        worst = ns_per_call(intersection(even, odd), number // n)
        late = ns_per_call(intersection(even, hit), number // n)
        short = ns_per_call(intersection(even, apart), number)
        rows.append(f"| {n} | {mask:.0f} ns | {worst:.0f} ns | {late:.0f} ns | {short:.0f} ns |")
    return rows


# -------------------------------------------------------------------- scenarios
def chain(
    k: int, prefix: str = "r", per_link: int = 2
) -> tuple[list[str], list[JointEdge[str]], dict[str, tuple[str, ...]]]:
    links = [f"{prefix}::l{i}" for i in range(k)]
    joints = [JointEdge(f"{prefix}_j0", "world", links[0], "revolute")]
    joints += [JointEdge(f"{prefix}_j{i}", links[i - 1], links[i], "revolute") for i in range(1, k)]
    elements = {link: tuple(f"{link}/g{e}" for e in range(per_link)) for link in links}
    return links, joints, elements


def tree(k: int, branching: int, per_link: int = 2) -> BodyGraph[str, str]:
    links = [f"t::l{i}" for i in range(k)]
    joints = [JointEdge("j0", "world", links[0], "revolute")]
    joints += [
        JointEdge(f"j{i}", links[(i - 1) // branching], links[i], "revolute") for i in range(1, k)
    ]
    elements = {link: tuple(f"{link}/g{e}" for e in range(per_link)) for link in links}
    return BodyGraph("world", ("world", *links), elements, tuple(joints))


def single_chain(k: int) -> tuple[BodyGraph[str, str], CollisionFilterGroups[str]]:
    links, joints, elements = chain(k)
    return BodyGraph("world", ("world", *links), elements, tuple(joints)), CollisionFilterGroups()


def robots(count: int, k: int = 7) -> tuple[BodyGraph[str, str], CollisionFilterGroups[str]]:
    """``count`` k-link arms; robot i's gripper (its last two links) ignores every other
    robot's arm group (all its links)."""
    bodies: list[str] = ["world"]
    joints: list[JointEdge[str]] = []
    elements: dict[str, tuple[str, ...]] = {"world": ("world/table",)}
    groups: CollisionFilterGroups[str] = CollisionFilterGroups()
    for r in range(count):
        links, chain_joints, chain_elements = chain(k, f"r{r}")
        bodies += links
        joints += chain_joints
        elements |= chain_elements
        groups.define_group(f"arm{r}")
        groups.define_group(f"gripper{r}")
        for link in links:
            for e in chain_elements[link]:
                groups.add_member(f"arm{r}", e)
        for link in links[-2:]:
            for e in chain_elements[link]:
                groups.add_member(f"gripper{r}", e)
    for r in range(count):
        for other in range(count):
            if other != r:
                groups.ignore(f"gripper{r}", f"arm{other}")
    return BodyGraph("world", tuple(bodies), elements, tuple(joints)), groups


def merged(parts: Sequence[CollisionCliques[str]]) -> CollisionCliques[str]:
    result: CollisionCliques[str] = CollisionCliques()
    for cliques in parts:
        for q in range(cliques.num_cliques):
            clique = result.new_clique()
            for e in cliques.members(q):
                result.add_to_clique(e, clique)
    return result


def clique_row(name: str, graph: BodyGraph[str, str], groups: CollisionFilterGroups[str]) -> str:
    elements = graph.all_elements()
    auto = auto_cliques(graph)
    pairs = LegacyFilter(groups, auto).filtered_pairs(elements)
    greedy = merged([auto, groups_to_cliques(groups, elements, "greedy")])
    cover = to_cliques(pairs, elements, "cover")
    assert greedy.filtered_pairs(elements) == pairs == cover.filtered_pairs(elements)
    bound = clique_cover_lower_bound(pairs, elements)
    try:
        bits = str(to_groups(pairs, elements).num_groups)
    except TooManyGroupsError:
        bits = ">127"
    return (
        f"| {name} | {len(elements)} | {len(pairs)} | {greedy.num_cliques} "
        f"({greedy.max_cliques_per_element()}) | {cover.num_cliques} "
        f"({cover.max_cliques_per_element()}) | {bound} | {bits} |"
    )


def clique_count_table(quick: bool) -> list[str]:
    rows = [
        "| scenario | elements | filtered pairs | greedy cliques (max per element) "
        "| cover cliques (max per element) | lower bound | groups (to_groups) |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for k in (5, 10, 50) if quick else (5, 10, 50, 100, 200):
        rows.append(clique_row(f"{k}-link chain", *single_chain(k)))
    for k, branching in ((15, 2), (40, 3)) if quick else ((15, 2), (63, 2), (40, 3), (121, 3)):
        rows.append(
            clique_row(
                f"{k}-link tree, branching {branching}", tree(k, branching), CollisionFilterGroups()
            )
        )
    for count in (2, 4) if quick else (2, 4, 8):
        rows.append(clique_row(f"{count} robots × 7 links, cross-robot groups", *robots(count)))
    return rows


def random_table(quick: bool) -> list[str]:
    """Random pair sets over 60 elements: how far the cover is from the lower bounds."""
    rows = [
        "| density | filtered pairs (mean) | greedy cliques | cover cliques | lower bound "
        "| cover / bound | groups (to_groups) | group lower bound |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    rng = random.Random(0)
    samples = 5 if quick else 20
    elements = list(range(60))
    for density in (0.05, 0.2, 0.5, 0.8):
        totals = [0.0] * 6
        for _ in range(samples):
            pairs = {
                frozenset((a, b))
                for a in elements
                for b in elements
                if a < b and rng.random() < density
            }
            cover = to_cliques(pairs, elements, "cover").num_cliques
            values = (
                len(pairs),
                cover,
                clique_cover_lower_bound(pairs, elements),
                to_groups(pairs, elements).num_groups,
                group_lower_bound(pairs, elements),
            )
            totals = [t + v for t, v in zip(totals, (*values, cover / values[2]), strict=True)]
        f, cover_mean, bound, groups, group_bound, ratio = (t / samples for t in totals)
        rows.append(
            f"| {density} | {f:.0f} | {f:.0f} | {cover_mean:.1f} | {bound:.1f} | {ratio:.2f} "
            f"| {groups:.1f} | {group_bound:.1f} |"
        )
    return rows


def main(argv: Sequence[str]) -> int:
    quick = "--quick" in argv
    json_path = argv[argv.index("--json") + 1] if "--json" in argv else None
    random.seed(0)
    tables = {"pair_cost": pair_cost_table(quick)}
    print("Per-pair test cost (CPython, ns per test; lower is better)\n")
    print("\n".join(tables["pair_cost"]))
    tables["cliques"] = clique_count_table(quick)
    print("\nCliques needed for an exact mapping (greedy vs cover)\n")
    print("\n".join(tables["cliques"]))
    tables["random"] = random_table(quick)
    print("\nRandom pair sets over 60 elements (20 per density): cover against the lower bounds\n")
    print("\n".join(tables["random"]))
    if json_path is not None:
        report = {"python": platform.python_version(), "quick": quick, "tables": tables}
        Path(json_path).write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
