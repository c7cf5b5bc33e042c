"""The scenario corpus: Corpus → ScenarioFile → Case → Step, loaded and checked.

A scenario file is JSON (``.json``) or YAML (``.yaml``, ``.yml``); both are read
by ``conformance._corpus.documents`` into the same data. Loading validates each
file against the scenario schema (with the ``jsonschema`` library; its step
rules come from ``conformance._grammar``) and then checks names statically:
every source, frame, geometry, body, context and declaration label a step
refers to must have been declared earlier in the same case, and an
expectation's pair names two different geometries. After a step that parses
models (``add_models``), model-scoped names (with ``::``: ``m::l1``,
``m::l1/Sphere``) of frames, geometries and bodies are accepted: the model
text holds them, and a backend raises ``UnknownNameError`` for one that does
not exist. A case needs the feature tags of its file, its own, and those of
its ops (from the grammar). Any problem raises ``ScenarioError`` naming
the file, the case and the field, so the CLI can report it and exit 2; input
echoed in a message is cut to about 200 characters.

A file's ``name`` (and so every case's ``qualified_name``) does not depend on
how its path was spelled: it is the path below the first of these roots that
holds the file, without the suffix: the embedded corpus, the nearest directory
holding ``scenario.schema.json`` (a corpus root, as for the pytest plugin), the
current directory; else it is the absolute path.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from itertools import chain
from pathlib import Path
from typing import Any

import jsonschema

from conformance._corpus.documents import (
    DOCUMENT_SUFFIXES,
    TOO_DEEP,
    DocumentError,
    clip,
    read_document,
)
from conformance._corpus_root import corpus_root
from conformance._grammar import ArgKind, declared_names, features_of, referenced_names, spec
from conformance._grammar.schema import SCHEMA_FILE as SCENARIO_SCHEMA
from conformance._grammar.schema import scenario_schema
from conformance._policy.release_facts import fact_side

__all__ = [
    "SCENARIO_SCHEMA",
    "Case",
    "ScenarioError",
    "ScenarioFile",
    "Step",
    "default_corpus_root",
    "enclosing_corpus",
    "in_model_package",
    "load_corpus",
    "load_file",
    "scenario_from_data",
]

_SPECIAL_REFS = frozenset({"@unknown", "@foreign"})
#: The separator of model-scoped names, and the kinds of name a model scopes.
_SCOPE = "::"
_SCOPED_KINDS = frozenset({"frame", "geometry", "body"})
_NON_ARGS = frozenset({"op", "comment", "expect"})
#: Expectation keys whose value is a list of geometry-name pairs.
_PAIR_KEYS = ("candidates", "filtered", "unfiltered")
#: What the top level of a document is, when it is not an object (bool before int).
_KINDS: tuple[tuple[type | tuple[type, ...], str], ...] = (
    (type(None), "null"),
    (bool, "a boolean"),
    ((int, float), "a number"),
    (str, "a string"),
    (list, "an array"),
)
#: A schema message is cut to this many characters (its echoed instance to ~200 first).
_MESSAGE_LIMIT = 400


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
            parts.append(f"case {clip(repr(case))}")
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
    name: str  # path below a stable root (see the module docstring), without the suffix
    description: str
    cases: tuple[Case, ...] = field(default=(), compare=False)


@cache
def _validator() -> jsonschema.protocols.Validator:
    schema = scenario_schema()
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)
    return cls(schema)


def default_corpus_root() -> Path:
    """The embedded default corpus: the clone's ``scenarios/`` or the wheel's (``corpus_root``)."""
    return corpus_root()


def _json_path(parts: Iterable[object], whole: str = "(top level)") -> str:
    shown = (f"[{p}]" if isinstance(p, int) else f".{clip(str(p), 40)}" for p in parts)
    return "".join(shown) or whole


def _case_label(data: Any, index: int) -> str:
    try:
        return str(data["cases"][index]["description"])
    except (KeyError, IndexError, TypeError):
        return f"#{index + 1}"


def _schema_message(error: jsonschema.ValidationError) -> str:
    """The error's message with its echoed instance, and then the whole, cut short."""
    message = error.message
    echoed = repr(error.instance)
    if len(echoed) > len(clip(echoed)):
        message = message.replace(echoed, clip(echoed))
    return clip(message, _MESSAGE_LIMIT)


def _describe_schema_error(data: Any, error: jsonschema.ValidationError) -> tuple[str | None, str]:
    """(case description or None, 'field: reason') for the most useful sub-error."""
    best = jsonschema.exceptions.best_match([error])
    path = list(best.absolute_path)
    case = None
    if len(path) >= 2 and path[0] == "cases" and isinstance(path[1], int):
        case = _case_label(data, path[1])
        if len(path) >= 4 and path[2] == "steps" and isinstance(path[3], int):
            where = f"step {path[3] + 1}, field {_json_path(path[4:])}"
        else:
            where = f"field {_json_path(path[2:], '(the case)')}"
    else:
        where = f"field {_json_path(path)}"
    return case, f"{where}: {_schema_message(best)}"


def _error_order(error: jsonschema.ValidationError) -> list[tuple[int, int, str]]:
    """Sorts errors by path; YAML may put a non-string key beside a string one."""
    return [(0, p, "") if isinstance(p, int) else (1, 0, str(p)) for p in error.absolute_path]


def _kind(value: Any) -> str:
    return next((name for types, name in _KINDS if isinstance(value, types)), type(value).__name__)


def _case_index(error: jsonschema.ValidationError) -> int | None:
    """The index of the case an error lies in (None: it lies outside every case)."""
    path = list(error.absolute_path)
    return path[1] if len(path) >= 2 and path[0] == "cases" and isinstance(path[1], int) else None


def _validate(shown: str, data: Any, errors: list[ScenarioError] | None = None) -> set[int]:
    """Raises ``ScenarioError`` unless ``data`` is a scenario object valid under the schema.

    With an ``errors`` list, a violation inside one case is recorded there, for that
    case (the first by path), and the case's index returned among the bad ones: the
    file's other cases still load. A violation outside the cases fails the file.
    """
    if not isinstance(data, dict):
        raise ScenarioError(
            shown, f"the top level is {_kind(data)}, not an object with 'description' and 'cases'"
        )
    try:
        found = sorted(_validator().iter_errors(data), key=_error_order)
        by_case: dict[int | None, jsonschema.ValidationError] = {}
        for error in found:
            index = _case_index(error) if errors is not None else None
            by_case.setdefault(index, error)
        described = {i: _describe_schema_error(data, e) for i, e in by_case.items()}
    except RecursionError:
        raise ScenarioError(shown, TOO_DEEP) from None
    except ValueError as exc:  # repr() of an integer too long to print in decimal
        raise ScenarioError(shown, f"cannot be validated: {clip(str(exc))}") from None
    if None in described:
        case, message = described[None]
        raise ScenarioError(shown, f"schema violation at {message}", case=case)
    for case, message in described.values():
        _record(ScenarioError(shown, f"schema violation at {message}", case=case), errors)
    return {i for i in described if i is not None}


def load_file(
    path: Path, *, root: Path | None = None, errors: list[ScenarioError] | None = None
) -> ScenarioFile:
    """Loads, validates and name-checks one scenario file (``.json``, ``.yaml`` or ``.yml``).

    Its ``name`` is the path below ``root`` if given and the file is under it,
    else the stable name of the module docstring. With an ``errors`` list, a
    case that fails the schema or names something undeclared is recorded there
    and left out, and the file's other cases are kept; a file whose own fields
    (outside its cases) fail the schema still raises.
    """
    try:
        data = read_document(path)
    except DocumentError as exc:
        raise ScenarioError(str(path), str(exc)) from None
    return scenario_from_data(data, path, root=root, errors=errors)


def scenario_from_data(
    data: Any,
    path: Path,
    *,
    root: Path | None = None,
    errors: list[ScenarioError] | None = None,
) -> ScenarioFile:
    """A ScenarioFile of scenario data (as a document holds it) standing at ``path``: what
    ``load_file`` does after reading, for cases a program writes (``corpus.model_files``)."""
    shown = str(path)
    bad = _validate(shown, data, errors)
    file = ScenarioFile(path=path, name=_name(path, root), description=data["description"])
    file_features = frozenset(data.get("features", ["core"]))
    cases = []
    seen: set[str] = set()
    for index, raw in enumerate(data["cases"]):
        if index in bad:
            continue
        description = raw["description"]
        if description in seen:
            raise ScenarioError(shown, "duplicate case description", case=description)
        seen.add(description)
        steps = tuple(_scene_steps(raw.get("scene", {}))) + tuple(
            _step(i, s, path.parent) for i, s in enumerate(raw["steps"], 1)
        )
        case = Case(
            file=file,
            description=description,
            features=file_features
            | frozenset(raw.get("features", ()))
            | features_of(step.op for step in steps),
            steps=steps,
            comment=raw.get("comment"),
            drake_refs=tuple(raw.get("drake_refs", ())),
        )
        try:
            _check_names(shown, case)
            _check_pairs(shown, case)
            _check_release_facts(shown, case)
        except ScenarioError as exc:
            _record(exc, errors)
            continue
        cases.append(case)
    object.__setattr__(file, "cases", tuple(cases))
    return file


def enclosing_corpus(path: Path) -> Path | None:
    """The nearest directory above ``path`` holding the scenario schema, if any."""
    return next((p for p in path.parents if (p / SCENARIO_SCHEMA).is_file()), None)


def _name_roots(path: Path) -> Iterator[Path]:
    """The roots a file's name is taken below, first match wins (all resolved)."""
    yield default_corpus_root().resolve()
    corpus = enclosing_corpus(path)
    if corpus is not None:
        yield corpus
    try:
        yield Path.cwd().resolve()
    except OSError:  # the current directory was removed
        return


def _name(path: Path, root: Path | None = None) -> str:
    """The file's name: its path below ``root`` or the first stable root, without the suffix."""
    resolved = path.resolve()
    roots = chain([root.resolve()] if root is not None else [], _name_roots(resolved))
    below = next((r for r in roots if resolved.is_relative_to(r)), None)
    name = resolved if below is None else resolved.relative_to(below)
    return name.with_suffix("").as_posix()


def _step(index: int, raw: Mapping[str, Any], base: Path) -> Step:
    """A Step of ``raw``; folder arguments (``ArgKind.FOLDER``, ``ArgKind.PACKAGES``) are made
    absolute against ``base``, the scenario file's folder."""
    expect = raw.get("expect", ())
    if isinstance(expect, Mapping):
        expect = (expect,)
    args = {k: v for k, v in raw.items() if k not in _NON_ARGS}
    for key, kind in spec(raw["op"]).arg_kinds.items():
        if kind is ArgKind.FOLDER and key in args:
            args[key] = str((base / args[key]).resolve())
        elif kind is ArgKind.PACKAGES and key in args:
            args[key] = {name: str((base / path).resolve()) for name, path in args[key].items()}
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
    for key in _PAIR_KEYS:
        for pair in expectation.get(key, ()):
            for name in pair:
                yield "geometry", name, f"expect.{key}"
    for label in expectation.get("active", {}):
        yield "label", label, "expect.active"


def _expectation_pairs(step: Step) -> Iterator[tuple[str, Sequence[str]]]:
    """(field, pair) for every geometry pair in the step's expectations."""
    for i, expectation in enumerate(step.expect):
        prefix = f"expect[{i}]" if len(step.expect) > 1 else "expect"
        for key in _PAIR_KEYS:
            for j, pair in enumerate(expectation.get(key, ())):
                yield f"{prefix}.{key}[{j}]", pair


def _check_pairs(path: str, case: Case) -> None:
    """An expectation's pair is two different geometries (C never holds a geometry with itself)."""
    for step in case.steps:
        for where, (a, b) in _expectation_pairs(step):
            if a == b:
                raise ScenarioError(
                    path,
                    f"the pair names geometry {clip(repr(a))} twice; a pair is two geometries",
                    case=case.description,
                    where=f"{step.label}, field {where}",
                )


def _check_release_facts(path: str, case: Case) -> None:
    """An expectation's ``release_fact`` names a row of the release table, on a side it has."""
    for step in case.steps:
        for i, expectation in enumerate(step.expect):
            references = expectation.get("release_fact", ())
            try:
                for reference in [references] if isinstance(references, str) else references:
                    fact_side(reference)
            except (KeyError, ValueError) as exc:
                raise ScenarioError(
                    path,
                    str(exc).strip('"'),
                    case=case.description,
                    where=f"{step.label}, field expect[{i}].release_fact",
                ) from None


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
        "body": {"world"},
    }
    scoped = False  # an earlier step parsed models: their scoped names may be used
    for step in case.steps:
        refs = list(_refs(step))
        for kind, name in _declares(step):
            if name in declared[kind] and kind != "label":
                raise ScenarioError(
                    path,
                    f"{kind} {clip(repr(name))} is declared twice",
                    case=case.description,
                    where=f"{step.label}, field name",
                )
        # A step's arguments see earlier declarations; its expectations see its own too.
        arguments = [r for r in refs if not r[2].startswith("expect")]
        _require(path, case, step, declared, arguments, scoped=scoped)
        for kind, name in _declares(step):
            declared[kind].add(name)
        scoped = scoped or spec(step.op).scoped_names
        expectations = [r for r in refs if r[2].startswith("expect")]
        _require(path, case, step, declared, expectations, scoped=scoped)


def _require(
    path: str,
    case: Case,
    step: Step,
    declared: Mapping[str, set[str]],
    refs: Iterable[tuple[str, str, str]],
    *,
    scoped: bool = False,
) -> None:
    for kind, name, where in refs:
        if scoped and kind in _SCOPED_KINDS and _SCOPE in name:
            continue
        if name not in _SPECIAL_REFS and name not in declared[kind]:
            raise ScenarioError(
                path,
                f"unknown {kind} name {clip(repr(name))} "
                "(declare it in the scene or an earlier step)",
                case=case.description,
                where=f"{step.label}, field {where}",
            )


def _record(error: ScenarioError, errors: list[ScenarioError] | None) -> None:
    """Raises ``error``, or, given an ``errors`` list, appends it there so loading goes on."""
    if errors is None:
        raise error
    errors.append(error)


#: A folder holding this file is a model package (ROS's and Drake's convention), whose
#: ``.yaml`` files are model directives, not scenarios: the walker does not enter it.
PACKAGE_MANIFEST = "package.xml"


def _is_scenario(path: Path) -> bool:
    """A file the walker loads: a known suffix, and not a schema (``*.schema.json``) or a
    model-directives file (``*.dmd.yaml``)."""
    suffix = path.suffix.lower()
    name = path.name.lower()
    return (
        suffix in DOCUMENT_SUFFIXES
        and not name.endswith((f".schema{suffix}", ".dmd.yaml"))
        and path.is_file()
    )


def in_model_package(path: Path, root: Path) -> bool:
    """Whether ``path`` lies in a model package below ``root`` (a folder between them, or its
    own, holds PACKAGE_MANIFEST), or is a model-directives file: model data, not a scenario."""
    if path.name.lower().endswith(".dmd.yaml"):
        return True
    folder = path.parent
    while folder != root and folder.is_relative_to(root):
        if (folder / PACKAGE_MANIFEST).is_file():
            return True
        folder = folder.parent
    return False


def _scenario_files(folder: Path) -> list[Path]:
    """The scenario files below ``folder``, sorted, outside model packages (PACKAGE_MANIFEST)."""
    found = []
    for parent, folders, names in os.walk(folder):
        if PACKAGE_MANIFEST in names and Path(parent) != folder:
            folders.clear()
            continue
        folders.sort()
        found += [Path(parent, name) for name in names if _is_scenario(Path(parent, name))]
    return sorted(found)


def _walk(targets: Iterable[Path], errors: list[ScenarioError] | None = None) -> Iterator[Path]:
    """The scenario files of ``targets``: files as given, directories walked in sorted order.

    A missing target, or a directory without scenario files, raises; with an
    ``errors`` list it is recorded there and the walk goes on.
    """
    for target in targets:
        try:
            if target.is_dir():
                found = _scenario_files(target)
                if not found:
                    raise ScenarioError(
                        str(target),
                        f"no scenario files ({', '.join(f'*{s}' for s in DOCUMENT_SUFFIXES)}) "
                        "in this directory",
                    )
                yield from found
            elif target.is_file():
                yield target
            elif target.exists():  # a pipe or a device: reading it could block forever
                raise ScenarioError(str(target), "not a regular file or a directory")
            else:
                raise ScenarioError(str(target), "no such file or directory")
        except ScenarioError as exc:
            _record(exc, errors)


def _once(paths: Iterable[Path]) -> Iterator[Path]:
    """``paths`` without repeats of one file (however spelled), first spelling kept."""
    seen: set[Path] = set()
    for path in paths:
        resolved = path.resolve()
        if resolved not in seen:
            seen.add(resolved)
            yield path


def _check_unique_names(
    files: Iterable[ScenarioFile], errors: list[ScenarioError] | None = None
) -> list[ScenarioFile]:
    """Two files may not share a name (say ``x.json`` and ``x.yaml``): their cases would clash.

    Returns the files; with an ``errors`` list, a file whose name is taken is
    recorded there and left out.
    """
    first: dict[str, Path] = {}
    kept = []
    for file in files:
        other = first.setdefault(file.name, file.path)
        if other != file.path:
            _record(
                ScenarioError(
                    str(file.path), f"has the same name {file.name!r} as {other}; rename one"
                ),
                errors,
            )
            continue
        kept.append(file)
    return kept


def load_corpus(
    paths: Sequence[Path] = (), *, errors: list[ScenarioError] | None = None
) -> list[ScenarioFile]:
    """Loads files and directories, each file once.

    Directories are walked recursively for ``*.json``, ``*.yaml`` and ``*.yml``
    files, skipping schemas (``*.schema.json``), model directives (``*.dmd.yaml``)
    and model packages (folders holding a ``package.xml``, such as the vendored
    real models). No paths: the embedded corpus.
    The first bad file raises ScenarioError; with an ``errors`` list, every bad
    file and case is recorded there instead and the good ones are loaded.
    """
    files = []
    for path in _once(_walk(paths or [default_corpus_root()], errors)):
        try:
            files.append(load_file(path, errors=errors))
        except ScenarioError as exc:
            _record(exc, errors)
    return _check_unique_names(files, errors)
