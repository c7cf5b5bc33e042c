"""Where the embedded default corpus is, in a clone and in an installed wheel.

The repository keeps the corpus at its top, ``scenarios/``. The wheel ships it
inside the package namespace, as ``conformance/_scenarios`` (pyproject.toml's
``package-dir`` maps ``conformance._scenarios`` to ``scenarios``), so an
install adds no top-level ``scenarios`` package. The examples (the backend
skeleton ``new-backend`` writes) ship the same way, ``conformance/_examples``
from ``examples/`` (``examples_root``). ``corpus_root`` looks for the
installed folder first, then for the clone's, each beside the real (resolved)
``conformance`` package, so a worker that reaches the package through a
symbolic link (``environments.harness_path``) finds the same corpus.

Only ``pathlib`` is imported here: workers, which import no third-party
package of the harness, ask it where a mesh file is.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["INSTALLED_NAME", "corpus_root", "examples_root", "is_installed", "package_folder"]

#: The corpus's folder inside an installed ``conformance`` package.
INSTALLED_NAME = "_scenarios"

#: A file every corpus root holds (the published schema).
_MARKER = "scenario.schema.json"


def _package() -> Path:
    return Path(__file__).resolve().parent


def corpus_root() -> Path:
    """``conformance/_scenarios`` when installed from a wheel, else the clone's ``scenarios/``."""
    package = _package()
    for candidate in (package / INSTALLED_NAME, package.parent / "scenarios"):
        if (candidate / _MARKER).is_file():
            return candidate
    raise FileNotFoundError(
        f"the scenario corpus is neither in {package / INSTALLED_NAME} (an installed wheel) "
        f"nor in {package.parent / 'scenarios'} (a clone)"
    )


def examples_root() -> Path:
    """``conformance/_examples`` when installed from a wheel, else the clone's ``examples/``."""
    package = _package()
    for candidate in (package / "_examples", package.parent / "examples"):
        if (candidate / "my_backend.py").is_file():
            return candidate
    raise FileNotFoundError(
        f"the examples are neither in {package / '_examples'} nor in {package.parent / 'examples'}"
    )


def is_installed() -> bool:
    """Whether this ``conformance`` is an installed wheel's (its corpus inside it), not a
    clone's: files of an installed package are not the user's to write."""
    return (_package() / INSTALLED_NAME / _MARKER).is_file()


def package_folder() -> Path:
    """The ``conformance`` package's folder (resolved)."""
    return _package()
