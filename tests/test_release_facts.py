"""The release table: its schema, its evidence, what reads it, and the page made from it."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from importlib import resources
from pathlib import Path

import jsonschema
import pytest

from conformance._backends.loader import load_backend
from conformance._backends.reimpl_worker import reimpl_spec_version
from conformance._corpus.loader import load_corpus
from conformance._engine import Outcome
from conformance._policy.divergences import known_divergences
from conformance._policy.guards import GUARDS
from conformance._policy.release_facts import (
    FactKind,
    Side,
    fact_side,
    recorded_crash,
    release_fact,
    release_facts,
    table_releases,
)
from conformance._run import release_facts_doc
from conformance._run.runner import run_case

ROOT = Path(__file__).resolve().parent.parent
FACTS = release_facts()
CASES = {c.qualified_name for f in load_corpus() for c in f.cases}
POLICY = resources.files("conformance._policy")
#: ``release.has("<id>")`` in reimpl's sources.
_SWITCH = re.compile(r"""release\.has\(\s*"([a-z0-9.-]+)"\s*\)""")


def _json(name: str) -> dict[str, object]:
    data: dict[str, object] = json.loads(POLICY.joinpath(name).read_text("utf-8"))
    return data


def test_the_table_is_valid_under_its_schema() -> None:
    schema = _json("release_facts.schema.json")
    jsonschema.Draft202012Validator.check_schema(schema)
    jsonschema.Draft202012Validator(schema).validate(_json("release_facts.json"))


def test_the_schema_describes_every_kind_of_release_fact() -> None:
    described = release_facts_doc.kind_descriptions()
    assert set(described) == set(FactKind)
    for title, description in described.values():
        assert title
        assert len(description) > 80


def test_a_row_missing_its_kind_s_field_is_refused_by_the_schema() -> None:
    schema = _json("release_facts.schema.json")
    table = _json("release_facts.json")
    crash = next(row for row in table["facts"] if row["kind"] == "crash")  # type: ignore[attr-defined]
    del crash["answer"]
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft202012Validator(schema).validate(table)


@pytest.mark.parametrize("fact_id", list(FACTS))
def test_every_row_names_evidence_that_exists(fact_id: str) -> None:
    fact = FACTS[fact_id]
    assert fact.scenarios or fact.tests
    for name in fact.scenarios:
        assert name in CASES, f"{fact_id}: no scenario {name!r}"
    for test in fact.tests:
        assert (ROOT / test.split("::")[0]).is_file(), f"{fact_id}: no test file {test}"


def test_every_switch_in_reimpl_names_a_row_of_the_table() -> None:
    switches = {
        fact_id
        for path in (ROOT / "reimpl").rglob("*.py")
        for fact_id in _SWITCH.findall(path.read_text("utf-8"))
    }
    assert switches, "reimpl reads the table"
    assert switches <= set(FACTS), switches - set(FACTS)


def test_every_guard_and_divergence_names_a_row() -> None:
    assert set(GUARDS) <= set(FACTS)
    assert {FACTS[g].kind for g in GUARDS} == {FactKind.CRASH}
    for entry in known_divergences():
        if entry.release_fact is not None:
            assert entry.releases == FACTS[entry.release_fact].releases, entry.id


def test_a_reference_names_a_side_of_a_row() -> None:
    fact, side = fact_side("before member-groups-since-1.27")
    assert (fact.id, side) == ("member-groups-since-1.27", Side.BEFORE)
    assert fact.side("1.26.0") is Side.BEFORE
    assert fact.side("1.27.0") is Side.HOLDS
    with pytest.raises(ValueError, match="has no after side"):
        fact_side("after member-groups-since-1.27")
    with pytest.raises(KeyError, match="no release fact 'no-such-row'"):
        release_fact("no-such-row")


def test_a_crash_is_the_release_s_answer_only_in_its_row_s_cases_and_releases() -> None:
    case = "models/model_errors > ignoring an undefined group is an error naming the scoped group"
    assert recorded_crash(case, "1.30.0") == "undefined-ignored-group-aborts"
    assert recorded_crash(case, "1.31.0") is None
    assert (
        recorded_crash("transient/table1 > Table 1 lines 1-7 hold step by step", "1.30.0") is None
    )


#: Segfaults of one release each, measured alone in a fresh process on every release from
#: 1.31.0 to 1.58.0 (the crash rows' summaries): (case, the release that crashes, its row,
#: the neighbouring releases that answer).
_ONE_RELEASE_CRASHES = [
    (
        "real_models/robot_models > drake_models/dishes/evo_bowl_compliant.urdf",
        "1.51.0",
        "vtk-mesh-segfaults-1.51.0",
        ("1.50.0", "1.51.1"),
    ),
    (
        "real_models/robot_models > drake_models/jaco_description/urdf/j2s7s300.urdf",
        "1.52.0",
        "mesh-file-segfaults-1.52.0",
        ("1.51.0", "1.51.1", "1.52.1"),
    ),
    (
        "real_models/drake_repository > drake/multibody/plant/test/deformable_box.sdf",
        "1.41.0",
        "deformable-continuous-plant-segfaults-1.41",
        ("1.40.0", "1.42.0"),
    ),
]


@pytest.mark.parametrize(("case", "crashes", "row", "answers"), _ONE_RELEASE_CRASHES)
def test_a_segfault_of_one_release_is_that_release_s_answer_alone(
    case: str, crashes: str, row: str, answers: tuple[str, ...]
) -> None:
    assert recorded_crash(case, crashes) == row
    for release in answers:
        assert recorded_crash(case, release) is None, release


def test_reimpl_follows_a_release_of_the_table_named_by_its_spec() -> None:
    span = table_releases()
    assert (span.since, span.until) == ("1.12.0", "1.58.0")
    assert reimpl_spec_version("reimpl==1.30.0") == "1.30.0"
    assert reimpl_spec_version("reimpl") is None


def _reimpl_at(release: str, code: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "REIMPL_DRAKE_RELEASE": release, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=False
    )


def test_reimpl_refuses_a_release_the_table_does_not_describe() -> None:
    done = _reimpl_at("1.11.0", "import reimpl.geometry")
    assert done.returncode != 0
    assert (
        "REIMPL_DRAKE_RELEASE='1.11.0': reimpl follows a Drake release from 1.12.0 to 1.58.0"
        in (done.stderr)
    )


#: Each release's answers (measured on pydrake 1.30.0 and 1.58.0): Activate is bound from
#: 1.55 (activation-since-1.55), Parser.GetCollisionFilterGroups from 1.31
#: (filter-groups-report-since-1.31); a second Finalize's wording (finalize-repeat-wording-
#: since-1.56); a failed DRAKE_DEMAND's path (demand-path-external-since-1.37).
_PROBE = """
from reimpl.geometry import CollisionFilterManager
from reimpl.multibody.plant import MultibodyPlant
from reimpl.common._drake_demand import demand_failure
from reimpl.multibody.parsing import Parser
print(hasattr(CollisionFilterManager, "Activate"), hasattr(Parser, "GetCollisionFilterGroups"))
plant = MultibodyPlant(0.0)
plant.Finalize()
try:
    plant.Finalize()
except RuntimeError as e:
    print(e)
print(demand_failure("a.cc", 1, "F", "c"))
"""


@pytest.mark.parametrize(
    ("release", "answers"),
    [
        (
            "1.30.0",
            [
                "False False",
                "MultibodyTreeSystem::Finalize(): repeated calls not allowed.",
                "Failure at a.cc:1 in F(): condition 'c' failed.",
            ],
        ),
        (
            "1.58.0",
            [
                "True True",
                "DeclareMiscContinuousState(): calls after Finalize() are not allowed.",
                "Failure at external/drake+/a.cc:1 in F(): condition 'c' failed.",
            ],
        ),
    ],
)
def test_reimpl_at_a_release_gives_that_release_s_recorded_answers(
    release: str, answers: list[str]
) -> None:
    done = _reimpl_at(release, _PROBE)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == answers


def test_docs_release_facts_md_is_what_the_table_gives() -> None:
    page = (ROOT / "docs" / "release_facts.md").read_text("utf-8")
    assert page == release_facts_doc.render(), "run: python -m conformance._run.release_facts_doc"
    for fact_id in FACTS:
        assert f"| `{fact_id}` |" in page


def test_no_hasattr_probe_decides_a_backend_s_capabilities() -> None:
    for name in ("scene_graph.py", "queries.py", "multibody.py", "reimpl_api.py"):
        text = (ROOT / "conformance" / "_backends" / name).read_text("utf-8")
        assert "hasattr(" not in text, name
    grammar = sorted((ROOT / "conformance" / "_grammar").glob("*.py"))
    assert grammar, "the grammar package moved: point this test at it"
    for path in grammar:
        assert "hasattr(" not in path.read_text("utf-8"), path.name


#: The cases of member-groups-since-1.27 whose expectations hold both sides, as the release
#: matrix measured them on 1.21-1.29 (docs/releases/report.md: 1.26.0 → 1.27.0).
_MEMBER_GROUP_CASES = [
    "models/urdf_groups > a member group adds its members to the group that names it, transitively",
    "models/urdf_groups > a cycle of member groups gives every group in it the union of their"
    " members",
    "models/urdf_groups > a group made of a member group and a link filters the nested members too",
    "models/sdf_groups > a member group named by its scoped name in a nested model adds its"
    " members",
]


@pytest.mark.parametrize("release", ["1.26.0", "1.27.0"])
def test_reimpl_at_a_release_reads_member_groups_as_that_release_does(release: str) -> None:
    cases = {c.qualified_name: c for f in load_corpus() for c in f.cases}
    backend = load_backend(f"reimpl=={release}")
    try:
        for name in _MEMBER_GROUP_CASES:
            report = run_case(cases[name], [backend])
            assert report.status[backend.name] is Outcome.PASS, (name, report.failures)
    finally:
        backend.close()  # type: ignore[attr-defined]


#: The cases of mjcf-eulerseq-since-1.25: arm.xml's eulerseq is a warning up to 1.24, so its
#: merge-include is dropped and the arm_mjcf model has no link; up to 1.22 the URDF merge is
#: refused first (sdf-merge-include-custom-parser-since-1.23). Each case expects the answer
#: of its release, as the release matrix measured them on 1.22.0-1.25.0.
_TOP_MERGE_INCLUDE_CASES = [
    "real_models/drake_repository > drake/multibody/parsing/test/sdf_parser_test/"
    f"interface_api_test/{name}.sdf"
    for name in (
        "top_merge_include",
        "top_merge_include_in_nested_model",
        "top_merge_include_world",
    )
]


@pytest.mark.parametrize("release", ["1.22.0", "1.24.0", "1.25.0"])
def test_reimpl_at_a_release_merge_includes_the_mujoco_arm_as_that_release_does(
    release: str,
) -> None:
    cases = {c.qualified_name: c for f in load_corpus() for c in f.cases}
    backend = load_backend(f"reimpl=={release}")
    try:
        for name in _TOP_MERGE_INCLUDE_CASES:
            report = run_case(cases[name], [backend])
            assert report.status[backend.name] is Outcome.PASS, (name, report.failures)
    finally:
        backend.close()  # type: ignore[attr-defined]


#: A MuJoCo body at euler="5.7 11.5 17.2" (degrees) in a free body: the first row of its
#: rotation in the parent, with no eulerseq, then with eulerseq="zyx", then eulerseq="abc".
_EULERSEQ_PROBE = """
import logging
from reimpl.multibody.plant import MultibodyPlant
from reimpl.multibody.parsing import Parser
logging.basicConfig(format="%(message)s")
body = (
    '<worldbody><body name="L1"><geom type="sphere" size="0.4"/><freejoint/>'
    '<body name="L2" euler="5.7295779513082321 11.459155902616466 17.188733853924695">'
    '<geom type="sphere" size="0.4"/><joint name="J1" type="hinge"/></body></body></worldbody>'
)
for compiler in ("", '<compiler eulerseq="zyx"/>', '<compiler eulerseq="abc"/>'):
    plant = MultibodyPlant(0.0)
    try:
        Parser(plant).AddModelsFromString(f'<mujoco model="arm">{compiler}{body}</mujoco>', "xml")
    except RuntimeError as e:
        print(e)
        continue
    plant.Finalize()
    X = plant.CalcRelativeTransform(
        plant.CreateDefaultContext(), plant.GetFrameByName("L1"), plant.GetFrameByName("L2")
    )
    print([round(float(v), 6) for v in X.rotation().matrix()[0]])
"""


@pytest.mark.parametrize(
    ("release", "rows", "warnings"),
    [
        (
            "1.24.0",
            [[0.936293, -0.275096, 0.218351]] * 3,
            ["<literal-string>.urdf:1: warning: The attribute 'eulerseq' found in a 'compiler' "
             "tag is currently unsupported and will be ignored."] * 2,
        ),
        (
            "1.25.0",
            [
                [0.936293, -0.289629, 0.198669],
                [0.97517, -0.036957, 0.218351],
                "<literal-string>.urdf:1: error: Illegal value 'abc' for the eulerseq in "
                "compiler. Valid eulerseq are exactly three characters from the set "
                "[x,y,z,X,Y,Z]",
            ],
            [],
        ),
    ],
)  # fmt: skip
def test_reimpl_at_a_release_reads_a_mujoco_eulerseq_as_that_release_does(
    release: str, rows: list[object], warnings: list[str]
) -> None:
    """Up to 1.24 eulerseq is ignored with a warning and euler is roll-pitch-yaw (extrinsic
    XYZ); from 1.25 it is read, the default intrinsic xyz (mjcf-eulerseq-since-1.25,
    measured on pydrake 1.24.0 and 1.25.0 with these bodies)."""
    done = _reimpl_at(release, _EULERSEQ_PROBE)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [str(r) for r in rows]
    assert done.stderr.splitlines() == warnings
