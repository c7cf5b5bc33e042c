"""Hypothesis strategies for collision-filter scenarios, and the lockstep machine that fuzzes
two implementations with them.

The public face of ``conformance._fuzz``: an implementation's own property tests draw
scenes (frames and geometries, posed or not), geometry sets, declarations and roles
here, and ``lockstep_machine(make_backend, make_reference)`` gives a Hypothesis state
machine that runs every drawn command on both and fails on the first difference::

    from conformance.strategies import lockstep_machine
    TestMine = lockstep_machine(MyBackend, PydrakeBackend).TestCase
"""

from conformance._fuzz.lockstep import LockstepMachine, PosedLockstepMachine, lockstep_machine
from conformance._fuzz.sequences import command_sequences
from conformance._fuzz.strategies import (
    DeclarationTemplate,
    GeometrySpec,
    Scene,
    SetTemplate,
    Touch,
    declaration_templates,
    declarations,
    geometry_sets,
    poses,
    roles,
    scenes,
    set_templates,
    shapes,
    statements,
    touches,
)

__all__ = [
    "DeclarationTemplate",
    "GeometrySpec",
    "LockstepMachine",
    "PosedLockstepMachine",
    "Scene",
    "SetTemplate",
    "Touch",
    "command_sequences",
    "declaration_templates",
    "declarations",
    "geometry_sets",
    "lockstep_machine",
    "poses",
    "roles",
    "scenes",
    "set_templates",
    "shapes",
    "statements",
    "touches",
]
