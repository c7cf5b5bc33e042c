"""The wheel's layout: the corpus inside the package namespace, found in a clone and installed.

The repository keeps the corpus at its top (``scenarios/``); the wheel ships it as
``conformance/_scenarios`` (pyproject.toml's package-dir mapping), so an install adds no
top-level ``scenarios``. Building a real wheel is CI's wheel step (.ci/run); here the
installed layout is made by copying the package beside a link to the corpus.
"""

from __future__ import annotations

import io
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from conformance._corpus.loader import default_corpus_root, load_corpus
from conformance._corpus_root import INSTALLED_NAME, corpus_root, is_installed
from conformance.cli.main import main

REPO = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((REPO / "pyproject.toml").read_text(encoding="utf-8"))


def test_the_wheel_lists_every_package_of_the_clone_and_the_corpus_under_conformance() -> None:
    listed = set(PYPROJECT["tool"]["setuptools"]["packages"])
    on_disk = {
        ".".join(init.parent.relative_to(REPO).parts)
        for top in ("reimpl", "conformance")
        for init in (REPO / top).rglob("__init__.py")
    }
    assert listed == on_disk | {"conformance._scenarios", "conformance._examples"}
    assert PYPROJECT["tool"]["setuptools"]["package-dir"] == {
        "conformance._scenarios": "scenarios",
        "conformance._examples": "examples",
    }
    assert not any(p == "scenarios" or p.startswith("scenarios.") for p in listed)


def test_in_a_clone_the_corpus_is_the_top_level_scenarios_folder() -> None:
    assert corpus_root() == REPO / "scenarios"
    assert default_corpus_root() == REPO / "scenarios"
    assert not is_installed()


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A site folder laid out as the wheel installs: conformance/ with _scenarios inside."""
    site = tmp_path_factory.mktemp("site")
    shutil.copytree(
        REPO / "conformance", site / "conformance", ignore=shutil.ignore_patterns("__pycache__")
    )
    (site / "conformance" / INSTALLED_NAME).symlink_to(REPO / "scenarios")
    (site / "conformance" / "_examples").symlink_to(REPO / "examples")
    (site / "reimpl").symlink_to(REPO / "reimpl")
    return site


def _python(site: Path, *args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(site)}
    return subprocess.run(
        [sys.executable, *args], cwd=cwd, env=env, capture_output=True, text=True, check=False
    )


def test_installed_the_corpus_is_conformance_scenarios_and_loads_whole(
    installed: Path, tmp_path: Path
) -> None:
    done = _python(
        installed,
        "-c",
        "from conformance._corpus.loader import load_corpus, default_corpus_root\n"
        "from conformance._corpus_root import is_installed\n"
        "print(default_corpus_root(), is_installed())\n"
        "print(sum(len(f.cases) for f in load_corpus()))",
        cwd=tmp_path,
    )
    assert done.returncode == 0, done.stderr
    root, count = done.stdout.splitlines()
    assert root == f"{installed / 'conformance' / '_scenarios'} True"
    assert int(count) == sum(len(f.cases) for f in load_corpus())


def test_schema_write_refuses_an_installed_package(installed: Path, tmp_path: Path) -> None:
    schema = installed / "conformance" / "_scenarios" / "scenario.schema.json"
    before = schema.read_bytes()
    done = _python(installed, "-m", "conformance", "schema", "--write", cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr == (
        "error: schema --write writes the schema files of a clone (scenarios/, "
        "conformance/protocol_schemas/); this conformance is installed in "
        f"{installed / 'conformance'}, not a clone: print the schema with `schema` instead\n"
    )
    assert schema.read_bytes() == before


def test_installed_new_backend_writes_the_skeleton_that_runs_as_a_backend(
    installed: Path, tmp_path: Path
) -> None:
    done = _python(installed, "-m", "conformance", "new-backend", "mine", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    written = tmp_path / "mine" / "my_backend.py"
    assert written.read_bytes() == (REPO / "examples" / "my_backend.py").read_bytes()
    assert done.stdout.splitlines()[-1] == (
        "    python -m conformance run --backend mine.my_backend:MyBackend --backend pydrake"
    )
    table1 = installed / "conformance" / "_scenarios" / "transient" / "table1.json"
    run = _python(
        installed, "-m", "conformance", "run", str(table1),
        "--backend", "mine.my_backend:MyBackend", "--backend", "reimpl", "-q",
        cwd=tmp_path,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines()[-1].split()[:4] == ["total", "2", "2", "pass,"]
    assert "mine" in run.stdout


def test_new_backend_never_overwrites_a_skeleton_and_exits_2(tmp_path: Path) -> None:
    (tmp_path / "my_backend.py").write_text("# mine\n", encoding="utf-8")
    out, err = io.StringIO(), io.StringIO()
    assert main(["new-backend", str(tmp_path)], out=out, err=err) == 2
    assert (
        err.getvalue()
        == f"error: {tmp_path / 'my_backend.py'} exists already (nothing was written)\n"
    )
    assert (tmp_path / "my_backend.py").read_text(encoding="utf-8") == "# mine\n"
