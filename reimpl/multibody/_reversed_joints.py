"""Finalize's answer to a joint that the tree must model from its child to its parent.

Since Drake 1.41 (world-child-joint-since-1.41) Finalize models a revolute,
prismatic or weld joint reversed, and refuses the other types. Up to 1.40 it
refuses every reversed joint (from 1.36 all but welds), each range of releases
in its own words; the table below holds them, newest first, each with the
release fact from which it holds (measured on every release from 1.12.0 to
1.58.0 with a revolute joint whose child is the world:
docs/releases/report.json). Up to 1.32 the refusal is the clash of the
joint with the floating joint Finalize gives its parent body, so the words
name that body; for a reversed joint whose child is not the world those
releases are not measured, and their words are 1.33's.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from reimpl._release import release

__all__ = ["REVERSIBLE_JOINT_TYPES", "reversed_joint_refusal"]

#: The joint types Finalize models reversed since 1.41.
REVERSIBLE_JOINT_TYPES = frozenset({"prismatic", "revolute", "weld"})


@dataclass(frozen=True)
class _Joint:
    """What the refusals name: the joint, its type, its instance, its bodies' names."""

    name: str
    kind: str
    instance: str
    parent_body: str
    child_is_world: bool
    parent_frame_index: int
    #: Whether the joint's frame on its parent is that body's own frame (not offset).
    on_body_frame: bool = True
    parent_body_index: int = 0


_ORDERING = (
    "MultibodyPlant::Finalize(): parent/child ordering for {what} in model instance {instance} "
    "would have to be reversed to make a tree-structured model for this system. Currently "
    "Drake does not support that{but}. Reverse the ordering in your joint definition so that "
    "all parent/child directions form a tree structure."
)


def _since_1_41(j: _Joint) -> str | None:
    if j.kind in REVERSIBLE_JOINT_TYPES:
        return None
    return (
        f"MultibodyPlant::Finalize(): parent/child ordering for {j.kind} joint {j.name} in "
        f"model instance {j.instance} would have to be reversed to make a tree-structured "
        f"model for this system. Currently Drake does not support reversed {j.kind} joints. "
        f"The joints that can be reversed are: {', '.join(sorted(REVERSIBLE_JOINT_TYPES))}. "
        "Reverse the ordering in your joint definition so that its parent body is closer to "
        "World in the tree."
    )


def _since_1_36(j: _Joint) -> str | None:
    if j.kind == "weld":
        return None
    what = f"{j.kind} joint {j.name}"
    return _ORDERING.format(what=what, instance=j.instance, but=" except for Weld joints")


def _since_1_33(j: _Joint) -> str | None:
    return _ORDERING.format(what=f"Joint {j.name}", instance=j.instance, but="")


def _graph(floating: Callable[[str], str]) -> Callable[[_Joint], str | None]:
    def refusal(j: _Joint) -> str | None:
        if not j.child_is_world:
            return _since_1_33(j)
        return (
            f"This MultibodyGraph already has a joint '{j.name}' connecting '{j.parent_body}' "
            f"to 'world'. Therefore adding joint '{floating(j.parent_body)}' connecting "
            f"'world' to '{j.parent_body}' is not allowed."
        )

    return refusal


def _until_1_19(j: _Joint) -> str | None:
    """The clash of the reversed mobilizer with the floating one: between the two frames
    when the joint is on the parent's body frame, else between the two bodies (measured
    on pydrake 1.19.0: an offset frame on the parent gives 'inboard body (index=0) and
    outboard body (index=<its body>)')."""
    if not j.child_is_world:
        return _since_1_33(j)
    if not j.on_body_frame:
        return (
            "This multibody tree already has a mobilizer connecting inboard body (index=0) and "
            f"outboard body (index={j.parent_body_index}). More than one mobilizer between two "
            "bodies is not allowed."
        )
    return (
        f"This multibody tree already has a mobilizer connecting inboard frame (index=0) and "
        f"outboard frame (index={j.parent_frame_index}). More than one mobilizer between two "
        "frames is not allowed."
    )


#: (release fact from which it holds, the refusal), newest first; the last holds before all.
_REFUSALS: tuple[tuple[str | None, Callable[[_Joint], str | None]], ...] = (
    ("world-child-joint-since-1.41", _since_1_41),
    ("reversed-joint-type-wording-since-1.36", _since_1_36),
    ("reversed-joint-ordering-wording-since-1.33", _since_1_33),
    ("reversed-joint-body-name-since-1.22", _graph(lambda body: body)),
    ("reversed-joint-graph-wording-since-1.20", _graph(lambda body: f"$world_{body}")),
    (None, _until_1_19),
)


def reversed_joint_refusal(joint: Any, instance: str) -> str | None:
    """The message Finalize raises for ``joint`` modeled reversed (None: it is modeled)."""
    parent = joint.frame_on_parent().body()
    child = joint.frame_on_child().body()
    facts = _Joint(
        name=joint.name(),
        kind=joint.type_name(),
        instance=instance,
        parent_body=parent.name(),
        child_is_world=int(child.index()) == 0,
        parent_frame_index=int(parent.body_frame().index()),
        on_body_frame=joint.frame_on_parent() is parent.body_frame(),
        parent_body_index=int(parent.index()),
    )
    refusal = next(rule for fact, rule in _REFUSALS if fact is None or release.has(fact))
    return refusal(facts)
