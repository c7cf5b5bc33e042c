"""``python -m conformance legacy-diff``: RigidBodyTree-era filtering of a URDF against
today's, through the backend machinery (pydrake by default, reimpl on request)."""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path
from typing import ClassVar

import pytest

from conformance._backends.loader import load_backend
from conformance._legacy_diff import Rule, legacy_diff
from conformance.cli.exit_codes import EXIT_OK, EXIT_USAGE
from conformance.cli.main import main
from conformance.protocol import MODEL, Command

#: A world floor; world -revolute- base -revolute- l1 (3 geometries) -fixed- l2 -fixed- l3;
#: l3 -floating- tool; an unprefixed group pair base/tool (and an undefined target).
ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="world">
    <collision name="floor"><geometry><box size="1 1 0.1"/></geometry></collision>
  </link>
  <link name="base"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="l1">
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
    <collision><geometry><box size="1 1 1"/></geometry></collision>
  </link>
  <link name="l2"><collision name="c"><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="l3"><collision name="c"><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="tool"><collision name="t"><geometry><sphere radius="1"/></geometry></collision></link>
  <joint name="j0" type="revolute"><parent link="world"/><child link="base"/></joint>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/></joint>
  <joint name="j2" type="fixed"><parent link="l1"/><child link="l2"/></joint>
  <joint name="j3" type="fixed"><parent link="l2"/><child link="l3"/></joint>
  <joint name="j4" type="floating"><parent link="l3"/><child link="tool"/></joint>
  <collision_filter_group name="ga">
    <member link="base"/>
    <ignored_collision_filter_group collision_filter_group="gb"/>
    <ignored_collision_filter_group collision_filter_group="nope"/>
  </collision_filter_group>
  <collision_filter_group name="gb">
    <member link="tool"/>
  </collision_filter_group>
</robot>
"""

#: Two bodies under a <drake:joint> ball (RBT: not read) and a drake: group pair.
MODERN_ONLY = """<robot name="m">
  <link name="a"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="c"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <drake:joint name="ball" type="ball"><parent link="a"/><child link="b"/></drake:joint>
  <drake:collision_filter_group name="x"><drake:member link="a"/>
    <drake:ignored_collision_filter_group name="y"/></drake:collision_filter_group>
  <drake:collision_filter_group name="y"><drake:member link="c"/></drake:collision_filter_group>
</robot>
"""


def run(argv: list[str]) -> tuple[int, str, str]:
    """``python -m conformance legacy-diff *argv``: exit code, stdout, stderr."""
    out, err = io.StringIO(), io.StringIO()
    code = main(["legacy-diff", *argv], out, err)
    return code, out.getvalue(), err.getvalue()


@pytest.fixture
def arm(tmp_path: Path) -> Path:
    path = tmp_path / "arm.urdf"
    path.write_text(ARM, encoding="utf-8")
    return path


class TestLegacyDiffExplainsEveryDifference:
    """Each differing pair is listed with the rule that explains it."""

    EXPECTED: ClassVar[dict[tuple[str, str], tuple[bool, Rule]]] = {
        ("WorldModelInstance::world/floor", "arm::base/Sphere"): (True, Rule.WORLD_ADJACENCY),
        ("arm::base/Sphere", "arm::tool/t"): (True, Rule.GROUP_SYNTAX),
        ("arm::l1/Box", "arm::l3/c"): (False, Rule.WELDED_SUBGRAPHS),
        ("arm::l1/Sphere", "arm::l3/c"): (False, Rule.WELDED_SUBGRAPHS),
        ("arm::l1/Sphere_1", "arm::l3/c"): (False, Rule.WELDED_SUBGRAPHS),
    }

    @pytest.mark.parametrize("spec", ["pydrake", "reimpl"])
    def test_the_arm(self, arm: Path, spec: str) -> None:
        diff = legacy_diff(arm, load_backend(spec))
        found = {d.pair: (d.legacy_filtered, d.explanations[0].rule) for d in diff.differences}
        assert found == self.EXPECTED
        assert all(len(d.explanations) == 1 for d in diff.differences)
        assert (len(diff.legacy_candidates), len(diff.modern_candidates)) == (16, 15)
        assert diff.legacy.groups.undefined_ignores == (("ga", "nope"),)

    def test_the_text_report(self, arm: Path) -> None:
        code, out, err = run([str(arm)])
        assert (code, err) == (EXIT_OK, "")
        assert "candidates: legacy 16, modern 15, in both 13" in out
        assert "5 pairs differ: world adjacency 1, welded subgraphs 3, group syntax 1" in out
        assert "      1  ga           0...0011   0...0100   arm::base" in out
        assert "joint 'j0' (revolute, line 15) joins the world" in out

    def test_the_json_report(self, arm: Path) -> None:
        code, out, _ = run([str(arm), "--json"])
        report = json.loads(out)
        assert code == EXIT_OK
        assert report["model"] == "arm"
        assert report["backend"]["name"] == "pydrake"
        assert report["summary"]["by_rule"]["unexplained"] == 0
        assert report["legacy"]["groups"][0] == {
            "name": "ga",
            "bit": 1,
            "membership": 0b11,
            "ignore": 0b100,
            "members": ["arm::base/Sphere"],
        }
        difference = report["differences"][0]
        assert difference["legacy"] == "filtered"
        assert difference["modern"] == "candidate"
        assert difference["rules"][0]["rule"] == "world adjacency"

    def test_all_pairs_side_by_side(self, arm: Path) -> None:
        code, out, _ = run([str(arm), "--all"])
        assert code == EXIT_OK
        assert "  candidate candidate  arm::l2/c" in out

    def test_drake_groups_and_drake_joints_explain_modern_only_filters(
        self, tmp_path: Path
    ) -> None:
        path = tmp_path / "m.urdf"
        path.write_text(MODERN_ONLY, encoding="utf-8")
        diff = legacy_diff(path, load_backend("pydrake"))
        rules = {d.pair: [e.rule for e in d.explanations] for d in diff.differences}
        assert rules == {
            ("m::a/Sphere", "m::b/Sphere"): [Rule.FLOATING_JOINTS],
            ("m::a/Sphere", "m::c/Sphere"): [Rule.GROUP_SYNTAX],
        }
        assert not any(d.legacy_filtered for d in diff.differences)


class TestTheUnprefixedSyntaxOnPydrake:
    """drake-semantics §6: the unprefixed <collision_filter_group> "is silently ignored by
    today's URDF parser. There is no warning and no filter"."""

    def test_it_parses_and_filters_nothing(self) -> None:
        backend = load_backend("pydrake")
        without = ARM.split("  <collision_filter_group", maxsplit=1)[0] + "</robot>\n"
        candidates = []
        for text in (ARM, without):
            backend.reset()
            result = backend.execute(
                Command("add_models", {"files": {"a.urdf": text}, "path": "a.urdf"})
            )
            assert result.error is None
            assert backend.execute(Command("collision_filter_groups", {})).value == {
                "groups": {},
                "pairs": [],
            }
            assert backend.execute(Command("finalize", {})).error is None
            candidates.append(backend.observe().locations[MODEL].candidates)
        assert candidates[0] == candidates[1]
        assert len(candidates[0]) == 15


class TestInputErrorsExitTwo:
    """Exit 2 with a message naming the file (and the element) for bad input."""

    def test_a_missing_file(self, tmp_path: Path) -> None:
        code, out, err = run([str(tmp_path / "nope.urdf")])
        assert (code, out) == (EXIT_USAGE, "")
        assert err.startswith(f"error: {tmp_path / 'nope.urdf'}: cannot read the file")

    def test_malformed_xml(self, tmp_path: Path) -> None:
        path = tmp_path / "bad.urdf"
        path.write_text('<robot name="r">\n<link name="a">\n</robot>\n', encoding="utf-8")
        code, _, err = run([str(path)])
        assert code == EXIT_USAGE
        assert err == f"error: {path}:3: malformed XML: mismatched tag\n"

    def test_an_unknown_link_in_a_legacy_group(self, arm: Path) -> None:
        arm.write_text(
            ARM.replace('<member link="tool"/>', '<member link="hand"/>'), encoding="utf-8"
        )
        code, _, err = run([str(arm)])
        assert code == EXIT_USAGE
        assert err == (
            f'error: {arm}:26: <member link="hand"> of <collision_filter_group name="gb">: '
            "robot 'arm' has no link named 'hand'\n"
        )

    def test_a_model_the_modern_parser_refuses(self, tmp_path: Path) -> None:
        path = tmp_path / "m.urdf"
        path.write_text(
            MODERN_ONLY.replace('<drake:member link="a"/>', '<drake:member link="zz"/>'),
            encoding="utf-8",
        )
        code, _, err = run([str(path)])
        assert code == EXIT_USAGE
        assert err.startswith(f"error: {path}: pydrake refused the model: m.urdf:")
        assert "'m::zz' not found" in err

    def test_an_unknown_backend(self, arm: Path) -> None:
        code, _, err = run([str(arm), "--backend", "nonsense"])
        assert code == EXIT_USAGE
        assert "unknown backend 'nonsense'" in err


def test_python_m_conformance_runs_it(arm: Path) -> None:
    """The real entry point: exit 0 with the report on stdout, exit 2 for a missing file."""
    done = subprocess.run(
        [sys.executable, "-m", "conformance", "legacy-diff", str(arm), "--json"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == EXIT_OK
    assert json.loads(done.stdout)["summary"]["differences"] == 5
    missing = subprocess.run(
        [sys.executable, "-m", "conformance", "legacy-diff", str(arm.with_name("x.urdf"))],
        capture_output=True,
        text=True,
        check=False,
    )
    assert missing.returncode == EXIT_USAGE
    assert "x.urdf: cannot read the file" in missing.stderr
