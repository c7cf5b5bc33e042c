"""Operations that compose an order of events across locations (issue 30).

Drawn one operation at a time, the combinations below almost never happen
(measured at seed 1 × 300: a model Apply followed at once by a new context,
with no geometry edit between, one time in 40 examples; a context made under
the model's history that removes an inherited declaration after one of its
own, never): each event is reached, their order is not. Each row here runs
one such order as a single operation, so the search reaches it as often as
any other row:

=====================================  ============================================
operation                              the order
=====================================  ============================================
``model_edit_then_context``            a model filter edit (Apply; or ApplyTransient
                                       then RemoveDeclaration), then a new context
``context_under_history``              a model transient declaration, a context made
                                       under it, one of the context's own, then the
                                       inherited one removed in the context
``partial_apply_then_clone``           an Apply in a context that raises at its last
                                       statement (what it wrote before stays), then a
                                       clone of that context
``frame_named_in_clone``               a clone, geometry registered into it on a
                                       frame, then a declaration naming the frame there
``reassign_by_frame_in_context``       a model filter on a frame's geometries, then in
                                       a context RemoveRole by that frame and
                                       AssignRole to each of them again
``disagreeing_stack``                  five or six transient declarations on one set,
                                       Exclude and Allow in turn, then the oldest
                                       removed
=====================================  ============================================

(A clone's inherited declarations removed in it: ``operations.clone_with_history``;
``operations.reassign_proximity`` reassigns by frame too, but at seed 1 × 300 never
in a context whose geometry the model filters.) ``with_orders`` adds ``ACROSS_LOCATIONS``
after the rows of a table (``operations.OPERATIONS``, ``POSED_OPERATIONS``), so
the swarm weights of the rows before them stay as they were.
"""

from __future__ import annotations

from typing import Any

from conformance._fuzz import strategies as cs
from conformance._fuzz.operations import (
    MAX_CONTEXTS,
    Machine,
    Operation,
    _can_clone,
    _clone,
    _registered,
    create_context,
)

__all__ = ["ACROSS_LOCATIONS", "with_orders"]

#: The geometry name no command made: a statement naming it makes Apply raise there.
_UNKNOWN = "@unknown"


def _room_for_a_context(m: Machine) -> bool:
    return m.contexts_made < MAX_CONTEXTS


def model_edit_then_context(m: Machine, picks: bytes, declaration: cs.DeclarationTemplate) -> None:
    """A model filter edit, then a new context at once (a context copies the model as it
    is now, whatever was cached at the last geometry edit)."""
    drawn = m.declaration(declaration)
    if picks[0] & 1:
        label = m.fresh("t")
        made = m.step("apply_transient", declaration=drawn, label=label)
        m.keep_if_made("filter_ids", label, made)
        if made.error is None:
            m.step("remove_declaration", label=label)
    else:
        m.step("apply", declaration=drawn)
    create_context(m, picks[1:])


def context_under_history(
    m: Machine, picks: bytes, first: cs.DeclarationTemplate, second: cs.DeclarationTemplate
) -> None:
    """A model transient declaration, a context made under it (it inherits the history), one
    of the context's own, then the inherited one removed there: the context's own stays."""
    inherited = m.fresh("t")
    made = m.step("apply_transient", declaration=m.declaration(first), label=inherited)
    m.keep_if_made("filter_ids", inherited, made)
    context = m.fresh("c")
    m.contexts_made += 1
    created = m.step("create_context", name=context)
    m.keep_if_made("contexts", context, created)
    if created.error is not None:
        return
    own = m.fresh("t")
    mine = m.step("apply_transient", declaration=m.declaration(second), label=own, context=context)
    m.keep_if_made("filter_ids", own, mine)
    m.step("remove_declaration", label=inherited, context=context)


def partial_apply_then_clone(m: Machine, picks: bytes, declaration: cs.DeclarationTemplate) -> None:
    """An Apply in a context whose last statement names an unknown geometry, then a clone
    of the context: what the Apply wrote before it raised is the context's, and the clone's."""
    origin = m.name("origin", picks[0])
    drawn = m.declaration(declaration)
    failing = {"op": "exclude_within", "set": {"geometries": [_UNKNOWN]}}
    statements = [*drawn.get("statements", ()), failing]
    m.step("apply", declaration={**drawn, "statements": statements}, context=origin)
    _clone(m, origin)


def _frames(m: Machine) -> list[str]:
    return [name for name in m.names["frames"] if name != cs.WORLD]


def frame_named_in_clone(m: Machine, picks: bytes) -> None:
    """A clone, a proximity geometry registered into it on a frame, then a declaration in
    the clone (persistent, or one time in two transient) excluding the frame against a
    geometry: the frame names the new geometry too."""
    clone = _clone(m, m.name("origin", picks[0]))
    frames = _frames(m)
    if clone is None or not frames:
        return
    frame = frames[picks[1] % len(frames)]
    name = m.fresh("g")
    result = m.step("register_geometry", name=name, frame=frame, roles=["proximity"], context=clone)
    if _registered(result):
        m.keep("geometries", name)
    other = m.name("geometry", picks[2])
    statement = {
        "op": "exclude_between",
        "a": {"frames": [frame]},
        "b": {"geometries": [other] if other is not None else []},
    }
    declaration: dict[str, Any] = {"statements": [statement]}
    if picks[3] & 1:
        label = m.fresh("t")
        made = m.step("apply_transient", declaration=declaration, label=label, context=clone)
        m.keep_if_made("filter_ids", label, made)
    else:
        m.step("apply", declaration=declaration, context=clone)


def disagreeing_stack(m: Machine, picks: bytes, geometry_set: cs.SetTemplate) -> None:
    """Five or six transient declarations on one drawn set, Exclude and Allow in turn, then
    the oldest removed: every pair of the set is decided by the replay order.

    CollisionFiltered of the set's first two geometries is asked at once; then, one time
    in two, the rest are removed too (newest first), so that the history does not stay
    active for the rest of the example (where every persistent Apply fails).
    """
    where, members = m.name("context", picks[0]), m.geometry_set(geometry_set)
    count = 5 + (picks[1] & 1)
    labels = []
    for i in range(count):
        op = "exclude_within" if (i + picks[2]) % 2 == 0 else "allow_within"
        label = m.fresh("t")
        made = m.step(
            "apply_transient",
            declaration={"statements": [{"op": op, "set": members}]},
            label=label,
            context=where,
        )
        m.keep_if_made("filter_ids", label, made)
        if made.error is None:
            labels.append(label)
    if not labels:
        return
    m.step("remove_declaration", label=labels[0], context=where)
    named = members.get("geometries", [])
    if len(named) > 1:
        m.step("collision_filtered", pair=named[:2], context=where)
    if picks[3] & 1:  # the rest too, newest first: the stack does not outlive the operation
        for label in reversed(labels[1:]):
            m.step("remove_declaration", label=label, context=where)


def reassign_by_frame_in_context(m: Machine, picks: bytes, others: cs.SetTemplate) -> None:
    """A persistent filter at the model between a frame's geometries and a drawn set, then
    in a context (a picked one, or a new one) RemoveRole of proximity by that frame and
    AssignRole of proximity to each geometry on it: there they start unfiltered (but for
    the invariants), whatever the model holds."""
    frames = _frames(m)
    if not frames:
        return
    frame = frames[picks[0] % len(frames)]
    statement = {"op": "exclude_between", "a": {"frames": [frame]}, "b": m.geometry_set(others)}
    m.step("apply", declaration={"statements": [statement]})
    where = m.name("origin", picks[1]) if picks[2] & 1 or not _room_for_a_context(m) else None
    if where is None:
        if not _room_for_a_context(m):
            return
        where = m.fresh("c")
        m.contexts_made += 1
        created = m.step("create_context", name=where)
        m.keep_if_made("contexts", where, created)
        if created.error is not None:
            return
    m.step("remove_role", frame=frame, role="proximity", context=where)
    for name, placed in list(m.poses.geometries.items()):
        if placed.frame == frame:
            m.step("assign_role", geometry=name, role="proximity", context=where)


_DECLARATION = cs.declaration_templates()

#: The rows of this module (see the module doc), added after ``operations.OPERATIONS``.
ACROSS_LOCATIONS: dict[str, Operation] = {
    "model_edit_then_context": Operation(
        model_edit_then_context,
        (_DECLARATION,),
        enabled=_room_for_a_context,
        issues=frozenset({"apply", "apply_transient", "remove_declaration", "create_context"}),
    ),
    "context_under_history": Operation(
        context_under_history,
        (_DECLARATION, _DECLARATION),
        enabled=_room_for_a_context,
        issues=frozenset({"apply_transient", "create_context", "remove_declaration"}),
    ),
    "partial_apply_then_clone": Operation(
        partial_apply_then_clone,
        (_DECLARATION,),
        enabled=_can_clone,
        issues=frozenset({"apply", "clone_context"}),
    ),
    "frame_named_in_clone": Operation(
        frame_named_in_clone,
        enabled=lambda m: _can_clone(m) and bool(_frames(m)),
        issues=frozenset({"clone_context", "register_geometry", "apply", "apply_transient"}),
    ),
    "reassign_by_frame_in_context": Operation(
        reassign_by_frame_in_context,
        (cs.set_templates(),),
        enabled=lambda m: (
            bool(_frames(m)) and (_room_for_a_context(m) or bool(m.names["contexts"]))
        ),
        issues=frozenset({"apply", "create_context", "remove_role", "assign_role"}),
    ),
    "disagreeing_stack": Operation(
        disagreeing_stack,
        (cs.set_templates(),),
        issues=frozenset({"apply_transient", "remove_declaration", "collision_filtered"}),
    ),
}


def with_orders(table: dict[str, Operation]) -> dict[str, Operation]:
    """``table`` with the rows of ``ACROSS_LOCATIONS`` after its own."""
    return {**table, **ACROSS_LOCATIONS}
