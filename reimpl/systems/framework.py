"""Systems, contexts, ports and diagrams: the parts of pydrake.systems.framework
SceneGraph scripts touch.

A Context belongs to the System that made it; a SceneGraph's context owns a
copy of the model's GeometryState, taken when the context is created; ports
give access to it (query output) or feed it (pose input). A Diagram holds
subsystems; its context holds one subcontext per subsystem. Passing a System
a context that is not its own raises Drake's context-system mismatch error.

Ports: ``DiagramBuilder.Connect(output, input)`` wires an output port of one
subsystem to an input port of another. In a context, an input port's value is
its fixed value if ``FixValue`` gave one (measured on pydrake 1.51.1: a fixed
value overrides the connection), else, when the context sits in a Diagram's
context that connects the port, the output port's value evaluated on the
sibling subcontext ``Eval(u, C) = Eval(y, C_sibling)``; else it has no value.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from reimpl._release import release
from reimpl._template import scalar_template
from reimpl.common._drake_demand import failed_demand
from reimpl.common._pybind_text import no_constructor
from reimpl.systems._context_keyword import context_argument

if TYPE_CHECKING:
    from reimpl.geometry.geometry_state import GeometryState

__all__ = [
    "Context",
    "Context_",
    "Diagram",
    "DiagramBuilder",
    "DiagramBuilder_",
    "Diagram_",
    "FixedInputPortValue",
    "InputPort",
    "InputPort_",
    "LeafContext",
    "LeafContext_",
    "LeafSystem",
    "LeafSystem_",
    "OutputPort",
    "OutputPort_",
    "System",
    "System_",
]

_MISMATCH_HELP = (
    "\nFor more information about Context-System mismatches, see "
    "https://drake.mit.edu/troubleshooting.html#framework-context-system-mismatch"
)


class System:
    """A named system; it validates that contexts handed to it are its own."""

    #: How Drake names the C++ type in messages, e.g. ``drake::systems::Diagram<double>``.
    _cpp_type = "drake::systems::System<double>"

    def __init__(self) -> None:
        self._name = ""
        self._parent: Diagram | None = None

    def get_name(self) -> str:
        return self._name

    def set_name(self, name: str) -> None:
        self._name = str(name)

    def GetSystemName(self) -> str:
        return self._name or "_"

    def GetSystemPathname(self) -> str:
        """``::`` then the names from the root diagram down; ``_`` for an empty name."""
        parent = "" if self._parent is None else self._parent.GetSystemPathname()
        return f"{parent}::{self.GetSystemName()}"

    def _root(self) -> System:
        return self if self._parent is None else self._parent._root()

    def _new_context(self) -> Context:
        raise NotImplementedError

    def CreateDefaultContext(self) -> Context:
        return self._new_context()

    def AllocateContext(self) -> Context:
        return self.CreateDefaultContext()

    def ValidateContext(self, context: Context) -> None:
        """Raises Drake's mismatch error unless ``context`` was made for this system."""
        if context._system is self:
            return
        what = f"A function call on a {self._cpp_type} system named '{self.GetSystemPathname()}'"
        if context._parent is None and self._parent is not None and context._system is self._root():
            raise RuntimeError(
                f"{what} was passed the root Diagram's Context instead of the appropriate "
                "subsystem Context. Use GetMyContextFromRoot() or similar to acquire the "
                f"appropriate subsystem Context.{_MISMATCH_HELP}"
            )
        if (
            isinstance(self, Diagram)
            and context._parent is not None
            and context._root_context()._system is self
        ):
            raise RuntimeError(
                "A function call on the root Diagram was passed a subcontext associated with "
                f"its subsystem named '{context._pathname}' instead of the root context. When "
                "calling a function on a the root Digram, you must pass a reference to the root "
                f"Context, not a subcontext.{_MISMATCH_HELP}"
            )
        raise RuntimeError(
            f"{what} was passed the Context of a system named '{context._pathname}' instead of "
            f"the appropriate subsystem Context.{_MISMATCH_HELP}"
        )

    def GetMyContextFromRoot(self, root_context: Context) -> Context:
        return root_context._subcontexts.get(self, root_context)

    def GetMyMutableContextFromRoot(self, root_context: Context) -> Context:
        return self.GetMyContextFromRoot(root_context)


class LeafSystem(System):
    """A system without subsystems."""


class Context:
    """The state of one system evaluation; independent of the model once made."""

    def __init__(self, *args: object, **kwargs: object) -> None:
        raise no_constructor(f"reimpl.systems.framework.{type(self).__name__}")

    _system: System
    _pathname: str
    _parent: Context | None
    _subcontexts: dict[System, Context]
    _geometry_state: GeometryState
    _fixed_inputs: dict[int, Any]
    _clone_check: Callable[[Context], None] | None
    _num_input_ports: int
    #: Bumped by every FixValue on one of the system's input ports.
    _input_revision: int
    #: A system's cached values in this context (SceneGraph's pose update), copied by Clone.
    _cache: dict[str, Any]
    #: A system's own values in this context (a plant's positions), copied by Clone.
    _values: dict[str, Any]

    @classmethod
    def _for(cls, system: System, num_input_ports: int = 0) -> Context:
        context = object.__new__(cls)
        context._system = system
        # N.B. Named once, at creation: the system's name then, without its diagram.
        context._pathname = f"::{system.GetSystemName()}"
        context._parent = None
        context._subcontexts = {}
        context._fixed_inputs = {}
        context._clone_check = None
        context._values = {}
        context._input_revision = 0
        context._cache = {}
        # N.B. Fixed at creation: ports of sources registered later are missing.
        context._num_input_ports = num_input_ports
        return context

    def _adopt(self, subcontext: Context) -> None:
        subcontext._parent = self
        subcontext._pathname = f"{self._pathname}::{subcontext._system.GetSystemName()}"
        self._subcontexts[subcontext._system] = subcontext

    def _root_context(self) -> Context:
        return self if self._parent is None else self._parent._root_context()

    def num_input_ports(self) -> int:
        return self._num_input_ports

    def Clone(self) -> Context:
        """A deep copy: for a SceneGraph, filters and transient history (same FilterIds)."""
        if self._clone_check is not None:
            self._clone_check(self)
        clone = type(self)._for(self._system, self._num_input_ports)
        clone._pathname = self._pathname
        clone._fixed_inputs = dict(self._fixed_inputs)
        # N.B. The clone holds a copy of the query port's value, so it checks too.
        clone._clone_check = self._clone_check
        clone._input_revision = self._input_revision
        clone._cache = dict(self._cache)
        clone._values = copy.deepcopy(self._values)
        if hasattr(self, "_geometry_state"):
            clone._geometry_state = self._geometry_state.clone()
        for subcontext in self._subcontexts.values():
            pathname = subcontext._pathname
            clone._adopt(subcontext.Clone())
            clone._subcontexts[subcontext._system]._pathname = pathname
        return clone


class LeafContext(Context):
    """The context of a LeafSystem (such as SceneGraph)."""


class OutputPort:
    """An output port whose value is computed from its system's context."""

    def __init__(
        self, system: System, name: str, index: int, calc: Callable[[Context], Any]
    ) -> None:
        self._system = system
        self._name = name
        self._index = index
        self._calc = calc

    def get_name(self) -> str:
        return self._name

    def get_index(self) -> int:
        return self._index

    def get_system(self) -> System:
        return self._system

    def Eval(self, context: Context) -> Any:
        _check_port_context("OutputPort", self._system, self._index, self._name, context)
        return self._calc(context)


class FixedInputPortValue:
    """What InputPort.FixValue returns."""

    def __init__(self, value: object) -> None:
        self._value = value

    def GetMutableData(self) -> object:
        return self._value


class InputPort:
    """An input port; FixValue stores a value in one of its system's contexts."""

    def __init__(self, system: System, name: str, index: int) -> None:
        self._system = system
        self._name = name
        self._index = index

    def get_name(self) -> str:
        return self._name

    def get_index(self) -> int:
        return self._index

    def get_system(self) -> System:
        return self._system

    def FixValue(self, context: Context, value: object) -> FixedInputPortValue:
        _check_port_context("InputPort", self._system, self._index, self._name, context)
        if self._index >= context.num_input_ports():
            # A context made before the port existed (a SceneGraph source registered later):
            # Drake's DRAKE_DEMAND in SetFixedInputPortValue (older-context-pose-port-aborts).
            raise failed_demand("SetFixedInputPortValue.index")
        # N.B. The context keeps a copy, as pydrake's does: editing ``value`` afterwards
        # does not change what the context holds.
        held = copy.copy(value)
        context._fixed_inputs[self._index] = held
        context._input_revision += 1
        return FixedInputPortValue(held)

    def _source(self, context: Context) -> tuple[OutputPort, Context] | None:
        """The output port wired to this port in ``context``'s diagram, and its subcontext."""
        parent = context._parent
        if parent is None or not isinstance(parent._system, Diagram):
            return None
        output = parent._system._connections.get((self._system, self._index))
        if output is None:
            return None
        return output, parent._subcontexts[output.get_system()]

    def _eval(self, context: Context) -> Any:
        """The value in ``context``: the fixed one, else the connected output's, else None."""
        if self._index in context._fixed_inputs:
            return context._fixed_inputs[self._index]
        source = self._source(context)
        if source is None:
            return None
        output, sibling = source
        return output._calc(sibling)

    def Eval(self, context: Context) -> Any:
        """The port's value; Drake's error when it is neither fixed nor connected."""
        _check_port_context("InputPort", self._system, self._index, self._name, context)
        value = self._eval(context)
        if value is None:
            short_type = self._system._cpp_type.rsplit("::", 1)[-1]
            raise RuntimeError(
                f"InputPort::Eval(): required InputPort[{self._index}] ({self._name}) of System "
                f"{self._system.GetSystemPathname()} ({short_type}) is not connected"
            )
        return value

    def HasValue(self, context: Context) -> bool:
        _check_port_context("InputPort", self._system, self._index, self._name, context)
        return self._index in context._fixed_inputs or self._source(context) is not None


def _check_port_context(kind: str, system: System, index: int, name: str, context: Context) -> None:
    if context._system is not system:
        short_type = system._cpp_type.rsplit("::", 1)[-1]
        raise RuntimeError(
            f"{kind}: The Context given as an argument was not created for this "
            f"{kind}[{index}] ({name}) of System {system.GetSystemPathname()} ({short_type})"
        )


class Diagram(System):
    """Subsystems built together by a DiagramBuilder; its context holds theirs."""

    _cpp_type = "drake::systems::Diagram<double>"

    def __init__(self, *args: object, **kwargs: object) -> None:
        raise no_constructor("reimpl.systems.framework.Diagram")

    _systems: list[System]
    #: (input system, input index) -> the output port wired to it.
    _connections: dict[tuple[System, int], OutputPort]

    @classmethod
    def _build(
        cls, systems: list[System], connections: dict[tuple[System, int], OutputPort]
    ) -> Diagram:
        diagram = object.__new__(cls)
        System.__init__(diagram)
        diagram._systems = list(systems)
        diagram._connections = dict(connections)
        for system in systems:
            system._parent = diagram
        return diagram

    def _new_context(self) -> Context:
        context = Context._for(self)
        for system in self._systems:
            context._adopt(system.CreateDefaultContext())
        return context

    def GetSystems(self) -> list[System]:
        return list(self._systems)

    def HasSubsystemNamed(self, name: str) -> bool:
        return any(s.get_name() == name for s in self._systems)

    def GetSubsystemByName(self, name: str) -> System:
        for system in self._systems:
            if system.get_name() == name:
                return system
        raise RuntimeError(
            f"System {self.GetSystemName()} does not have a subsystem named {name}. The existing "
            f"subsystems are named {{{', '.join(s.get_name() for s in self._systems)}}}."
        )

    def num_input_ports(self) -> int:
        return 0

    def num_output_ports(self) -> int:
        return 0

    @context_argument
    def SetDefaultContext(self, context: Context) -> None:
        """Resets every subsystem's subcontext to its defaults (those that have any)."""
        self.ValidateContext(context)
        for system in self._systems:
            reset = getattr(system, "SetDefaultContext", None)
            if reset is not None:
                reset(context._subcontexts[system])

    def GetSubsystemContext(self, subsystem: System, context: Context) -> Context:
        self.ValidateContext(context)
        if subsystem not in context._subcontexts:
            raise RuntimeError(
                f"GetSubsystemContext(): {subsystem._cpp_type} subsystem "
                f"'{subsystem.GetSystemPathname()}' is not contained in {self._cpp_type} System "
                f"'{self.GetSystemPathname()}'."
            )
        return context._subcontexts[subsystem]

    def GetMutableSubsystemContext(self, subsystem: System, context: Context) -> Context:
        return self.GetSubsystemContext(subsystem, context)


class DiagramBuilder:
    """Collects systems, then builds them into one Diagram (once)."""

    def __init__(self) -> None:
        self._systems: list[System] = []
        self._connections: dict[tuple[System, int], OutputPort] = {}
        self._built = False

    def _check_not_built(self) -> None:
        if self._built:
            raise RuntimeError(
                "DiagramBuilder: Build() or BuildInto() has already been called to create a "
                "Diagram; this DiagramBuilder may no longer be used."
            )

    def AddSystem(self, system: System) -> Any:
        """Adds ``system``; an unnamed one is named after its type and identity, as in Drake."""
        self._check_not_built()
        if not system.get_name():
            type_path = system._cpp_type.split("<", 1)[0].replace("::", "/")
            system.set_name(f"{type_path}@{id(system):016x}")
        self._systems.append(system)
        return system

    def AddNamedSystem(self, name: str, system: System) -> Any:
        system.set_name(name)
        return self.AddSystem(system)

    def GetSystems(self) -> list[System]:
        return list(self._systems)

    def Connect(self, arg0: OutputPort, arg1: InputPort, /) -> None:
        """Wires output port ``arg0`` to input port ``arg1`` (pybind names them arg0, arg1).

        Both systems must have been added to this builder; an input port is
        wired once (pydrake 1.51.1 ends the program with SystemExit then).
        """
        self._check_not_built()
        for port in (arg0, arg1):
            self._check_registered(port.get_system())
        key = (arg1.get_system(), arg1.get_index())
        if key in self._connections:
            # N.B. Up to 1.24 a RuntimeError (connect-wired-input-demand-since-1.25).
            if not release.has("connect-wired-input-demand-since-1.25"):
                raise RuntimeError("Input port is already wired.")
            raise failed_demand("ThrowIfInputAlreadyWired.wired")
        self._connections[key] = arg0

    def IsConnectedOrExported(self, port: InputPort) -> bool:
        return (port.get_system(), port.get_index()) in self._connections

    def _check_registered(self, system: System) -> None:
        if any(s is system for s in self._systems):
            return
        name = system.get_name()
        known = ", ".join(f"'{s.get_name()}'" for s in self._systems) or "NONE"
        raise RuntimeError(
            f"DiagramBuilder: System '{name}' has not been registered to this DiagramBuilder "
            f"using AddSystem nor AddNamedSystem.\n\nThe systems currently registered to this "
            f"builder are: {known}.\n\nIf '{name}' was registered as a subsystem to one of "
            "these, you must export the input or output port using ExportInput/ExportOutput "
            "and then connect to the exported port."
        )

    def empty(self) -> bool:
        return not self._systems

    def already_built(self) -> bool:
        return self._built

    def Build(self) -> Diagram:
        self._check_not_built()
        if not self._systems:
            raise RuntimeError("Cannot Compile an empty DiagramBuilder.")
        self._built = True
        return Diagram._build(self._systems, self._connections)


System_ = scalar_template("reimpl.systems.framework", "System_", System)
LeafSystem_ = scalar_template("reimpl.systems.framework", "LeafSystem_", LeafSystem)
Context_ = scalar_template("reimpl.systems.framework", "Context_", Context)
LeafContext_ = scalar_template("reimpl.systems.framework", "LeafContext_", LeafContext)
Diagram_ = scalar_template("reimpl.systems.framework", "Diagram_", Diagram)
DiagramBuilder_ = scalar_template("reimpl.systems.framework", "DiagramBuilder_", DiagramBuilder)
InputPort_ = scalar_template("reimpl.systems.framework", "InputPort_", InputPort)
OutputPort_ = scalar_template("reimpl.systems.framework", "OutputPort_", OutputPort)
