"""A failed DRAKE_DEMAND reads the same on reimpl as on the installed pydrake.

Not a port. Each demand of reimpl's table (reimpl/common/demand_lines.json) is
failed through the same call (tools/demand_triggers.py) on pydrake and on
reimpl, which follows the installed release (tests/conftest.py sets
REIMPL_DRAKE_RELEASE): both end the same way, a SystemExit with the same file,
line, function and condition, or, where the release reaches no demand, the same
builtin exception and message. The table's row for the installed release is
what pydrake reports.
"""

from __future__ import annotations

import builtins
import importlib
import json
import re
from importlib import resources
from importlib.metadata import version
from types import ModuleType

import pytest

from reimpl._release import release
from reimpl.common import _demand_lines
from reimpl.common._demand_lines import measured_releases, site_in
from tools.demand_triggers import TRIGGERS

_MODULES = ("geometry", "math", "common.schema", "multibody.plant", "multibody.parsing")


def _root(name: str) -> ModuleType:
    for module in _MODULES:
        importlib.import_module(f"{name}.{module}")
    return importlib.import_module(name)


def _outcome(demand: str, root: ModuleType) -> tuple[str, str]:
    """How the call ends: the builtin exception class (for a subclass, its builtin base)
    and the message; or ``returned``."""
    try:
        TRIGGERS[demand](root)
    except (SystemExit, Exception) as error:  # N.B. The ending is the measurement.
        builtin = next(c for c in type(error).__mro__ if getattr(builtins, c.__name__, 0) is c)
        message = str(error).split("\n", 1)[0]
        if isinstance(error, AttributeError):
            # N.B. An absent binding: pybind names its class by module (pydrake.x.C), Python
            # by name ('C'); the missing attribute is what both say alike.
            message = message[message.find("has no attribute") :]
        return builtin.__name__, message
    return "returned", ""


def _row(release_name: str) -> dict[str, list[object]]:
    table = resources.files("reimpl.common").joinpath("demand_lines.json")
    rows: dict[str, dict[str, dict[str, list[object]]]] = json.loads(table.read_text("utf-8"))[
        "releases"
    ]
    return rows[release_name]["demands"]


def test_reimpl_follows_the_installed_release() -> None:
    assert release.version == version("drake")


@pytest.mark.parametrize("demand", sorted(TRIGGERS))
def test_a_failed_demand_ends_reimpl_as_it_ends_pydrake(demand: str) -> None:
    expected = _outcome(demand, _root("pydrake"))
    assert _outcome(demand, _root("reimpl")) == expected
    row = _row(version("drake"))
    if demand in row:
        path, line, function, condition = row[demand]
        failure = f"Failure at {path}:{line} in {function}(): condition '{condition}' failed."
        # N.B. A shape's check adds the value: "... failed. radius = -1.0."
        assert expected[0] == "SystemExit"
        assert expected[1] == failure or expected[1].startswith(failure + " ")
    else:
        assert not expected[1].startswith("Failure at ")


def test_the_table_holds_a_site_for_every_trigger_and_lists_its_releases() -> None:
    releases = measured_releases()
    assert version("drake") in releases
    assert set(_row(releases[-1])) <= set(TRIGGERS)
    assert {d for r in releases for d in _row(r)} == set(TRIGGERS)
    # The module's docstring lists the measured releases.
    doc = _demand_lines.__doc__ or ""
    listed = doc[doc.index("Measured releases:") : doc.index(" (every release")]
    assert re.findall(r"\d+\.\d+\.\d+", listed) == releases


def test_an_unmeasured_release_reports_as_the_nearest_measured_one_below_it() -> None:
    releases = measured_releases()
    major, minor, patch = releases[-1].split(".")
    later = f"{major}.{minor}.{int(patch) + 1}"
    # A later patch release of the newest measured release: that release's site.
    assert site_in("Parser.plant", later) == site_in("Parser.plant", releases[-1])
    # Older than every release that reaches a demand: the oldest that does.
    first = next(r for r in releases if "RenameModelInstance.finalized" in _row(r))
    assert first != releases[0]
    assert site_in("RenameModelInstance.finalized", releases[0]) == tuple(
        _row(first)["RenameModelInstance.finalized"]
    )
