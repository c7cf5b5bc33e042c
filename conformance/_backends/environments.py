"""Isolated, cached environments that each hold one Drake release, for worker backends.

A release needs a Python that its wheels support (``PYTHONS_FOR``, as pip
serves them):

==============  =====================
Drake           Python
==============  =====================
1.12 - 1.21     3.11
1.22 - 1.51     3.11, 3.12
1.52 - 1.58     3.12, 3.13
==============  =====================

Releases up to 1.30 also need ``numpy<2`` (``EXTRA_REQUIREMENTS``): their
wheels ask for any numpy, were built against numpy 1, and under numpy 2
``pydrake.multibody`` fails to import up to 1.23 ("initialization failed":
``ndarray.itemset`` is gone) and 1.24-1.30 crash (SIGSEGV) on the first
Eigen vector argument, e.g. ``RevoluteJoint(axis=...)``; ``pydrake.geometry``
works either way. 1.31 and later run under numpy 2 (all measured).

``find_python`` looks for such an interpreter on PATH (``python3.11`` ...)
and in pyenv's versions, and checks each candidate by running it; a given
``python`` overrides the search. ``ensure_environment`` builds
``<cache>/drake-<version>-py<X.Y>`` once and marks it complete; later runs
reuse it, and each use touches its ``.last-used`` stamp (``cache list`` and
``cache prune`` read it: ``env_cache``). It builds with ``uv`` (a declared
dependency: ``uv venv``, ``uv pip install``; uv's cache hard-links the files
environments share, so a second release costs the disk of what differs), and
with ``venv`` and ``pip`` if uv is missing, saying so. Measured on Python 3.11,
cold caches, two releases each: by hand, Drake 1.48.0 and 1.49.0: pip 47 s and
29 s, 416 + 420 MB; uv 4.2 s and 3.3 s, 568 MB for both with uv's cache.
Through ``ensure_environment`` (a busier machine), 1.46.0 and 1.47.0: pip 66 s
and 85 s, 829 MB; uv 16 s and 11 s, 518 MB for both with uv's cache. It holds a
lock file (``<env>.lock``, ``fcntl.flock``) while it checks and builds, so
processes that want the same environment at once (pytest-xdist workers, a
matrix's jobs) wait for one build instead of removing it under each other.
The cache is ``$DRAKE_FILTER_CONFORMANCE_CACHE``, else
``~/.cache/drake-filter-conformance``. ``$DRAKE_FILTER_CONFORMANCE_ENV_PATH``
(folders joined with ``os.pathsep``) names more caches whose complete
environments are used as they are and never written to (no stamp, no
build): the test suite points the cache at a temporary folder and reads the
developer's environments this way.

The worker imports only this harness's pure-Python modules plus the
release's pydrake: the harness reaches it through a folder that links to the
``conformance`` package alone (``harness_path``), so nothing
else of this environment (its own pydrake included) can leak in.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import subprocess
import threading
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

import conformance
from conformance._policy.versions import version_in_range

__all__ = [
    "CACHE_VARIABLE",
    "ENV_PATH_VARIABLE",
    "EXTRA_REQUIREMENTS",
    "PYTHONS_FOR",
    "DrakeEnvironment",
    "DrakeEnvironmentError",
    "cache_dir",
    "ensure_environment",
    "find_python",
    "find_uv",
    "harness_path",
    "read_only_caches",
    "requirements_for",
]

CACHE_VARIABLE = "DRAKE_FILTER_CONFORMANCE_CACHE"
ENV_PATH_VARIABLE = "DRAKE_FILTER_CONFORMANCE_ENV_PATH"

#: (since, until) Drake release → the Python versions its wheels support, preferred first.
PYTHONS_FOR: tuple[tuple[str, str, tuple[str, ...]], ...] = (
    ("1.12", "1.21", ("3.11",)),
    ("1.22", "1.51", ("3.11", "3.12")),
    ("1.52", "1.58", ("3.12", "3.13")),
)

#: (since, until) Drake release → what pip must install besides ``drake==X`` (see the module doc).
EXTRA_REQUIREMENTS: tuple[tuple[str, str, tuple[str, ...]], ...] = (("1.12", "1.30", ("numpy<2",)),)

#: Marks an environment whose install finished; it holds the requirements installed.
COMPLETE = ".complete"
#: Touched each time an environment of the cache is used.
LAST_USED = ".last-used"


class DrakeEnvironmentError(RuntimeError):
    """No usable interpreter, or the environment could not be built."""


@dataclass(frozen=True)
class DrakeEnvironment:
    version: str
    python: str  # "3.11"
    path: Path

    @property
    def interpreter(self) -> Path:
        return self.path / "bin" / "python"


def cache_dir() -> Path:
    """``$DRAKE_FILTER_CONFORMANCE_CACHE``, else ``~/.cache/drake-filter-conformance``."""
    configured = os.environ.get(CACHE_VARIABLE)
    if configured:
        return Path(configured).expanduser()
    return Path.home() / ".cache" / "drake-filter-conformance"


def read_only_caches() -> list[Path]:
    """The folders ``$DRAKE_FILTER_CONFORMANCE_ENV_PATH`` names (used, never written)."""
    configured = os.environ.get(ENV_PATH_VARIABLE, "")
    return [Path(p).expanduser() for p in configured.split(os.pathsep) if p]


def pythons_for(version: str) -> tuple[str, ...]:
    """The Python versions Drake ``version``'s wheels support (empty if unknown)."""
    for since, until, pythons in PYTHONS_FOR:
        if version_in_range(version, since, until):
            return pythons
    return ()


def requirements_for(version: str) -> tuple[str, ...]:
    """What an environment for Drake ``version`` installs: ``drake==X`` and its extras."""
    extras = (
        r
        for since, until, rs in EXTRA_REQUIREMENTS
        if version_in_range(version, since, until)
        for r in rs
    )
    return (f"drake=={version}", *extras)


def _candidates(python: str) -> Iterator[str]:
    """Interpreters that may be Python ``python``: on PATH, then pyenv's."""
    found = shutil.which(f"python{python}")
    if found:
        yield found
    roots = [os.environ.get("PYENV_ROOT"), str(Path.home() / ".pyenv")]
    for root in filter(None, roots):
        for version_dir in sorted(Path(root, "versions").glob(f"{python}.*"), reverse=True):
            yield str(version_dir / "bin" / f"python{python}")


def _is_python(executable: str, python: str) -> bool:
    try:
        done = subprocess.run(
            [executable, "-c", "import sys; print('%d.%d' % sys.version_info[:2])"],
            capture_output=True,
            text=True,
            timeout=30,
            check=False,
        )
    except OSError:
        return False
    return done.returncode == 0 and done.stdout.strip() == python


def find_python(version: str, *, override: str | Sequence[str] | None = None) -> tuple[str, str]:
    """(Python version, interpreter) for Drake ``version``; see the module doc.

    ``override``: the interpreter(s) given with ``--python``; the first that the
    release supports is chosen, and if none is, that is an error (no search).
    """
    pythons = pythons_for(version)
    if not pythons:
        raise DrakeEnvironmentError(f"drake=={version}: no known Python for this release")
    if override:
        given = [override] if isinstance(override, str) else list(override)
        for executable in given:
            for python in pythons:
                if _is_python(executable, python):
                    return python, executable
        raise DrakeEnvironmentError(
            f"drake=={version} needs Python {' or '.join(pythons)}; "
            f"--python {' '.join(given)} {'is' if len(given) == 1 else 'are'} not"
        )
    for python in pythons:
        for candidate in _candidates(python):
            if _is_python(candidate, python):
                return python, candidate
    raise DrakeEnvironmentError(
        f"drake=={version} needs Python {' or '.join(pythons)}; none found on PATH or in pyenv "
        "(install one, or name it with --python)"
    )


def _run(argv: list[str], log: Callable[[str], None]) -> None:
    log("  $ " + " ".join(argv))
    done = subprocess.run(argv, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        tail = "\n".join((done.stderr or done.stdout).strip().splitlines()[-5:])
        raise DrakeEnvironmentError(f"{argv[0]} failed ({done.returncode}):\n{tail}")


def ensure_environment(
    version: str,
    *,
    python: str | Sequence[str] | None = None,
    cache: Path | None = None,
    log: Callable[[str], None] = lambda line: None,
) -> DrakeEnvironment:
    """The cached environment for Drake ``version``, built first if needed."""
    python_version, interpreter = find_python(version, override=python)
    name = f"drake-{version}-py{python_version}"
    path = (cache or cache_dir()) / name
    if not (path / COMPLETE).exists():
        for shared in read_only_caches():
            if _holds(shared / name, requirements_for(version)):
                return DrakeEnvironment(version, python_version, shared / name)
    environment = DrakeEnvironment(version, python_version, path)
    with _locked(path):
        _build(environment, interpreter, log)
    (path / LAST_USED).touch()
    return environment


def _holds(path: Path, requirements: Sequence[str]) -> bool:
    """Whether ``path`` is a complete environment with all of ``requirements``."""
    marker = path / COMPLETE
    return marker.is_file() and set(requirements) <= set(marker.read_text().split())


@contextlib.contextmanager
def _locked(path: Path) -> Iterator[None]:
    """Holds an exclusive lock on ``<path>.lock`` (one builder of ``path`` at a time)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.with_name(path.name + ".lock").open("w") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def _build(environment: DrakeEnvironment, interpreter: str, log: Callable[[str], None]) -> None:
    """Makes ``environment`` complete: builds it, or adds requirements it lacks."""
    version, python_version, path = environment.version, environment.python, environment.path
    requirements = requirements_for(version)
    marker = path / COMPLETE
    if marker.exists():
        missing = [r for r in requirements if r not in marker.read_text().split()]
        if missing:  # built before its extras were known: add them once
            log(f"adding {' '.join(missing)} to the environment for drake=={version}")
            _install(environment, missing, log)
            marker.write_text("\n".join(requirements) + "\n")
        return
    log(f"building the environment for drake=={version} (Python {python_version}) in {path}")
    shutil.rmtree(path, ignore_errors=True)
    path.parent.mkdir(parents=True, exist_ok=True)
    uv = find_uv()
    if uv:
        _run([uv, "venv", "--quiet", "--python", interpreter, str(path)], log)
    else:
        log(f"  uv not found ({_NO_UV}): building with venv and pip (slower, no shared files)")
        _run([interpreter, "-m", "venv", str(path)], log)
    _install(environment, requirements, log)
    marker.write_text("\n".join(requirements) + "\n")


def _install(
    environment: DrakeEnvironment, requirements: Sequence[str], log: Callable[[str], None]
) -> None:
    """pip-installs ``requirements`` into ``environment`` (with ``uv`` if there is one)."""
    uv = find_uv()
    if uv:
        _run([uv, "pip", "install", "--python", str(environment.interpreter), *requirements], log)
    else:
        _run([str(environment.interpreter), "-m", "pip", "install", "--quiet",
              "--disable-pip-version-check", *requirements], log)  # fmt: skip


#: How to get uv when it is missing (it is a dependency of this package).
_NO_UV = "pip install uv"


def find_uv() -> str | None:
    """The ``uv`` executable: the ``uv`` package's (a dependency), else one on PATH, else None."""
    try:
        from uv import find_uv_bin  # noqa: PLC0415 (optional at run time: pip is the fallback)

        return str(find_uv_bin())
    except (ImportError, FileNotFoundError):
        return shutil.which("uv")


def harness_path(cache: Path | None = None) -> Path:
    """A folder holding only a link to this harness's ``conformance`` package, for PYTHONPATH
    (the worker finds the corpus beside the package the link resolves to, as
    ``conformance._corpus_root`` says: a mesh command names a file below it)."""
    package = Path(conformance.__file__).resolve().parent
    folder = (cache or cache_dir()) / "harness" / _slug(str(package))
    link = folder / "conformance"
    if not link.is_symlink() or link.resolve() != package:
        # Made under a name of this thread's, then renamed over ``link`` (atomic): releases
        # that start at once (matrix and models columns, in threads) each make it, and an
        # unlink-then-symlink raced (measured: "[Errno 17] File exists" in a CI run).
        folder.mkdir(parents=True, exist_ok=True)
        mine = folder / f".conformance-{os.getpid()}-{threading.get_ident()}"
        mine.unlink(missing_ok=True)
        mine.symlink_to(package, target_is_directory=True)
        mine.replace(link)
    return folder


def _slug(text: str) -> str:
    return "".join(c if c.isalnum() else "-" for c in text).strip("-")[-80:]
