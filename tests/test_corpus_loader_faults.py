"""The scenario loader turns every faulty input into one ScenarioError naming the file.

Each fault is checked on the loader directly and, for the first ones, through
the real CLI in a subprocess: exit code 2, one ``error:`` line naming the
file, no traceback, and a short stderr however large the input.
"""

from __future__ import annotations

import codecs
import json
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from conformance._corpus import loader
from conformance._corpus.documents import MAX_DEPTH, TOO_DEEP
from conformance._corpus.loader import (
    SCENARIO_SCHEMA,
    ScenarioError,
    default_corpus_root,
    load_corpus,
    load_file,
)
from conformance.cli.exit_codes import EXIT_OK, EXIT_USAGE

DESCRIPTION = "exclude_within of two geometries empties C"
SCENARIO: dict[str, Any] = {
    "description": "a tiny file",
    "features": ["core"],
    "cases": [
        {
            "description": DESCRIPTION,
            "comment": "both geometries on their own frames",
            "scene": {
                "frames": [{"name": "f0"}, {"name": "f1"}],
                "geometries": [
                    {"name": "g0", "frame": "f0", "roles": ["proximity"]},
                    {"name": "g1", "frame": "f1", "roles": ["proximity"]},
                ],
            },
            "steps": [
                {"op": "check", "expect": {"candidates": [["g0", "g1"]]}},
                {
                    "op": "apply",
                    "declaration": {
                        "statements": [
                            {"op": "exclude_within", "set": {"geometries": ["g0", "g1"]}}
                        ]
                    },
                    "expect": [
                        {"until": "1.51.1", "candidates": []},
                        {"since": "1.52", "filtered": [["g0", "g1"]]},
                    ],
                },
            ],
        }
    ],
}

#: SCENARIO, written by hand in YAML (versions quoted: unquoted, 1.52 is a number).
SCENARIO_YAML = """\
# The JSON twin is SCENARIO.
description: a tiny file
features: [core]
cases:
  - description: exclude_within of two geometries empties C
    comment: both geometries on their own frames
    scene:
      frames:
        - name: f0
        - name: f1
      geometries:
        - {name: g0, frame: f0, roles: [proximity]}
        - {name: g1, frame: f1, roles: [proximity]}
    steps:
      - op: check
        expect: {candidates: [[g0, g1]]}
      - op: apply
        declaration:
          statements:
            - op: exclude_within
              set: {geometries: [g0, g1]}
        expect:
          - {until: "1.51.1", candidates: []}
          - {since: "1.52", filtered: [[g0, g1]]}
"""

SIX_MEGABYTES = "[" + ",".join(["0"] * 3_000_000) + "]"


def write(directory: Path, name: str, content: str | bytes | object) -> Path:
    path = directory / name
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content if isinstance(content, str) else json.dumps(content))
    return path


def with_step(step: dict[str, Any]) -> dict[str, Any]:
    """SCENARIO with ``step`` as its only step."""
    data = json.loads(json.dumps(SCENARIO))
    data["cases"][0]["steps"] = [step]
    return data


def load_error(path: Path) -> ScenarioError:
    with pytest.raises(ScenarioError) as info:
        load_file(path)
    return info.value


def cli(*paths: Path | str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "conformance", "run", *map(str, paths), "--backend", "reimpl"],
        capture_output=True,
        text=True,
        check=False,
        cwd=cwd,
        timeout=300,
    )


def cli_error(path: Path) -> str:
    """The CLI's one error line for ``path``, after checking exit code 2 and no traceback."""
    result = cli(path)
    assert result.returncode == EXIT_USAGE, result.stderr
    assert "Traceback" not in result.stderr
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr[:2000]
    assert lines[0].startswith(f"error: {path}: ")
    return lines[0]


def nested(depth: int) -> list[Any]:
    """A list nested ``depth`` deep, built without recursion."""
    inner: list[Any] = []
    for _ in range(depth - 1):
        inner = [inner]
    return inner


# 1. Bytes that are not UTF-8


def test_non_utf8_bytes_are_an_input_error_naming_the_byte_offset_and_line(
    tmp_path: Path,
) -> None:
    path = write(tmp_path, "latin1.json", b'{\n  "description": "caf\xe9"}')
    error = load_error(path)
    assert str(error) == f"{path}: not UTF-8 text (byte 0xe9 at offset 23, line 2)"
    assert error.path == str(path)


def test_the_cli_reports_non_utf8_bytes_in_one_line_and_exits_two(tmp_path: Path) -> None:
    path = write(tmp_path, "latin1.json", b'{"description": "caf\xe9"}')
    assert cli_error(path) == f"error: {path}: not UTF-8 text (byte 0xe9 at offset 20, line 1)"


def test_a_utf16_file_is_an_input_error_that_asks_for_utf8(tmp_path: Path) -> None:
    path = write(
        tmp_path, "utf16.json", codecs.BOM_UTF16_LE + json.dumps(SCENARIO).encode("utf-16-le")
    )
    assert load_error(path).message == "UTF-16 text (a UTF-16 byte order mark); save it as UTF-8"


# 2. Nesting


def test_json_nested_a_hundred_thousand_deep_is_an_input_error_not_a_recursion_error(
    tmp_path: Path,
) -> None:
    path = write(tmp_path, "deep.json", "[" * 100_000 + "]" * 100_000)
    assert str(load_error(path)) == f"{path}: {TOO_DEEP}"
    assert "nested too deeply" in TOO_DEEP


def test_the_cli_reports_json_nested_a_hundred_thousand_deep_in_one_line(tmp_path: Path) -> None:
    path = write(tmp_path, "deep.json", "[" * 100_000 + "]" * 100_000)
    assert cli_error(path) == f"error: {path}: {TOO_DEEP}"


def test_yaml_nested_a_hundred_thousand_deep_is_an_input_error(tmp_path: Path) -> None:
    path = write(tmp_path, "deep.yaml", "[" * 100_000 + "]" * 100_000)
    assert load_error(path).message == TOO_DEEP


def test_parseable_json_one_level_deeper_than_the_limit_is_refused_before_validation(
    tmp_path: Path,
) -> None:
    at_limit = {"description": "x", "cases": nested(MAX_DEPTH - 1)}  # object + lists = limit
    too_deep = {"description": "x", "cases": nested(MAX_DEPTH)}
    assert "schema violation" in load_error(write(tmp_path, "ok.json", at_limit)).message
    assert load_error(write(tmp_path, "deep.json", too_deep)).message == TOO_DEEP


def test_schema_validation_that_recurses_too_deeply_is_an_input_error() -> None:
    # Past the parsers' depth check: jsonschema's repr() of the instance recurses.
    step = {"op": "check", "expect": nested(100_000)}
    data = {"description": "x", "cases": [{"description": "c", "steps": [step]}]}
    with pytest.raises(ScenarioError) as info:
        loader._validate("deep.json", data)
    assert str(info.value) == f"deep.json: {TOO_DEEP}"


# 3. Large documents: nothing is echoed whole


def test_a_six_megabyte_top_level_array_is_refused_without_echoing_it(tmp_path: Path) -> None:
    path = write(tmp_path, "big.json", SIX_MEGABYTES)
    assert path.stat().st_size > 6_000_000
    error = load_error(path)
    assert (
        error.message == "the top level is an array, not an object with 'description' and 'cases'"
    )


def test_the_cli_reports_a_six_megabyte_top_level_array_in_under_two_kilobytes(
    tmp_path: Path,
) -> None:
    path = write(tmp_path, "big.json", SIX_MEGABYTES)
    line = cli_error(path)
    assert len(line.encode()) < 2000
    assert line.endswith("the top level is an array, not an object with 'description' and 'cases'")


def test_a_schema_error_echoes_a_six_megabyte_instance_cut_to_about_200_characters(
    tmp_path: Path,
) -> None:
    path = write(tmp_path, "big.json", '{"description": "x", "cases": [' + SIX_MEGABYTES + "]}")
    error = load_error(path)
    assert error.case == "#1"
    assert error.message.startswith("schema violation at field (the case): [0, 0, 0")
    assert error.message.endswith(", 0, 0] is not of type 'object'")
    echoed = error.message.split(": ", 1)[1].removesuffix(" is not of type 'object'")
    assert len(echoed) == 200
    assert "…" in echoed


def test_the_cli_reports_a_schema_error_on_six_megabytes_in_under_two_kilobytes(
    tmp_path: Path,
) -> None:
    path = write(tmp_path, "big.json", '{"description": "x", "cases": [' + SIX_MEGABYTES + "]}")
    line = cli_error(path)
    assert len(line.encode()) < 2000
    assert line.endswith("] is not of type 'object'")


def test_a_megabyte_case_description_is_cut_in_the_case_label_and_in_the_message(
    tmp_path: Path,
) -> None:
    data = json.loads(json.dumps(SCENARIO))
    data["cases"][0]["description"] = "d" * 1_000_000
    error = load_error(write(tmp_path, "long.json", data))
    assert error.case == "d" * 1_000_000
    assert error.message.startswith("schema violation at field .description: 'ddd")
    assert error.message.endswith("ddd' is too long")
    assert 400 < len(str(error)) < 600


def test_a_megabyte_undeclared_name_is_cut_in_the_message(tmp_path: Path) -> None:
    name = "g" * 1_000_000
    error = load_error(
        write(
            tmp_path,
            "name.json",
            with_step({"op": "check", "expect": {"candidates": [[name, "g0"]]}}),
        )
    )
    assert error.message.startswith("unknown geometry name 'ggg")
    assert error.message.endswith("ggg' (declare it in the scene or an earlier step)")
    assert len(error.message) < 300


# 4. Expectation pairs naming one geometry twice


@pytest.mark.parametrize("key", ["candidates", "filtered", "unfiltered"])
def test_an_expectation_pair_naming_one_geometry_twice_is_an_input_error(
    tmp_path: Path, key: str
) -> None:
    path = write(
        tmp_path,
        "self.json",
        with_step({"op": "check", "expect": {key: [["g0", "g1"], ["g0", "g0"]]}}),
    )
    error = load_error(path)
    assert (error.case, error.where) == (DESCRIPTION, f"step 1, field expect.{key}[1]")
    assert error.message == "the pair names geometry 'g0' twice; a pair is two geometries"


def test_a_self_pair_in_the_second_expectation_of_a_list_names_its_index(tmp_path: Path) -> None:
    expect = [{"candidates": [["g0", "g1"]]}, {"since": "1.52", "filtered": [["g1", "g1"]]}]
    error = load_error(write(tmp_path, "self.json", with_step({"op": "check", "expect": expect})))
    assert error.where == "step 1, field expect[1].filtered[0]"


def test_the_cli_reports_a_self_pair_as_an_input_error_not_a_failure(tmp_path: Path) -> None:
    path = write(
        tmp_path, "self.json", with_step({"op": "check", "expect": {"candidates": [["g0", "g0"]]}})
    )
    assert cli_error(path) == (
        f"error: {path}: case {DESCRIPTION!r}: step 1, field expect.candidates[0]: "
        "the pair names geometry 'g0' twice; a pair is two geometries"
    )


def test_collision_filtered_may_still_name_one_geometry_twice(tmp_path: Path) -> None:
    step = {"op": "collision_filtered", "pair": ["g0", "g0"], "expect": {"returns": True}}
    (case,) = load_file(write(tmp_path, "ok.json", with_step(step))).cases
    assert case.steps[-1].args == {"pair": ["g0", "g0"]}


# 5. YAML


@pytest.mark.parametrize("suffix", [".yaml", ".yml"])
def test_a_yaml_file_and_its_json_twin_load_to_equal_cases(tmp_path: Path, suffix: str) -> None:
    from_json = load_file(write(tmp_path, "twin.json", SCENARIO))
    from_yaml = load_file(write(tmp_path / "yaml", "twin" + suffix, SCENARIO_YAML))

    def contents(file: loader.ScenarioFile) -> list[tuple[object, ...]]:
        return [(c.description, c.features, c.steps, c.comment, c.drake_refs) for c in file.cases]

    assert contents(from_yaml) == contents(from_json)
    assert len(from_yaml.cases[0].steps) == 6  # four scene steps, two steps
    assert from_yaml.description == from_json.description == "a tiny file"


def test_a_yaml_syntax_error_is_an_input_error_with_line_and_column(tmp_path: Path) -> None:
    path = write(tmp_path, "bad.yaml", "description: x\ncases: [\n  {description: y,\n")
    assert load_error(path).message == (
        "malformed YAML at line 4, column 1: expected the node content, but found '<stream end>' "
        "(while parsing a flow node)"
    )


def test_a_yaml_file_is_validated_against_the_scenario_schema(tmp_path: Path) -> None:
    path = write(tmp_path, "bad.yaml", SCENARIO_YAML.replace('"1.52"', "1.52"))
    error = load_error(path)
    assert error.case == DESCRIPTION
    assert error.message == (
        "schema violation at step 2, field .expect[1].since: 1.52 is not of type 'string'"
    )


def test_yaml_aliases_are_refused_with_their_line_and_column(tmp_path: Path) -> None:
    path = write(tmp_path, "alias.yaml", "description: &d x\ncomment: *d\ncases: []\n")
    assert load_error(path).message == (
        "YAML alias at line 2, column 10: aliases are not supported; write it out"
    )


def test_a_yaml_mapping_key_that_is_not_a_string_is_refused(tmp_path: Path) -> None:
    path = write(tmp_path, "key.yaml", "description: x\n1.52: y\ncases: []\n")
    assert load_error(path).message == "mapping key 1.52 at line 2, column 1 is not a string"


@pytest.mark.parametrize(
    ("name", "text", "message"),
    [
        (
            "dup.json",
            '{"description": "x", "description": "y"}',
            "duplicate key 'description' in an object",
        ),
        (
            "dup.yaml",
            "description: x\ndescription: y\n",
            "duplicate key 'description' at line 2, column 1",
        ),
    ],
)
def test_a_key_given_twice_is_an_input_error_not_silently_dropped(
    tmp_path: Path, name: str, text: str, message: str
) -> None:
    assert load_error(write(tmp_path, name, text)).message == message


def test_the_cli_runs_a_yaml_scenario(tmp_path: Path) -> None:
    path = write(tmp_path, "tiny.yaml", SCENARIO_YAML)
    result = cli(path)
    assert result.returncode == EXIT_OK, result.stderr
    assert (
        f"{path.resolve().with_suffix('').as_posix()} > {DESCRIPTION}  reimpl:pass" in result.stderr
    )


def test_a_directory_walk_loads_json_yaml_and_yml_files_and_never_a_schema(tmp_path: Path) -> None:
    shutil.copy(default_corpus_root() / SCENARIO_SCHEMA, tmp_path / SCENARIO_SCHEMA)
    write(tmp_path, "a.json", SCENARIO)
    write(tmp_path, "b.yaml", SCENARIO_YAML)
    write(tmp_path, "deeper/c.yml", SCENARIO_YAML)
    write(tmp_path, "deeper/other.schema.json", {"type": "object"})
    write(tmp_path, "notes.txt", "not a scenario")
    (tmp_path / "folder.json").mkdir()
    names = [f.name for f in load_corpus([tmp_path])]
    assert names == ["a", "b", "deeper/c"]


def test_a_json_and_a_yaml_file_of_one_name_are_an_input_error(tmp_path: Path) -> None:
    write(tmp_path, "twin.json", SCENARIO)
    yaml_path = write(tmp_path, "twin.yaml", SCENARIO_YAML)
    with pytest.raises(ScenarioError) as info:
        load_corpus([tmp_path])
    error = info.value
    name = (tmp_path / "twin").resolve().as_posix()
    assert (
        str(error)
        == f"{yaml_path}: has the same name {name!r} as {tmp_path / 'twin.json'}; rename one"
    )


def test_a_file_of_another_type_is_an_input_error(tmp_path: Path) -> None:
    path = write(tmp_path, "case.txt", json.dumps(SCENARIO))
    assert load_error(path).message == (
        "unsupported file type '.txt': scenario files end in .json, .yaml, .yml"
    )


# 6. Names do not depend on how a path is spelled; a file is loaded once


def test_corpus_file_names_do_not_depend_on_how_the_path_is_spelled(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    root = default_corpus_root()
    monkeypatch.chdir(root.parent)
    relative = Path(root.name, "transient", "table1.json")
    spellings = [relative, Path(".", relative), root / "transient" / "table1.json"]
    spellings += [Path(root.name, "transient"), Path(root.name), Path(root.name, "..", root.name)]
    for spelling in spellings:
        table = next(f for f in load_corpus([spelling]) if f.path.stem == "table1")
        assert table.name == "transient/table1", spelling
        assert table.cases[0].qualified_name.startswith("transient/table1 > ")


def test_the_embedded_corpus_keeps_its_names(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.chdir(tmp_path)
    names = {f.name for f in load_corpus()}
    assert {"transient/table1", "errors/errors", "statements/allow_within"} <= names
    assert names == {f.name for f in load_corpus([default_corpus_root()])}


def test_names_of_files_below_the_current_directory_are_relative_to_it(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    write(tmp_path, "work/sub/x.json", SCENARIO)
    monkeypatch.chdir(tmp_path / "work")
    spellings = [
        "sub/x.json",
        "./sub/x.json",
        str(tmp_path / "work/sub/x.json"),
        "sub",
        ".",
        "../work",
    ]
    for spelling in spellings:
        (file,) = load_corpus([Path(spelling)])
        assert file.name == "sub/x", spelling
        assert file.cases[0].qualified_name == f"sub/x > {DESCRIPTION}"


def test_names_of_files_elsewhere_are_their_absolute_paths(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    path = write(tmp_path, "elsewhere/x.yaml", SCENARIO_YAML)
    (tmp_path / "cwd").mkdir()
    monkeypatch.chdir(tmp_path / "cwd")
    for spelling in [path, Path("../elsewhere/x.yaml"), Path("../elsewhere")]:
        (file,) = load_corpus([spelling])
        assert file.name == (tmp_path / "elsewhere" / "x").resolve().as_posix()


def test_names_below_a_folder_holding_the_schema_are_relative_to_that_folder(
    tmp_path: Path,
) -> None:
    shutil.copy(default_corpus_root() / SCENARIO_SCHEMA, tmp_path / SCENARIO_SCHEMA)
    path = write(tmp_path, "topic/x.json", SCENARIO)
    assert [f.name for f in load_corpus([path])] == ["topic/x"]
    assert [f.name for f in load_corpus([tmp_path / "topic"])] == ["topic/x"]


def test_a_file_given_twice_or_with_its_directory_is_loaded_once(tmp_path: Path) -> None:
    path = write(tmp_path, "x.json", SCENARIO)
    write(tmp_path, "y.yaml", SCENARIO_YAML)
    assert len(load_corpus([path, path])) == 1
    assert len(load_corpus([path, tmp_path / "." / "x.json"])) == 1
    files = load_corpus([path, tmp_path])
    assert [f.path for f in files] == [path, tmp_path / "y.yaml"]


def test_the_cli_runs_a_file_given_twice_once_with_one_name(tmp_path: Path) -> None:
    write(tmp_path, "sub/x.json", SCENARIO)
    result = cli("sub/x.json", "./sub/x.json", "sub", tmp_path / "sub" / "x.json", cwd=tmp_path)
    assert result.returncode == EXIT_OK, result.stderr
    assert result.stderr == f"[1/1] sub/x > {DESCRIPTION}  reimpl:pass\n"


# 7. Empty, null and other top levels; a byte order mark


@pytest.mark.parametrize(
    ("name", "text", "message"),
    [
        ("empty.json", "", "the file is empty"),
        ("blank.json", " \n\t\n", "the file is empty"),
        ("empty.yaml", "", "the file is empty"),
        (
            "null.json",
            "null",
            "the top level is null, not an object with 'description' and 'cases'",
        ),
        (
            "comment.yaml",
            "# nothing yet\n",
            "the top level is null, not an object with 'description' and 'cases'",
        ),
        (
            "number.json",
            "42",
            "the top level is a number, not an object with 'description' and 'cases'",
        ),
        (
            "string.yaml",
            "just text",
            "the top level is a string, not an object with 'description' and 'cases'",
        ),
        (
            "bool.json",
            "true",
            "the top level is a boolean, not an object with 'description' and 'cases'",
        ),
    ],
)
def test_a_file_without_a_scenario_object_is_an_input_error(
    tmp_path: Path, name: str, text: str, message: str
) -> None:
    path = write(tmp_path, name, text)
    assert str(load_error(path)) == f"{path}: {message}"


def test_an_integer_of_five_thousand_digits_is_an_input_error(tmp_path: Path) -> None:
    path = write(tmp_path, "huge.json", '{"description": ' + "1" * 5000 + "}")
    assert load_error(path).message.startswith("malformed JSON: Exceeds the limit (4300 digits)")


def test_a_yaml_integer_too_long_to_print_is_an_input_error_not_a_crash(tmp_path: Path) -> None:
    # Hexadecimal parses at any length; jsonschema's message would print it in decimal.
    path = write(tmp_path, "hex.yaml", "description: 0x" + "f" * 4000 + "\ncases: []\n")
    assert load_error(path).message.startswith("cannot be validated: Exceeds the limit")


def test_the_cli_reports_an_empty_file_in_one_line(tmp_path: Path) -> None:
    path = write(tmp_path, "empty.json", "")
    assert cli_error(path) == f"error: {path}: the file is empty"


@pytest.mark.parametrize(
    ("name", "text"), [("bom.json", json.dumps(SCENARIO)), ("bom.yaml", SCENARIO_YAML)]
)
def test_a_file_with_a_utf8_byte_order_mark_loads_like_one_without(
    tmp_path: Path, name: str, text: str
) -> None:
    with_bom = load_file(write(tmp_path / "bom", name, codecs.BOM_UTF8 + text.encode()))
    without = load_file(write(tmp_path, name, text))
    assert [c.steps for c in with_bom.cases] == [c.steps for c in without.cases]
    assert with_bom.cases[0].description == DESCRIPTION


def test_a_folder_walk_skips_model_packages_and_model_directives(tmp_path: Path) -> None:
    (tmp_path / "a.json").write_text(json.dumps(SCENARIO), encoding="utf-8")
    package = tmp_path / "models" / "robot"
    package.mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>robot</name></package>")
    (package / "setup.yaml").write_text("directives: []\n", encoding="utf-8")
    (tmp_path / "cell.dmd.yaml").write_text("directives: []\n", encoding="utf-8")
    errors: list[ScenarioError] = []
    files = load_corpus([tmp_path], errors=errors)
    assert [f.path.name for f in files] == ["a.json"]
    assert errors == []


def test_the_embedded_corpus_loads_without_reading_the_vendored_model_files() -> None:
    errors: list[ScenarioError] = []
    files = load_corpus(errors=errors)
    assert errors == []
    assert not [f for f in files if "real_models/drake/" in f.name]


def test_a_schema_error_in_one_case_leaves_the_file_s_other_cases_loaded(tmp_path: Path) -> None:
    good = {"description": "good", "steps": [{"op": "register_source", "name": "s"}]}
    bad = {"description": "bad", "steps": [{"op": "register_source", "name": "s"}, {"op": "x"}]}
    also_bad = {"description": "also bad", "steps": [{"op": "apply", "frob": 1}]}
    path = write(tmp_path, "three.json", {"description": "d", "cases": [bad, good, also_bad]})
    errors: list[ScenarioError] = []
    loaded = load_file(path, errors=errors)
    assert [c.description for c in loaded.cases] == ["good"]
    assert [(e.case, e.message.split(",")[0]) for e in errors] == [
        ("bad", "schema violation at step 2"),
        ("also bad", "schema violation at step 1"),
    ]


def test_a_schema_error_outside_the_cases_fails_the_whole_file(tmp_path: Path) -> None:
    good = {"description": "good", "steps": [{"op": "register_source", "name": "s"}]}
    path = write(tmp_path, "f.json", {"description": 7, "cases": [good]})
    with pytest.raises(ScenarioError, match=r"schema violation at field \.description"):
        load_file(path, errors=[])
