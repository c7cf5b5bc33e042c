"""conformance._fuzz.models draws kinematic trees that pydrake parses as drawn; ``fuzz --models``
compares them on two backends and writes a shrunk finding that ``run`` replays."""

from __future__ import annotations

import dataclasses
import io
import logging
from collections.abc import Iterator
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import seed as hypothesis_seed
from pydrake.geometry import GeometryId, SceneGraph
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import MultibodyPlant

from conformance._backends.loader import load_backend
from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.reimpl_api import reimpl_api
from conformance._backends.scene_graph import SceneGraphBackend
from conformance._corpus.loader import load_file
from conformance._engine import HarnessError
from conformance._fuzz import models as fm
from conformance._fuzz.model_campaign import ModelCampaign, model_cases
from conformance._fuzz.model_coverage import MODEL_FEATURES
from conformance._fuzz.models import Body, Geometry, Group, Joint, Model
from conformance._testing.model_mutants import MODEL_MUTANTS, model_mutant_backend
from conformance.cli.main import EXIT_FAILURE, EXIT_OK, EXIT_USAGE, main
from conformance.protocol import Command
from reimpl.multibody import tree as reimpl_tree

PYDRAKE = load_backend("pydrake")
SETTINGS = settings(
    max_examples=60, deadline=None, database=None, suppress_health_check=list(HealthCheck)
)


@pytest.fixture(autouse=True)
def _quiet_drake() -> Iterator[None]:
    """Drake warns about URDF floating joints and renamed geometry; the tests need no log."""
    logger = logging.getLogger("drake")
    level = logger.level
    logger.setLevel(logging.ERROR)
    yield
    logger.setLevel(level)


def candidates(text: str, fmt: str, *, adjacent: bool = True) -> set[tuple[str, str]]:
    """pydrake's candidate pairs after parsing ``text`` and Finalize, as ``body/geometry``."""
    scene_graph = SceneGraph()
    plant = MultibodyPlant(time_step=0.0)
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    plant.set_adjacent_bodies_collision_filters(adjacent)
    Parser(plant).AddModelsFromString(text, fmt)
    plant.Finalize()
    inspector = scene_graph.model_inspector()

    def name(geometry_id: GeometryId) -> str:
        body = plant.GetBodyFromFrameId(inspector.GetFrameId(geometry_id))
        return f"{body.name()}/{inspector.GetName(geometry_id).split('::')[-1]}"

    return {
        tuple(sorted((name(a), name(b))))  # type: ignore[misc]
        for a, b in inspector.GetCollisionCandidates()
    }


#: l0 welded to the world, l1 revolute on it, l2 prismatic on l1, l3 free with l4 on a
#: universal joint; g0 = {l2} + member group g1 = {l3} ignores g1 (a forward reference).
FIXED = Model(
    "m",
    (
        Body("l0", (Geometry("sphere"), Geometry("box", "c0"))),
        Body("l1", (Geometry("sphere", "c1"), Geometry("box", collision=False))),
        Body("l2", (Geometry("cylinder", "c2"),)),
        Body("l3", (Geometry("sphere", "c0"),)),
        Body("l4", (Geometry("box", "c0"),)),
        Body("l5", (Geometry("sphere", "v", collision=False),)),
    ),
    (
        Joint("j0", "fixed", fm.WORLD, "l0"),
        Joint("j1", "revolute", "l0", "l1"),
        Joint("j2", "prismatic", "l1", "l2"),
        Joint("j3", "universal", "l3", "l4"),
        Joint("j4", "ball", "l4", "l5"),
    ),
    (Group("g0", ("l2",), ("g1",), ("g1",)), Group("g1", ("l3",))),
)
#: Adjacent pairs (l0-l1, l1-l2, l3-l4) and the group pair (l2-l3) are filtered.
FIXED_URDF_PAIRS = {
    ("l0/Sphere", "l2/c2"),
    ("l0/c0", "l2/c2"),
    ("l0/Sphere", "l3/c0"),
    ("l0/c0", "l3/c0"),
    ("l0/Sphere", "l4/c0"),
    ("l0/c0", "l4/c0"),
    ("l1/c1", "l3/c0"),
    ("l1/c1", "l4/c0"),
    ("l2/c2", "l4/c0"),
}


def test_a_fixed_model_renders_to_urdf_that_pydrake_filters_as_drawn() -> None:
    text = fm.to_urdf(FIXED)
    assert 'xmlns:drake="http://drake.mit.edu"' in text
    assert '<drake:member_group name="g1" />' in text
    assert candidates(text, "urdf") == FIXED_URDF_PAIRS


def test_a_fixed_model_renders_to_sdf_with_text_members_and_named_collisions() -> None:
    text = fm.to_sdf(FIXED)
    assert "<drake:member>l2</drake:member>" in text
    assert '<collision name="collision0">' in text  # l0's unnamed sphere
    renamed = {
        tuple(p.replace("l0/Sphere", "l0/collision0") for p in pair) for pair in FIXED_URDF_PAIRS
    }
    assert candidates(text, "sdf") == renamed


def test_without_adjacency_filters_only_welds_and_groups_filter() -> None:
    pairs = candidates(fm.to_urdf(FIXED), "urdf", adjacent=False)
    assert pairs - FIXED_URDF_PAIRS == {
        ("l0/Sphere", "l1/c1"),
        ("l0/c0", "l1/c1"),
        ("l1/c1", "l2/c2"),
        ("l3/c0", "l4/c0"),
    }
    assert pairs >= FIXED_URDF_PAIRS


def test_ignore_1_drops_a_group_in_sdformat_but_not_in_urdf() -> None:
    group = Group("g0", ("l0", "l1"), ignored=("g0",), ignore="1")
    model = Model(
        "m", (Body("l0", (Geometry("sphere", "c"),)), Body("l1", (Geometry("box", "c"),)))
    )
    model = Model(model.name, model.bodies, groups=(group,))
    assert (fm.drops(group, "urdf"), fm.drops(group, "sdf")) == (False, True)
    assert candidates(fm.to_urdf(model), "urdf") == set()
    assert candidates(fm.to_sdf(model), "sdf") == {("l0/c", "l1/c")}


#: Model ``m`` with links a, b and a nested model ``n0`` with links a, b joined by a weld;
#: a revolute from m's b to n0's a; m's group g = {a, n0::b} + member group n0::h ignores
#: itself, where n0::h = {a} (n0's own a).
NESTED = Model(
    "m",
    (Body("a", (Geometry("sphere", "c"),)), Body("b", (Geometry("box", "c"),))),
    (Joint("j0", "revolute", "b", "n0::a"),),
    (Group("g", ("a", "n0::b"), ("n0::h",), ("g",)),),
    (
        Model(
            "n0",
            (Body("a", (Geometry("sphere", "c"),)), Body("b", (Geometry("box", "c"),))),
            (Joint("n0j0", "fixed", "a", "b"),),
            (Group("h", ("a",)),),
        ),
    ),
)


def test_a_nested_model_renders_to_sdf_with_scoped_names_that_pydrake_resolves() -> None:
    text = fm.to_sdf(NESTED)
    assert "<drake:member_group>n0::h</drake:member_group>" in text
    assert "<child>n0::a</child>" in text
    # g = {m::a, m::n0::b, m::n0::a} excludes within; n0's weld filters n0::a-n0::b, and the
    # revolute b-n0::a; only m::a-m::b and m::b-m::n0::b stay candidates.
    assert candidates(text, "sdf") == {("a/c", "b/c"), ("b/c", "b/c")}
    assert fm.geometry_names(NESTED, "sdf") == ["m::a/c", "m::b/c", "m::n0::a/c", "m::n0::b/c"]
    with pytest.raises(ValueError, match="URDF has no nested models"):
        fm.to_urdf(NESTED)


def test_geometry_names_lists_only_names_drake_does_not_choose() -> None:
    assert fm.geometry_names(FIXED, "urdf") == [
        "m::l0/c0",
        "m::l1/c1",
        "m::l2/c2",
        "m::l3/c0",
        "m::l4/c0",
    ]
    assert fm.geometry_names(FIXED, "sdf")[:2] == ["m::l0/collision0", "m::l0/c0"]
    assert "m::l5/v" in fm.geometry_names(FIXED, "urdf", visual=True)


@pytest.mark.parametrize(
    ("formats", "nested"), [(("urdf", "sdf"), 0), (("urdf",), 0), (("sdf",), 2)]
)
def test_every_drawn_valid_tree_parses_and_finalizes_on_pydrake(
    formats: tuple[str, ...], nested: int
) -> None:
    @SETTINGS
    @given(fm.kinematic_trees(formats=formats, max_nested=nested))
    def parses(model: Model) -> None:
        for fmt in formats:
            candidates(fm.render(model, fmt), fmt)

    parses()


@pytest.mark.parametrize("fmt", fm.FORMATS)
def test_every_drawn_invalid_tree_is_refused_by_pydrake(fmt: str) -> None:
    @SETTINGS
    @given(fm.kinematic_trees(formats=(fmt,), invalid=True, max_nested=2 if fmt == "sdf" else 0))
    def refused(model: Model) -> None:
        # A failed DRAKE_DEMAND is a SystemExit (a URDF lower limit above the upper); a
        # URDF scale of two values a ValueError; the rest RuntimeErrors.
        with pytest.raises((RuntimeError, ValueError, SystemExit)):
            candidates(fm.render(model, fmt), fmt)

    refused()


def _drawn(seed: int) -> list[Model]:
    out: list[Model] = []

    @hypothesis_seed(seed)
    @SETTINGS
    @given(fm.kinematic_trees())
    def draw(model: Model) -> None:
        out.append(model)

    draw()
    return out


def test_trees_are_deterministic_for_a_seed() -> None:
    first = _drawn(7)
    assert first == _drawn(7)
    assert first != _drawn(8)


def test_trees_reach_every_joint_kind_both_world_attachments_and_group_cycles() -> None:
    models = _drawn(1) + _drawn(2)
    joints = [j for m in models for j in m.joints]
    urdf_only = {"floating", "planar", "drake_planar", "curvilinear"}
    assert {j.kind for j in joints} == set(fm.JOINT_KINDS) - urdf_only
    assert any(j.parent == fm.WORLD for j in joints)
    assert any(g.name in g.ignored for m in models for g in m.groups)
    assert any(
        a.name in b.member_groups and b.name in a.member_groups
        for m in models
        for a in m.groups
        for b in m.groups
        if a != b
    )
    urdf = [j for seed in (1, 2) for m in _urdf_trees(seed) for j in m.joints]
    assert {j.kind for j in urdf} == set(fm.JOINT_KINDS)
    assert any(j.child == fm.WORLD for j in urdf)


def _urdf_trees(seed: int) -> list[Model]:
    out: list[Model] = []

    @hypothesis_seed(seed)
    @SETTINGS
    @given(fm.kinematic_trees(formats=("urdf",)))
    def draw(model: Model) -> None:
        out.append(model)

    draw()
    return out


# ------------------------------------------------------------------ fuzz --models
def _cases(seed: int) -> list[list[Command]]:
    out: list[list[Command]] = []

    @hypothesis_seed(seed)
    @SETTINGS
    @given(model_cases())
    def draw(commands: list[Command]) -> None:
        out.append(commands)

    draw()
    return out


def test_model_cases_are_deterministic_for_a_seed_and_report_after_every_parse() -> None:
    first = _cases(3)
    assert first == _cases(3)
    assert first != _cases(4)
    for commands in first:
        ops = [c.op for c in commands]
        assert ops.count("add_models") >= 1
        for at, op in enumerate(ops):
            if op == "add_models":
                assert ops[at + 1 : at + 3] == ["collision_filter_groups", "model_inventory"]
        assert ops[-1] == "check"
        assert ops.index("model_inventory", ops.index("finalize")) > ops.index("finalize")


@pytest.mark.fuzz
def test_two_pydrake_backends_agree_on_100_random_model_cases() -> None:
    twin = SceneGraphBackend(dataclasses.replace(pydrake_api(), name="pydrake-twin"))
    result = ModelCampaign(
        backend=lambda: twin, reference=lambda: PYDRAKE, seed=2, max_examples=100
    ).run()
    assert result.divergences == []
    assert result.stats.examples == 100


def test_fuzz_models_needs_the_model_features_of_both_backends() -> None:
    bare = SceneGraphBackend(dataclasses.replace(reimpl_api(), name="no-parser", parsing=None))
    campaign = ModelCampaign(backend=lambda: bare, reference=lambda: PYDRAKE, max_examples=1)
    with pytest.raises(HarnessError, match="needs the feature"):
        campaign.run()


def fuzz(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    code = main(["fuzz", "--models", *argv], out=out, err=err)
    return code, out.getvalue(), err.getvalue()


def run(*argv: str) -> int:
    return main(["run", *argv, "-q"], out=io.StringIO(), err=io.StringIO())


#: reimpl answers as Drake 1.51.1 does. Against another release a campaign finds the
#: release's changes first: on 1.58.0 a URDF joint without <origin> adds no
#: '<joint>_parent' frame, which 1.51.1 adds (both measured; model_inventory shows it).
SAME_RELEASE = pytest.mark.skipif(
    PYDRAKE.version() != load_backend("reimpl").version(),
    reason="reimpl answers as 1.51.1; the campaign would find the release's changes",
)


@SAME_RELEASE
def test_fuzz_models_of_reimpl_against_pydrake_exits_0_and_writes_nothing(tmp_path: Path) -> None:
    out_dir = tmp_path / "r"
    code, out, err = fuzz("--seed", "3", "--max-examples", "50", "--out", str(out_dir))
    assert code == EXIT_OK, out + err
    assert "50 examples" in out
    assert "0 divergence(s)" in out
    assert err.startswith("fuzz --models: reimpl")
    assert not out_dir.exists()


MUTANT = "conformance._testing.model_mutants:rpy_floating_unfiltered"
#: Seeds 1-6 all meet the mutant's bug (an RpyFloatingJoint between two bodies with
#: collision geometry) within 300 examples; seed 2 takes 156 runs, shrinking included.
SEED_2 = ("--seed", "2", "--max-examples", "300")


@pytest.mark.mutant_proof
@SAME_RELEASE
def test_fuzz_models_catches_the_rpy_floating_mutant_with_a_shrunk_file_that_replays(
    tmp_path: Path,
) -> None:
    code, out, _ = fuzz(
        "--backend", MUTANT, "--seed", "3", "--max-examples", "300", "--out", str(tmp_path),
    )  # fmt: skip
    assert code == EXIT_FAILURE
    assert "(reproduces)" in out
    (path,) = tmp_path.glob("*.json")
    assert path.name.startswith("models-")
    (case,) = load_file(path, root=tmp_path).cases
    # Shrunk: a parsed model and its reports, a body added on an RpyFloatingJoint, Finalize
    # and the inventory after it, where pydrake lists 'DefaultModelInstance::J0
    # (rpy_floating)' and the mutant the joint's type as quaternion_floating.
    ops = [s.op for s in case.steps]
    assert ops[0] == "add_models"
    assert ops[-3:] == ["add_joint", "finalize", "model_inventory"]
    assert len(ops) <= 9
    assert case.steps[-3].args["type"] == "rpy_floating"
    joints = case.steps[-1].expect[0]["returns"]["joints"]
    assert "DefaultModelInstance::J0 (rpy_floating)" in joints
    assert "fuzz --models --backend" in (path.read_text())
    assert run(str(path), "--backend", MUTANT, "--backend", "pydrake") == EXIT_FAILURE
    assert run(str(path), "--backend", MUTANT) == EXIT_FAILURE
    assert run(str(path), "--backend", "reimpl", "--backend", "pydrake") == EXIT_OK


@pytest.mark.mutant_proof
@SAME_RELEASE
def test_the_same_seed_gives_the_same_model_finding(tmp_path: Path) -> None:
    found = []
    for attempt in ("a", "b"):
        folder = tmp_path / attempt
        code, out, _ = fuzz(
            "--backend", MUTANT, "--seed", "3", "--max-examples", "300", "--out", str(folder),
            )  # fmt: skip
        assert code == EXIT_FAILURE
        (path,) = folder.glob("*.json")
        found.append((path.name, path.read_text(), out.splitlines()[-1].split(" in ")[0]))
    assert found[0] == found[1]


def test_a_model_mutant_leaves_plain_reimpl_alone() -> None:
    mutant = model_mutant_backend("rpy_floating_unfiltered")
    assert mutant.api.tree is not None
    assert mutant.api.tree.RpyFloatingJoint.kTypeName == "quaternion_floating"
    assert reimpl_tree.RpyFloatingJoint.kTypeName == "rpy_floating"
    assert len(MODEL_MUTANTS) >= 11


def test_without_needs_models_and_names_known_grammar_elements(tmp_path: Path) -> None:
    code, _, err = fuzz("--without", "nope", "--max-examples", "1", "--out", str(tmp_path))
    assert code == EXIT_USAGE
    assert "--without: unknown model grammar element(s) nope" in err
    out, err_io = io.StringIO(), io.StringIO()
    argv = ["fuzz", "--without", "packages", "--max-examples", "1", "--out", str(tmp_path)]
    assert main(argv, out=out, err=err_io) == EXIT_USAGE
    assert "--without leaves out model grammar elements: it needs --models" in err_io.getvalue()


@pytest.mark.fuzz
@SAME_RELEASE
def test_fuzz_models_reaches_every_grammar_feature_at_seed_1_in_300_examples(
    tmp_path: Path,
) -> None:
    """reimpl against pydrake 1.51.1, the campaign CI runs: no divergence, and every feature
    of the table reached (measured: the least reached in 9 cases, about 45 s)."""
    code, out, err = fuzz(
        "--seed", "1", "--max-examples", "300", "--coverage", "--out", str(tmp_path)
    )
    assert code == EXIT_OK, out + err
    count = len(MODEL_FEATURES)
    assert f"coverage: {count} of {count} model grammar features reached" in out
    assert "gaps: none" in out
