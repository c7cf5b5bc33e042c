"""One URDF under RigidBodyTree's filtering and under today's Drake, pair by pair.

The legacy side is ``reimpl.legacy``: the unprefixed groups, the auto cliques
(seed 002) and the anchored-pair rule, over the URDF's collision elements.
The modern side is a backend (by default pydrake) that runs the scenario ops
``add_models`` and ``finalize`` and reports its candidates with
``observe()``; geometries are named ``<model>::<body>/<geometry>`` on both
sides (``conformance._backends.multibody``).

Each pair the two sides classify differently is explained by the rules
whose differences produce it:

- **world adjacency**: RBT put a body jointed to the world (not floating) in
  a clique with the world; MultibodyPlant skips joints whose parent is the world;
- **welded subgraphs**: MultibodyPlant filters every pair inside a set of
  bodies welded together; RBT only adjacent pairs (and pairs anchored to the world);
- **floating joints**: RBT made no adjacency clique across a floating joint,
  and read no ``<drake:joint>`` (its child hung from the world by a floating
  base), where MultibodyPlant filters the joint's bodies;
- **group syntax**: the unprefixed ``<collision_filter_group>`` is silently
  ignored by today's parser, and RBT did not read ``drake:`` groups;
- **anchored pairs**: RBT excluded every pair of elements rigidly fixed to the world.

A pair no rule explains is listed as **unexplained** (a gap in this model of
the two systems). The modern side's names must match the legacy elements'
(Drake's geometry names, ``reimpl.legacy.urdf``); a mismatch is an error.
"""

from __future__ import annotations

import enum
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from conformance._backends.calls import call
from conformance.protocol import (
    MODEL,
    Backend,
    BackendId,
    Command,
    Observation,
    Pair,
    Result,
    UnknownNameError,
    backend_id,
)
from reimpl.legacy import LegacyError, LegacyModel, format_mask, legacy_model, load_legacy_urdf
from reimpl.legacy.urdf import WORLD_BODY, UrdfGroup, UrdfJoint

__all__ = [
    "Difference",
    "Explanation",
    "LegacyDiff",
    "LegacyDiffError",
    "Rule",
    "legacy_diff",
]


class LegacyDiffError(Exception):
    """Raised when the comparison cannot be made: the file cannot be read or parsed (by
    either side), or the two sides' geometry names do not match. The message names the
    file and, where there is one, the element."""


class Rule(enum.Enum):
    """Why the two sides classify a pair differently (module doc)."""

    WORLD_ADJACENCY = "world adjacency"
    WELDED_SUBGRAPHS = "welded subgraphs"
    FLOATING_JOINTS = "floating joints"
    GROUP_SYNTAX = "group syntax"
    ANCHORED = "anchored pairs"
    UNEXPLAINED = "unexplained"


@dataclass(frozen=True)
class Explanation:
    rule: Rule
    detail: str

    def to_json(self) -> dict[str, str]:
        return {"rule": self.rule.value, "detail": self.detail}


@dataclass(frozen=True)
class Difference:
    """A pair that is a candidate on exactly one side."""

    pair: Pair
    legacy_filtered: bool
    explanations: tuple[Explanation, ...]

    def to_json(self) -> dict[str, Any]:
        return {
            "pair": list(self.pair),
            "legacy": "filtered" if self.legacy_filtered else "candidate",
            "modern": "candidate" if self.legacy_filtered else "filtered",
            "rules": [e.to_json() for e in self.explanations],
        }


#: ``<joint type>`` / ``<drake:joint type>`` → MultibodyPlant's joint type (None: no joint).
_MODERN_JOINTS: Mapping[tuple[bool, str], str | None] = {
    (False, "fixed"): "weld",
    (False, "revolute"): "revolute",
    (False, "continuous"): "revolute",
    (False, "prismatic"): "prismatic",
    (False, "planar"): "planar",
    (False, "floating"): None,  # Drake warns and leaves the child free.
    (True, "ball"): "ball_rpy",
    (True, "universal"): "universal",
    (True, "planar"): "planar",
    (True, "screw"): "screw",
}
_MESH_FILENAME = re.compile(r"""(<mesh\b[^>]*?\bfilename\s*=\s*)(["'])(.*?)\2""", re.DOTALL)


@dataclass(frozen=True)
class LegacyDiff:
    """The comparison of one model: both candidate sets and every difference, explained."""

    source: str
    backend: BackendId
    legacy: LegacyModel
    legacy_candidates: frozenset[Pair]
    modern_candidates: frozenset[Pair]
    differences: tuple[Difference, ...]
    notes: tuple[str, ...]

    def counts(self) -> dict[str, int]:
        """Differences per rule (a pair with two rules counts for both)."""
        counts = {rule.value: 0 for rule in Rule}
        for difference in self.differences:
            for explanation in difference.explanations:
                counts[explanation.rule.value] += 1
        return counts

    # ------------------------------------------------------------ reports
    def to_json(self) -> dict[str, Any]:
        model = self.legacy
        return {
            "file": self.source,
            "model": model.name,
            "backend": self.backend.to_json(),
            "legacy": {
                "elements": model.elements(),
                "groups": [
                    {
                        "name": model.groups.name_of(bit),
                        "bit": bit,
                        "membership": model.groups.group_masks(bit)[0],
                        "ignore": model.groups.group_masks(bit)[1],
                        "members": list(model.groups.members(bit)),
                    }
                    for bit in model.groups.bits()
                ],
                "undefined_ignores": [list(p) for p in model.groups.undefined_ignores],
                "cliques": [
                    list(model.cliques.members(c)) for c in range(model.cliques.num_cliques)
                ],
                "anchored_bodies": sorted(model.anchored),
                "candidates": sorted(list(p) for p in self.legacy_candidates),
            },
            "modern": {"candidates": sorted(list(p) for p in self.modern_candidates)},
            "differences": [d.to_json() for d in self.differences],
            "summary": {
                "legacy_candidates": len(self.legacy_candidates),
                "modern_candidates": len(self.modern_candidates),
                "common": len(self.legacy_candidates & self.modern_candidates),
                "differences": len(self.differences),
                "by_rule": self.counts(),
            },
            "notes": list(self.notes),
        }

    def to_text(self, *, all_pairs: bool = False) -> str:
        """The report: the legacy groups and cliques, the counts, then each differing pair
        (every pair, side by side, with ``all_pairs``) and its rules."""
        model = self.legacy
        lines = [
            f"legacy-diff {self.source}: model '{model.name}', legacy RigidBodyTree vs "
            f"modern {self.backend}",
            "",
            f"legacy: {len(model.elements())} elements on "
            f"{sum(1 for b in model.graph.bodies if model.graph.elements_of(b))} bodies",
            *self._legacy_lines(),
            "",
            f"candidates: legacy {len(self.legacy_candidates)}, modern "
            f"{len(self.modern_candidates)}, in both "
            f"{len(self.legacy_candidates & self.modern_candidates)}",
            "",
        ]
        if all_pairs:
            lines += self._pair_lines(sorted(self.legacy_candidates | self.modern_candidates))
            lines.append("")
        if not self.differences:
            lines.append("no pair differs")
        else:
            lines.append(f"differing pairs ({len(self.differences)}):")
            lines += self._pair_lines([d.pair for d in self.differences], explain=True)
            counted = ", ".join(f"{rule} {n}" for rule, n in self.counts().items() if n)
            lines += ["", f"{len(self.differences)} pairs differ: {counted}"]
        lines += [f"note: {note}" for note in self.notes]
        return "\n".join(lines) + "\n"

    def _legacy_lines(self) -> list[str]:
        model, groups = self.legacy, self.legacy.groups
        lines = []
        if groups.num_groups:
            width = max(4, groups.num_groups + 1)
            column = width + 6
            lines += [
                "  groups (unprefixed <collision_filter_group>; bit 0 is universal):",
                f"    {'bit':>3}  {'group':<12} {'membership':<{column}} {'ignore':<{column}} "
                "members",
            ]
            for bit in groups.bits():
                membership, ignore = groups.group_masks(bit)
                members = sorted({model.body_of(e) for e in groups.members(bit)})
                lines.append(
                    f"    {bit:>3}  {groups.name_of(bit):<12} "
                    f"{format_mask(membership, width):<{column}} "
                    f"{format_mask(ignore, width):<{column}} {', '.join(members) or '-'}"
                )
        else:
            lines.append("  groups: none")
        lines += [
            f"  note: group '{group}' ignores '{target}', which is never defined "
            "(not an error; RBT logged a warning)"
            for group, target in groups.undefined_ignores
        ]
        lines.append(f"  cliques (seed 002 auto cliques): {model.cliques.num_cliques}")
        for clique in range(model.cliques.num_cliques):
            bodies = list(dict.fromkeys(model.body_of(e) for e in model.cliques.members(clique)))
            lines.append(
                f"    {clique:>3}  {' + '.join(bodies)}  ({_clique_reason(model, bodies)})"
            )
        lines.append(f"  anchored bodies: {', '.join(sorted(model.anchored))}")
        return lines

    def _pair_lines(self, pairs: list[Pair], *, explain: bool = False) -> list[str]:
        """A side-by-side table of ``pairs``: legacy, modern, the pair, its rules."""
        by_pair = {d.pair: d for d in self.differences}
        a_width = max(len(a) for a, _ in pairs)
        b_width = max(len(b) for _, b in pairs)
        lines = [f"  {'legacy':<9} {'modern':<9}  {'pair':<{a_width + b_width + 2}}  rules"]
        for pair in pairs:
            legacy = "candidate" if pair in self.legacy_candidates else "filtered"
            modern = "candidate" if pair in self.modern_candidates else "filtered"
            difference = by_pair.get(pair)
            rules = (
                ", ".join(e.rule.value for e in difference.explanations)
                if difference is not None
                else "-"
            )
            lines.append(
                f"  {legacy:<9} {modern:<9}  {pair[0]:<{a_width}}  {pair[1]:<{b_width}}  {rules}"
            )
            if explain and difference is not None:
                lines += [f"      {e.rule.value}: {e.detail}" for e in difference.explanations]
        return lines


def _clique_reason(model: LegacyModel, bodies: list[str]) -> str:
    if len(bodies) == 1:
        return "the elements of one body"
    joints = [
        j for j in model.graph.joints if {j.parent, j.child} == set(bodies) and not j.is_floating
    ]
    names = ", ".join(f"{j.name} ({j.type_name})" for j in joints)
    world = " with the world" if WORLD_BODY in bodies else ""
    return f"adjacent{world} through {names}"


# ---------------------------------------------------------------- the modern side
def _absolute_mesh_paths(text: str, folder: Path) -> tuple[str, int]:
    """``text`` with relative mesh file names made absolute (the modern side parses a copy of
    the file in a temporary folder), and how many were changed."""
    changed = 0

    def absolute(match: re.Match[str]) -> str:
        nonlocal changed
        name = match.group(3)
        if "://" in name or Path(name).is_absolute():
            return match.group(0)
        changed += 1
        return f"{match.group(1)}{match.group(2)}{(folder / name).resolve()}{match.group(2)}"

    return _MESH_FILENAME.sub(absolute, text), changed


def _execute(backend: Backend, path: Path, command: Command) -> Result:
    """``backend.execute(command)``; a backend that breaks is a BackendError naming the file."""
    return call(backend, "execute", command, where=f"{path} ({command.op})", returns=Result)


def _modern(backend: Backend, path: Path, text: str) -> tuple[list[str], frozenset[Pair]]:
    """The model names ``add_models`` returns and the candidates after ``finalize``."""
    call(backend, "reset", where=f"{path} (reset)", returns=object)
    files = {"files": {path.name: text}, "path": path.name}
    result = _execute(backend, path, Command("add_models", files))
    if result.error is not None:
        raise LegacyDiffError(f"{path}: {backend.name} refused the model: {result.error.message}")
    models = list(result.value)
    result = _execute(backend, path, Command("finalize", {}))
    if result.error is not None:
        raise LegacyDiffError(f"{path}: {backend.name} could not finalize: {result.error.message}")
    observed = call(backend, "observe", where=f"{path} (observe)", returns=Observation)
    return models, observed.locations[MODEL].candidates


def _check_names(
    backend: Backend, path: Path, elements: list[str], modern: frozenset[Pair]
) -> None:
    """Every modern geometry is a legacy element, and every legacy element exists there."""
    seen = {name for pair in modern for name in pair}
    unknown = sorted(seen - set(elements))
    if unknown:
        raise LegacyDiffError(
            f"{path}: the modern plant's geometry '{unknown[0]}' matches no legacy element "
            "(geometry names differ)"
        )
    for name in elements:
        if name in seen:
            continue
        other = next((e for e in elements if e != name), None)
        if other is None:
            return
        try:
            _execute(backend, path, Command("collision_filtered", {"pair": [name, other]}))
        except UnknownNameError:
            raise LegacyDiffError(
                f"{path}: the legacy element '{name}' is no geometry of the modern plant "
                "(geometry names differ)"
            ) from None


# ------------------------------------------------------------------ explanations
class _Explainer:
    """Body-level facts of both sides, for the module doc's rules."""

    def __init__(self, model: LegacyModel) -> None:
        self.model = model
        urdf = model.urdf
        self.joints = urdf.joints
        welds = [
            (model.scoped(j.parent), model.scoped(j.child), j.name)
            for j in urdf.joints
            if _MODERN_JOINTS.get((j.drake_joint, j.type)) == "weld"
        ]
        self.weld_edges = welds
        self.modern_groups = _resolve_drake_groups(urdf.drake_groups)

    def _bodies(self, links: Iterable[str]) -> set[str]:
        return {self.model.scoped(link) for link in links}

    def _joints_between(self, a: str, b: str) -> list[UrdfJoint]:
        model = self.model
        return [j for j in self.joints if {model.scoped(j.parent), model.scoped(j.child)} == {a, b}]

    def legacy_only(self, a: str, b: str) -> list[Explanation]:
        """Why RBT filters bodies a, b and MultibodyPlant does not."""
        found = []
        for g, h in _group_pairs(self.model.urdf.groups, self._bodies, a, b):
            found.append(
                Explanation(
                    Rule.GROUP_SYNTAX,
                    f"legacy group '{g.name}' (line {g.line}) ignores '{h.name}'; today's parser "
                    "silently ignores the unprefixed <collision_filter_group>",
                )
            )
        for joint in self._joints_between(a, b):
            legacy_type = None if joint.drake_joint else joint.type
            if WORLD_BODY in (a, b) and legacy_type not in (None, "floating"):
                found.append(
                    Explanation(
                        Rule.WORLD_ADJACENCY,
                        f"joint '{joint.name}' ({joint.type}, line {joint.line}) joins the world "
                        "and a body: RBT's adjacency clique included the world, MultibodyPlant "
                        "skips joints whose parent is the world",
                    )
                )
        if a in self.model.anchored and b in self.model.anchored:
            found.append(
                Explanation(
                    Rule.ANCHORED,
                    "both bodies are rigidly fixed to the world: RBT excluded anchored pairs",
                )
            )
        return found

    def modern_only(self, a: str, b: str) -> list[Explanation]:
        """Why MultibodyPlant filters bodies a, b and RBT does not."""
        found = []
        path = _weld_path(self.weld_edges, a, b)
        if path:
            found.append(
                Explanation(
                    Rule.WELDED_SUBGRAPHS,
                    f"welded together through {', '.join(path)}: MultibodyPlant filters every "
                    "pair of a welded subgraph, RBT only adjacent bodies",
                )
            )
        for g, h in _group_pairs(self.modern_groups, self._bodies, a, b):
            found.append(
                Explanation(
                    Rule.GROUP_SYNTAX,
                    f"drake:collision_filter_group '{g.name}' (line {g.line}) ignores "
                    f"'{h.name}'; RBT did not read drake:-prefixed groups",
                )
            )
        for joint in self._joints_between(a, b):
            modern_type = _MODERN_JOINTS.get((joint.drake_joint, joint.type))
            if modern_type is None or modern_type == "quaternion_floating":
                continue
            if joint.drake_joint:
                found.append(
                    Explanation(
                        Rule.FLOATING_JOINTS,
                        f"RBT did not read <drake:joint> '{joint.name}' ({joint.type}, line "
                        f"{joint.line}): its child hung from the world by a floating base, "
                        "and floating joints make no adjacency clique",
                    )
                )
        return found


def _group_pairs(
    groups: Iterable[UrdfGroup], bodies: Any, a: str, b: str
) -> list[tuple[UrdfGroup, UrdfGroup]]:
    """(G, H) for every group G ignoring a defined group H with a ∈ G, b ∈ H or the reverse."""
    by_name = {g.name: g for g in groups}
    pairs = []
    for g in by_name.values():
        for target in g.ignored:
            h = by_name.get(target)
            if h is None:
                continue
            in_g, in_h = bodies(g.members), bodies(h.members)
            if (a in in_g and b in in_h) or (b in in_g and a in in_h):
                pairs.append((g, h))
    return pairs


def _resolve_drake_groups(groups: Iterable[UrdfGroup]) -> list[UrdfGroup]:
    """``drake:`` groups with member groups expanded (transitively; cycles allowed)."""
    by_name = {g.name: g for g in groups}
    members = {name: set(g.members) for name, g in by_name.items()}
    changed = True
    while changed:
        changed = False
        for name, g in by_name.items():
            for inner in g.member_groups:
                extra = members.get(inner, set()) - members[name]
                if extra:
                    members[name] |= extra
                    changed = True
    return [
        UrdfGroup(g.name, g.line, tuple(sorted(members[g.name])), g.ignored, (), True)
        for g in by_name.values()
    ]


def _weld_path(edges: list[tuple[str, str, str]], a: str, b: str) -> list[str]:
    """The joint names of a weld path from a to b (empty if none)."""
    previous: dict[str, tuple[str, str]] = {a: (a, "")}
    frontier = [a]
    while frontier:
        nxt = []
        for body in frontier:
            for parent, child, name in edges:
                for here, there in ((parent, child), (child, parent)):
                    if here == body and there not in previous:
                        previous[there] = (body, name)
                        nxt.append(there)
        frontier = nxt
    if b not in previous:
        return []
    path, body = [], b
    while body != a:
        body, name = previous[body]
        path.append(name)
    return path[::-1]


# ------------------------------------------------------------------------ entry
def _pair(pair: Iterable[str]) -> Pair:
    a, b = sorted(pair)
    return (a, b)


def legacy_diff(path: str | Path, backend: Backend) -> LegacyDiff:
    """Compares the URDF at ``path`` under RBT's rules and on ``backend`` (module doc).

    Raises:
        LegacyDiffError: the file is missing or malformed, a legacy group names an
            unknown link, the backend refuses the model, or the names do not match.
    """
    path = Path(path)
    try:
        urdf = load_legacy_urdf(path)
    except LegacyError as exc:
        raise LegacyDiffError(str(exc)) from None
    text, meshes = _absolute_mesh_paths(path.read_text(encoding="utf-8"), path.parent.resolve())
    models, modern = _modern(backend, path, text)
    if len(models) != 1:
        raise LegacyDiffError(f"{path}: expected one model, the modern parser made {models}")
    try:
        model = legacy_model(urdf, models[0])
    except LegacyError as exc:
        raise LegacyDiffError(str(exc)) from None
    elements = model.elements()
    _check_names(backend, path, elements, modern)
    legacy = frozenset(_pair(p) for p in model.candidate_pairs())
    explainer = _Explainer(model)
    differences = []
    for pair in sorted(legacy ^ modern):
        a, b = model.body_of(pair[0]), model.body_of(pair[1])
        legacy_filtered = pair in modern
        found = explainer.legacy_only(a, b) if legacy_filtered else explainer.modern_only(a, b)
        if not found:
            found = [Explanation(Rule.UNEXPLAINED, "no rule of this comparison accounts for it")]
        differences.append(Difference(pair, legacy_filtered, tuple(found)))
    notes = []
    if meshes:
        notes.append(f"{meshes} relative mesh file name(s) made absolute for the modern parser")
    if any(j.type == "floating" and not j.drake_joint for j in urdf.joints):
        notes.append(
            "a floating <joint> is no joint for MultibodyPlant (its child stays free) and "
            "makes no adjacency clique for RBT"
        )
    return LegacyDiff(
        str(path),
        backend_id(backend),
        model,
        legacy,
        modern,
        tuple(differences),
        tuple(notes),
    )
