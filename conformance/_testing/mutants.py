"""Mutants: reimpl with one deliberate bug each, to measure the harness itself.

This module is the registry; the mutants are in ``mutants_basic``, ``mutants_state``, and
(issue 30) ``mutants_order`` (an order across locations), ``mutants_boundary`` (a query's
edges) and ``mutants_report`` (what only ``observe`` reports), and ``mutants_blind``
(bugs from a blind audit of reimpl).

Mutation testing of the harness: a differential fuzzer that cannot tell these
backends from real pydrake cannot be trusted to catch a real regression either.
Each mutant is the ``reimpl`` backend with exactly one bug; the ``bug`` field of
its table entry says, in one sentence, what is wrong.

A mutant touches nothing inside reimpl. It is an ``Api`` whose ``geometry``
module is a copy of ``reimpl.geometry`` in which ``SceneGraph`` (and
``CollisionFilterDeclaration``) are replaced by subclasses of reimpl's public
classes, and whose managers and inspectors are thin wrappers of reimpl's. The
bug is written with pydrake's public calls only (Apply, ApplyTransient,
RemoveDeclaration, IsActive, AssignRole, GetGeometryIds, CollisionFiltered...),
so a change to how reimpl stores C cannot break a mutant. Nothing is
monkeypatched: a plain reimpl backend in the same process is unaffected.

What a mutant remembers about one location (the model, or one context) is kept
by its SceneGraph per location. N.B. ``Context.Clone()`` is not a SceneGraph
call, so a clone starts with no such memory; contexts made by
CreateDefaultContext/SetDefaultContext start from what the model's state holds.

Use a mutant as a backend spec, ``conformance._testing.mutants:<name>``, e.g.
``python -m conformance run --backend conformance._testing.mutants:reverse_statement_order
--backend pydrake``, or build one with ``mutant_backend(name)``.
"""

from __future__ import annotations

from collections.abc import Callable

from conformance._testing.mutants_basic import BASIC_MUTANTS, Mutant, MutantBackend
from conformance._testing.mutants_blind import BLIND_MUTANTS
from conformance._testing.mutants_boundary import BOUNDARY_MUTANTS
from conformance._testing.mutants_order import ORDER_MUTANTS
from conformance._testing.mutants_report import REPORT_MUTANTS
from conformance._testing.mutants_state import STATE_MUTANTS

__all__ = ["MUTANTS", "Mutant", "MutantBackend", "mutant_backend"]

#: Every mutant by name: the basic ones (``mutants_basic``), then those whose bug
#: needs a reached state (``mutants_state``), then an order across locations
#: (``mutants_order``), then the edges of a query (``mutants_boundary``: ``fuzz --poses``),
#: then reports no command asks for (``mutants_report``), then those of a blind audit
#: (``mutants_blind``: written from reimpl's code before this table was read).
MUTANTS: dict[str, Mutant] = {
    m.name: m
    for m in (
        *BASIC_MUTANTS,
        *STATE_MUTANTS,
        *ORDER_MUTANTS,
        *BOUNDARY_MUTANTS,
        *REPORT_MUTANTS,
        *BLIND_MUTANTS,
    )
}


def mutant_backend(name: str) -> MutantBackend:
    """A fresh backend for the mutant ``name`` (a key of MUTANTS)."""
    return MutantBackend(MUTANTS[name])


def __getattr__(name: str) -> Callable[[], MutantBackend]:
    """``conformance._testing.mutants:<name>`` as a backend spec: a zero-argument factory."""
    if name in MUTANTS:
        return lambda: mutant_backend(name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
