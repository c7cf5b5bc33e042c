"""``cache list|prune|path`` and the environments' last use, on fake environments in tmp_path.

A fake environment has the layout the cache code recognises (``drake-X.Y.Z-pyA.B/`` with
``.complete`` holding the requirements, ``.last-used``), and files of known size; no Drake
is installed. The suite's own cache is a temporary folder (tests/conftest.py).
"""

from __future__ import annotations

import fcntl
import io
import os
import re
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

import conformance
from conformance._backends.env_cache import (
    TYPICAL_ENVIRONMENT_BYTES,
    cached_environments,
    disk_note,
    disk_usage,
    missing_releases,
)
from conformance._backends.environments import (
    CACHE_VARIABLE,
    ENV_PATH_VARIABLE,
    LAST_USED,
    cache_dir,
    ensure_environment,
    find_uv,
    harness_path,
    requirements_for,
)
from conformance.cli.main import main
from tests.conftest import REAL_CACHE_VARIABLE

DAY = 86400.0
MB = 10**6
PYTHON = f"{sys.version_info.major}.{sys.version_info.minor}"


def fake_environment(
    root: Path, release: str, *, days_ago: float, size: int = MB, complete: bool = True
) -> Path:
    """An environment folder for ``release``, last used ``days_ago``, holding ``size`` bytes."""
    path = root / f"drake-{release}-py{PYTHON}"
    (path / "bin").mkdir(parents=True)
    (path / "lib.bin").write_bytes(os.urandom(size))
    when = time.time() - days_ago * DAY
    stamps = [LAST_USED, ".complete"] if complete else [LAST_USED]
    for stamp in stamps:
        (path / stamp).write_text("\n".join(requirements_for(release)) + "\n")
        os.utime(path / stamp, (when, when))
    return path


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    root = tmp_path / "cache"
    root.mkdir()
    monkeypatch.setenv(CACHE_VARIABLE, str(root))
    monkeypatch.delenv(ENV_PATH_VARIABLE, raising=False)
    return root


def _cli(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    code = main(["cache", *argv], out=out, err=err)
    return code, out.getvalue(), err.getvalue()


def test_the_suite_writes_its_cache_under_a_temporary_folder() -> None:
    real = Path(os.environ[REAL_CACHE_VARIABLE])
    assert cache_dir() != real
    assert cache_dir().name.startswith("drake-filter-conformance-tests-")
    assert str(real) in os.environ[ENV_PATH_VARIABLE].split(os.pathsep)


def test_cache_path_prints_the_folder_the_variable_names(cache: Path) -> None:
    assert _cli("path") == (0, f"{cache}\n", "")


def test_cache_list_shows_release_python_size_and_last_use_most_recent_first(
    cache: Path,
) -> None:
    fake_environment(cache, "1.40.0", days_ago=3, size=2 * MB)
    fake_environment(cache, "1.45.0", days_ago=0.5, size=MB)
    fake_environment(cache, "1.30.0", days_ago=30, size=MB, complete=False)
    (cache / "drake-1.40.0-py3.11.lock").touch()
    (cache / "harness").mkdir()  # not an environment
    code, out, err = _cli("list")
    assert (code, err) == (0, "")
    lines = out.splitlines()
    assert [line.split()[0] for line in lines[:3]] == [
        "drake==1.45.0",
        "drake==1.40.0",
        "drake==1.30.0",
    ]
    assert f"Python {PYTHON}" in lines[0]
    assert lines[0].endswith("(today)")
    assert lines[1].endswith("(3 days ago)")
    assert lines[2].endswith("(30 days ago)  (incomplete)")
    sizes = {e.release: e.size for e in cached_environments(cache)}
    assert 2 * MB <= sizes["1.40.0"] < 2 * MB + 64 * 1024  # allocated blocks of the file
    assert MB <= sizes["1.45.0"] < MB + 64 * 1024
    assert " 2.0 MB  last used" in lines[1]
    total = rf"3 environment\(s\), 4\.[01] MB on disk in {re.escape(str(cache))}"
    assert re.fullmatch(total, lines[3])  # 4 MB of files, and the folders' blocks


def test_a_file_hard_linked_into_two_environments_is_counted_once_in_the_total(
    cache: Path,
) -> None:
    first = fake_environment(cache, "1.40.0", days_ago=1, size=MB)
    second = fake_environment(cache, "1.45.0", days_ago=1, size=0)
    os.link(first / "lib.bin", second / "shared.bin")
    each = [disk_usage([first]), disk_usage([second])]
    assert each[1] >= MB  # the link is in the second environment's size too
    assert disk_usage([first, second]) < sum(each) - MB + 1


def test_prune_keep_removes_all_but_the_n_most_recently_used(cache: Path) -> None:
    for release, days in (("1.30.0", 9), ("1.40.0", 1), ("1.45.0", 5), ("1.51.1", 2)):
        fake_environment(cache, release, days_ago=days)
    code, out, err = _cli("prune", "--keep", "2")
    assert (code, err) == (0, "")
    assert sorted(p.name for p in cache.iterdir() if p.is_dir()) == [
        f"drake-1.40.0-py{PYTHON}",
        f"drake-1.51.1-py{PYTHON}",
    ]
    assert out.splitlines()[-1].startswith("removed 2 environment(s), 2.0 MB; kept 2")
    assert [line.split()[1] for line in out.splitlines()[:2]] == ["drake==1.45.0", "drake==1.30.0"]


def test_prune_older_than_removes_those_unused_for_more_than_the_days_given(
    cache: Path,
) -> None:
    fake_environment(cache, "1.30.0", days_ago=40)
    fake_environment(cache, "1.40.0", days_ago=8)
    fake_environment(cache, "1.45.0", days_ago=2)
    code, out, _ = _cli("prune", "--older-than", "7", "--dry-run")
    assert code == 0
    assert out.splitlines()[-1].startswith("would remove 2 environment(s)")
    assert len(cached_environments(cache)) == 3  # a dry run removes nothing
    assert _cli("prune", "--older-than", "7")[0] == 0
    assert [e.release for e in cached_environments(cache)] == ["1.45.0"]


def test_prune_leaves_an_environment_another_process_is_building_and_exits_2(
    cache: Path,
) -> None:
    building = fake_environment(cache, "1.30.0", days_ago=9, complete=False)
    fake_environment(cache, "1.40.0", days_ago=1)
    with (cache / f"{building.name}.lock").open("w") as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        code, out, err = _cli("prune", "--keep", "1")
    assert code == 2
    assert err == f"error: {building} is in use by another process (left in place)\n"
    assert building.is_dir()
    assert out.splitlines()[-1].startswith("removed 0 environment(s), 0 B; kept 1")


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (("prune",), "one of the arguments --keep --older-than is required"),
        (("prune", "--keep", "-1"), "argument --keep: must be 0 or more, got -1"),
        (("prune", "--keep", "two"), "argument --keep: not a whole number: 'two'"),
        (("prune", "--older-than", "nan"), "argument --older-than: must be 0 or more days"),
        (("prune", "--keep", "1", "--older-than", "3"), "not allowed with argument --keep"),
        (("tidy",), "invalid choice: 'tidy'"),
    ],
)
def test_bad_cache_arguments_exit_2_saying_why(
    cache: Path, capsys: pytest.CaptureFixture[str], argv: tuple[str, ...], message: str
) -> None:
    fake_environment(cache, "1.40.0", days_ago=1)
    with pytest.raises(SystemExit) as exited:
        _cli(*argv)
    assert exited.value.code == 2
    assert message in capsys.readouterr().err
    assert len(cached_environments(cache)) == 1


def test_using_an_environment_stamps_its_last_use(cache: Path) -> None:
    path = fake_environment(cache, "1.40.0", days_ago=20)
    before = (path / LAST_USED).stat().st_mtime
    environment = ensure_environment("1.40.0", python=sys.executable)
    assert environment.path == path
    assert (path / LAST_USED).stat().st_mtime > before + 19 * DAY


def test_an_environment_of_a_read_only_cache_is_used_and_never_written(
    cache: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    shared = tmp_path / "shared"
    path = fake_environment(shared, "1.40.0", days_ago=20)
    listing = sorted(p.name for p in shared.rglob("*"))
    stamp = (path / LAST_USED).stat().st_mtime
    monkeypatch.setenv(ENV_PATH_VARIABLE, str(shared))
    assert ensure_environment("1.40.0", python=sys.executable).path == path
    assert sorted(p.name for p in shared.rglob("*")) == listing  # no lock file, no stamp
    assert (path / LAST_USED).stat().st_mtime == stamp
    assert missing_releases(["1.40.0", "1.45.0"]) == ["1.45.0"]
    assert not any(cache.iterdir())


def test_a_matrix_of_many_new_environments_says_the_disk_they_take(cache: Path) -> None:
    releases = [f"1.{minor}.0" for minor in range(30, 42)]  # 12 releases
    assert disk_note(releases) == (
        f"12 release environments to build in {cache}: about 5.4 GB on disk (450.0 MB each, "
        "a typical environment; less where uv hard-links the files they share); "
        "`python -m conformance cache prune` removes them"
    )
    assert TYPICAL_ENVIRONMENT_BYTES == 450 * MB
    fake_environment(cache, "1.30.0", days_ago=1, size=3 * MB)
    note = disk_note(releases)
    assert note is not None
    assert note.startswith("11 release environments to build")
    assert "(3.0 MB each, the median of the 1 cached;" in note
    fake_environment(cache, "1.31.0", days_ago=1)
    assert disk_note(releases) is None  # 10 to build: no note


def test_without_uv_the_environments_are_built_with_pip(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "uv", None)  # the import fails
    monkeypatch.setenv("PATH", "")
    assert find_uv() is None


def test_threads_that_make_the_harness_link_at_once_all_get_it(tmp_path: Path) -> None:
    """Releases start at once in threads, each making the same link (a CI run once failed
    with "[Errno 17] File exists" when two made it together)."""
    start = threading.Barrier(8)

    def make() -> Path:
        start.wait()
        return harness_path(tmp_path)

    with ThreadPoolExecutor(max_workers=8) as pool:
        folders = list(pool.map(lambda _: make(), range(8)))
    assert len(set(folders)) == 1
    link = folders[0] / "conformance"
    assert link.resolve() == Path(conformance.__file__).resolve().parent
    assert sorted(p.name for p in folders[0].iterdir()) == ["conformance"]
