"""``python -m conformance``; see conformance/cli.py.

Before anything imports reimpl, the in-process reimpl is set to follow the installed
pydrake's release (``REIMPL_DRAKE_RELEASE``, when unset and the release table covers it),
so that the default pair, reimpl and pydrake, compares one release with itself: 1.51.1
under Python 3.11, 1.58.0 under 3.12 (``constraints.txt``). tests/conftest.py does the same.
"""

import json
import os
import re
import sys
from importlib import resources
from importlib.metadata import PackageNotFoundError, version


def _follow_installed_drake() -> None:
    if "REIMPL_DRAKE_RELEASE" in os.environ:
        return
    try:
        installed = version("drake")
    except PackageNotFoundError:
        return
    table = json.loads(
        resources.files("conformance._policy").joinpath("release_facts.json").read_text("utf-8")
    )

    def key(text: str) -> tuple[int, ...]:
        return tuple(int(part) for part in text.split("."))

    if re.fullmatch(r"\d+\.\d+\.\d+", installed) and (
        key(table["first_release"]) <= key(installed) <= key(table["last_release"])
    ):
        os.environ["REIMPL_DRAKE_RELEASE"] = installed


_follow_installed_drake()

from conformance.cli.main import main  # noqa: E402 (after the release is chosen)

sys.exit(main())
