"""The scenario corpus: Corpus → ScenarioFile → Case → Step, loaded and checked.

Loading validates each file against the scenario schema (with the
``jsonschema`` library; its step rules come from ``conformance.grammar``)
and then checks names statically: every source,
frame, geometry, context and declaration label a step refers to must have been
declared earlier in the same case. Any problem raises ``ScenarioError`` naming
the file, the case and the field, so the CLI can report it and exit 2.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

import jsonschema

from conformance.grammar import declared_names, referenced_names
from conformance.grammar.schema import SCHEMA_FILE as SCENARIO_SCHEMA
from conformance.grammar.schema import scenario_schema

__all__ = [
    "SCENARIO_SCHEMA",
    "Case",
    "ScenarioError",
    "ScenarioFile",
    "Step",
    "default_corpus_root",
    "load_corpus",
    "load_file",
]

_SPECIAL_REFS = frozenset({"@unknown", "@foreign"})
_NON_ARGS = frozenset({"op", "comment", "expect"})


class ScenarioError(ValueError):
    """Raised when a scenario file is malformed, invalid, or names something undeclared."""

    def __init__(
        self, path: str, message: str, *, case: str | None = None, where: str | None = None
    ) -> None:
        self.path = path
        self.case = case
        self.where = where
        self.message = message
        parts = [path]
        if case is not None:
            parts.append(f"case {case!r}")
        if where is not None:
            parts.append(where)
        super().__init__(f"{': '.join(parts)}: {message}")


@dataclass(frozen=True)
class Step:
    """One command of a case, with its expectations (a list; empty if none)."""

    index: int  # 1-based position among the case's steps; 0 for scene steps
    op: str
    args: Mapping[str, Any]
    expect: tuple[Mapping[str, Any], ...]
    comment: str | None = None

    @property
    def label(self) -> str:
        return "scene" if self.index == 0 else f"step {self.index}"

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {"op": self.op, **self.args}
        if self.expect:
            out["expect"] = list(self.expect) if len(self.expect) > 1 else self.expect[0]
        return out


@dataclass(frozen=True)
class Case:
    file: ScenarioFile
    description: str
    features: frozenset[str]
    steps: tuple[Step, ...]
    comment: str | None = None
    drake_refs: tuple[str, ...] = ()

    @property
    def qualified_name(self) -> str:
        return f"{self.file.name} > {self.description}"


@dataclass(frozen=True)
class ScenarioFile:
    path: Path
    name: str  # path relative to the corpus root, without ".json"
    description: str
    cases: tuple[Case, ...] = field(default=(), compare=False)


@cache
def _validator() -> jsonschema.protocols.Validator:
    schema = scenario_schema()
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)
    return cls(schema)


def default_corpus_root() -> Path:
    """The embedded default corpus (the ``scenarios`` package's directory)."""
    return Path(str(resources.files("scenarios")))


def _json_path(parts: Iterable[object]) -> str:
    return "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in parts) or "(top level)"


def _describe_schema_error(data: Any, error: jsonschema.ValidationError) -> tuple[str | None, str]:
    """(case description or None, 'field: reason') for the most useful sub-error."""
    best = jsonschema.exceptions.best_match([error])
    path = list(best.absolute_path)
    case = None
    if len(path) >= 2 and path[0] == "cases" and isinstance(path[1], int):
        try:
            case = str(data["cases"][path[1]].get("description", f"#{path[1] + 1}"))
        except (KeyError, IndexError, TypeError, AttributeError):
            case = f"#{path[1] + 1}"
        if len(path) >= 4 and path[2] == "steps" and isinstance(path[3], int):
            where = f"step {path[3] + 1}, field {_json_path(path[4:])}"
        else:
            where = f"field {_json_path(path[2:])}"
    else:
        where = f"field {_json_path(path)}"
    return case, f"{where}: {best.message}"


def load_file(path: Path, *, root: Path | None = None) -> ScenarioFile:
    """Loads, validates and name-checks one scenario file."""
    shown = str(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ScenarioError(shown, f"cannot read the file: {exc.strerror}") from None
    except json.JSONDecodeError as exc:
        raise ScenarioError(
            shown, f"malformed JSON at line {exc.lineno}, column {exc.colno}: {exc.msg}"
        ) from None
    errors = sorted(_validator().iter_errors(data), key=lambda e: list(e.absolute_path))
    if errors:
        where, message = _describe_schema_error(data, errors[0])
        raise ScenarioError(shown, f"schema violation at {message}", case=where)
    try:
        name = path.resolve().relative_to((root or path.parent).resolve()).with_suffix("")
    except ValueError:
        name = Path(path.stem)
    file = ScenarioFile(path=path, name=name.as_posix(), description=data["description"])
    file_features = frozenset(data.get("features", ["core"]))
    cases = []
    seen: set[str] = set()
    for raw in data["cases"]:
        description = raw["description"]
        if description in seen:
            raise ScenarioError(shown, "duplicate case description", case=description)
        seen.add(description)
        steps = tuple(_scene_steps(raw.get("scene", {}))) + tuple(
            _step(i, s) for i, s in enumerate(raw["steps"], 1)
        )
        case = Case(
            file=file,
            description=description,
            features=file_features | frozenset(raw.get("features", ())),
            steps=steps,
            comment=raw.get("comment"),
            drake_refs=tuple(raw.get("drake_refs", ())),
        )
        _check_names(shown, case)
        cases.append(case)
    object.__setattr__(file, "cases", tuple(cases))
    return file


def _step(index: int, raw: Mapping[str, Any]) -> Step:
    expect = raw.get("expect", ())
    if isinstance(expect, Mapping):
        expect = (expect,)
    args = {k: v for k, v in raw.items() if k not in _NON_ARGS}
    return Step(index, raw["op"], args, tuple(expect), raw.get("comment"))


def _scene_steps(scene: Mapping[str, Any]) -> Iterator[Step]:
    for name in scene.get("sources", ()):
        yield Step(0, "register_source", {"name": name}, ())
    for frame in scene.get("frames", ()):
        yield Step(0, "register_frame", dict(frame), ())
    for geometry in scene.get("geometries", ()):
        yield Step(0, "register_geometry", dict(geometry), ())


def _refs(step: Step) -> Iterator[tuple[str, str, str]]:
    """(kind, name, field) for every name the step refers to (not declares), expectations too."""
    for kind, name, where in referenced_names(step.op, step.args):
        yield kind.value, name, where
    for expectation in step.expect:
        yield from _expectation_refs(expectation)


def _expectation_refs(expectation: Mapping[str, Any]) -> Iterator[tuple[str, str, str]]:
    if "at" in expectation:
        yield "context", expectation["at"], "expect.at"
    for key in ("candidates", "filtered", "unfiltered"):
        for pair in expectation.get(key, ()):
            for name in pair:
                yield "geometry", name, f"expect.{key}"
    for label in expectation.get("active", {}):
        yield "label", label, "expect.active"


def _declares(step: Step) -> Iterator[tuple[str, str]]:
    for kind, name, _ in declared_names(step.op, step.args):
        yield kind.value, name


def _check_names(path: str, case: Case) -> None:
    declared: dict[str, set[str]] = {
        "source": {"source"},
        "frame": {"world"},
        "geometry": set(),
        "context": {"model"},
        "label": set(),
    }
    for step in case.steps:
        refs = list(_refs(step))
        for kind, name in _declares(step):
            if name in declared[kind] and kind != "label":
                raise ScenarioError(
                    path,
                    f"{kind} {name!r} is declared twice",
                    case=case.description,
                    where=f"{step.label}, field name",
                )
        # A step's arguments see earlier declarations; its expectations see its own too.
        _require(path, case, step, declared, [r for r in refs if not r[2].startswith("expect")])
        for kind, name in _declares(step):
            declared[kind].add(name)
        _require(path, case, step, declared, [r for r in refs if r[2].startswith("expect")])


def _require(
    path: str,
    case: Case,
    step: Step,
    declared: Mapping[str, set[str]],
    refs: Iterable[tuple[str, str, str]],
) -> None:
    for kind, name, where in refs:
        if name not in _SPECIAL_REFS and name not in declared[kind]:
            raise ScenarioError(
                path,
                f"unknown {kind} name {name!r} (declare it in the scene or an earlier step)",
                case=case.description,
                where=f"{step.label}, field {where}",
            )


def load_corpus(paths: Sequence[Path] = ()) -> list[ScenarioFile]:
    """Loads files and directories (recursively, ``*.json`` except the schema)."""
    root = default_corpus_root()
    targets = list(paths) or [root]
    files: list[ScenarioFile] = []
    for target in targets:
        if target.is_dir():
            for path in sorted(target.rglob("*.json")):
                if path.name != SCENARIO_SCHEMA:
                    files.append(load_file(path, root=target))
        elif target.exists():
            files.append(load_file(target, root=_root_for(target, root)))
        else:
            raise ScenarioError(str(target), "no such file or directory")
    return files


def _root_for(path: Path, root: Path) -> Path:
    try:
        path.resolve().relative_to(root.resolve())
    except ValueError:
        return path.parent
    return root
