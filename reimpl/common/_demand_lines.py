"""Where each Drake release reports the DRAKE_DEMANDs reimpl reproduces: file and line.

A failed DRAKE_DEMAND names the file and line of the release's own sources
(see _drake_demand), and those move from release to release. The table
``demand_lines.json`` (package data next to this module) holds, for each
measured release, each demand's ``[file, line, function, condition]`` by id
(``SetPositions.q.size``: the method, then what it demands), as pydrake
reported it; tools/measure_demand_lines.py measures a release by failing each
demand of tools/demand_triggers.py, and merges releases into the table. The
function and condition are measured too, as the call that fails a demand can
fail an earlier one in an older release (up to 1.30 a URDF parse into a
finalized SceneGraph source fails the URDF reader's own check first); the
table then records what that call reports.

Measured releases: 1.12.0, 1.13.0, 1.14.0, 1.15.0, 1.16.0, 1.17.0, 1.18.0,
1.19.0, 1.20.0, 1.21.0, 1.22.0, 1.23.0, 1.24.0, 1.25.0, 1.26.0, 1.27.0, 1.28.0,
1.29.0, 1.30.0, 1.31.0, 1.32.0, 1.33.0, 1.34.0, 1.35.0, 1.36.0, 1.37.0, 1.38.0,
1.39.0, 1.40.0, 1.41.0, 1.42.0, 1.43.0, 1.44.0, 1.45.0, 1.46.0, 1.47.0, 1.48.0,
1.49.0, 1.50.0, 1.51.0, 1.51.1, 1.52.0, 1.52.1, 1.53.0, 1.54.0, 1.55.0, 1.56.0,
1.57.0, 1.58.0 (every release pip serves from 1.12.0 to 1.58.0).

``demand_site(id)`` is the site for the release reimpl follows: the measured
one if that release was measured and reaches the demand; otherwise that of the
nearest measured release below it that reaches the demand (an unmeasured
release, such as a later patch release, is assumed to report as the measured
one before it); and for a release older than every measured release that
reaches the demand, the oldest such one. A demand a release does not reach
(its binding is absent, the release raises something else there, or the call
succeeds) has no site in that release's row; the table lists what happened
instead under ``not_demands``.
"""

from __future__ import annotations

import json
from functools import cache
from importlib import resources

from reimpl._release import release

__all__ = ["demand_site", "measured_releases", "site_in"]

Version = tuple[int, ...]
#: file, line, function, condition
Site = tuple[str, int, str, str]


def _version(text: str) -> Version:
    return tuple(int(part) for part in text.split("."))


@cache
def _table() -> dict[Version, dict[str, Site]]:
    path = resources.files("reimpl.common").joinpath("demand_lines.json")
    releases = json.loads(path.read_text("utf-8"))["releases"]
    return {
        _version(name): {
            demand: (site[0], site[1], site[2], site[3]) for demand, site in row["demands"].items()
        }
        for name, row in releases.items()
    }


def measured_releases() -> list[str]:
    """The releases the table measured, oldest first."""
    return [".".join(map(str, version)) for version in sorted(_table())]


def site_in(demand: str, version: str) -> Site:
    """Where Drake ``version`` reports ``demand``, by the rule above (KeyError if the
    table has no such demand)."""
    reached = [(v, row[demand]) for v, row in sorted(_table().items()) if demand in row]
    if not reached:
        raise KeyError(f"no demand {demand!r} in demand_lines.json")
    at_or_below = [site for measured, site in reached if measured <= _version(version)]
    return at_or_below[-1] if at_or_below else reached[0][1]


@cache
def demand_site(demand: str) -> Site:
    """Where reimpl's release reports ``demand``: file, line, function, condition."""
    return site_in(demand, release.version)
