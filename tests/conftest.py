"""Shared fixtures: the two implementations under test, and a small scene builder."""

from __future__ import annotations

import builtins
import os
import shutil
import tempfile
from collections.abc import Iterable
from importlib.metadata import version
from pathlib import Path
from typing import Any

# reimpl follows the installed pydrake's release in the tests (unless the variable says
# otherwise), so each test compares the two at one release: 1.51.1 under Python 3.11,
# the newest Drake in CI's Python 3.12 step. It is read when reimpl is first imported.
os.environ.setdefault("REIMPL_DRAKE_RELEASE", version("drake"))

import pytest
from hypothesis import settings
from hypothesis.configuration import set_hypothesis_home_dir

from conformance._backends.environments import CACHE_VARIABLE, ENV_PATH_VARIABLE, cache_dir
from conformance._backends.pydrake_api import pydrake_api
from conformance._backends.reimpl_api import reimpl_api
from conformance._backends.scene_graph import Api
from tests import opt_in

IMPLEMENTATIONS = ("reimpl", "pydrake")

#: Names the developer's own cache while the tests point the cache at a temporary folder.
REAL_CACHE_VARIABLE = "DRAKE_FILTER_CONFORMANCE_TESTS_REAL_CACHE"


def _temporary_cache() -> Path | None:
    """Tests write caches only under a temporary folder: the cache (environments built,
    harness links, the release index) is a fresh folder for the whole run, shared by the
    xdist workers (they inherit this process's environment, so it is made once). The
    developer's environments are still used, read-only (``ENV_PATH_VARIABLE``: never
    stamped or built into), and its release index is copied. Returns the folder made here."""
    if REAL_CACHE_VARIABLE in os.environ:  # an xdist worker, or a run inside a test
        return None
    real = cache_dir()
    folder = Path(tempfile.mkdtemp(prefix="drake-filter-conformance-tests-"))
    if (real / "drake-releases.json").is_file():
        shutil.copy2(real / "drake-releases.json", folder / "drake-releases.json")
    shared = [str(real), *filter(None, os.environ.get(ENV_PATH_VARIABLE, "").split(os.pathsep))]
    os.environ[REAL_CACHE_VARIABLE] = str(real)
    os.environ[CACHE_VARIABLE] = str(folder)
    os.environ[ENV_PATH_VARIABLE] = os.pathsep.join(shared)
    return folder


_CACHE_MADE_HERE = _temporary_cache()


def pytest_unconfigure(config: pytest.Config) -> None:
    """Removes the temporary cache when the run that made it ends."""
    if _CACHE_MADE_HERE is not None:
        shutil.rmtree(_CACHE_MADE_HERE, ignore_errors=True)


# The test suite searches deterministically, so a fresh clone's CI sees the examples
# the developer saw (a random search once failed CI on a strategy bug no local run
# drew). Exploration is the fuzz campaigns' job: `python -m conformance fuzz --seed N`,
# or HYPOTHESIS_PROFILE=explore for the tests.
# Hypothesis' own folder (its constants cache; example databases are the campaigns' own,
# under tmp_path) lives under the temporary directory, not in the working tree.
set_hypothesis_home_dir(str(Path(tempfile.gettempdir()) / "drake-filter-conformance-tests"))
settings.register_profile("deterministic", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "deterministic"))


@pytest.fixture(params=IMPLEMENTATIONS)
def api(request: pytest.FixtureRequest) -> Api:
    """Each test using ``api`` runs once on reimpl and once on real pydrake."""
    return reimpl_api() if request.param == "reimpl" else pydrake_api()


class Scene:
    """A SceneGraph built through the public API, with names for everything.

    It calls the API exactly as a pydrake script would (keyword arguments), so
    the same test body runs unchanged on either implementation.
    """

    def __init__(self, api: Api) -> None:
        self.api = api
        self.g = api.geometry
        self.sg = self.g.SceneGraph()
        self.source = self.sg.RegisterSource(name="source")
        self.frames: dict[str, Any] = {"world": self.sg.world_frame_id()}
        self.ids: dict[str, Any] = {}
        self.names: dict[int, str] = {}

    # registration
    def frame(self, name: str, parent: str | None = None) -> Any:
        frame = self.g.GeometryFrame(frame_name=name)
        if parent is None:
            fid = self.sg.RegisterFrame(source_id=self.source, frame=frame)
        else:
            fid = self.sg.RegisterFrame(
                source_id=self.source, parent_id=self.frames[parent], frame=frame
            )
        self.frames[name] = fid
        return fid

    def geometry(
        self, name: str, frame: str, *, proximity: bool = True, context: Any = None
    ) -> Any:
        instance = self.g.GeometryInstance(
            X_PG=self.api.math.RigidTransform(), shape=self.g.Sphere(radius=0.1), name=name
        )
        if context is not None:
            gid = self.sg.RegisterGeometry(
                context=context,
                source_id=self.source,
                frame_id=self.frames[frame],
                geometry=instance,
            )
        elif frame == "world":
            gid = self.sg.RegisterAnchoredGeometry(source_id=self.source, geometry=instance)
        else:
            gid = self.sg.RegisterGeometry(
                source_id=self.source, frame_id=self.frames[frame], geometry=instance
            )
        self.ids[name] = gid
        self.names[gid.get_value()] = name
        if proximity:
            self.assign_proximity(name, context=context)
        return gid

    def geometries(self, *names: str) -> None:
        """One frame per geometry: ``g0`` on ``f_g0``, and so on."""
        for name in names:
            self.frame(f"f_{name}")
            self.geometry(name, f"f_{name}")

    def assign_proximity(self, name: str, *, replace: bool = False, context: Any = None) -> None:
        kwargs: dict[str, Any] = {
            "source_id": self.source,
            "geometry_id": self.ids[name],
            "properties": self.g.ProximityProperties(),
            "assign": self.g.RoleAssign.kReplace if replace else self.g.RoleAssign.kNew,
        }
        if context is not None:
            kwargs["context"] = context
        self.sg.AssignRole(**kwargs)

    def remove_proximity(self, name: str) -> int:
        return int(
            self.sg.RemoveRole(
                source_id=self.source, geometry_id=self.ids[name], role=self.g.Role.kProximity
            )
        )

    # declarations
    def set(self, *names: str, frames: Iterable[str] = ()) -> Any:
        return self.g.GeometrySet(
            geometry_ids=[self.ids[n] for n in names], frame_ids=[self.frames[f] for f in frames]
        )

    def decl(self) -> Any:
        return self.g.CollisionFilterDeclaration()

    def manager(self, context: Any = None) -> Any:
        if context is None:
            return self.sg.collision_filter_manager()
        return self.sg.collision_filter_manager(context=context)

    def apply(self, declaration: Any, context: Any = None) -> None:
        self.manager(context).Apply(declaration=declaration)

    def apply_transient(self, declaration: Any, context: Any = None) -> Any:
        return self.manager(context).ApplyTransient(declaration=declaration)

    def remove(self, filter_id: Any, context: Any = None) -> bool:
        return bool(self.manager(context).RemoveDeclaration(filter_id=filter_id))

    # observation
    def inspector(self, context: Any = None) -> Any:
        if context is None:
            return self.sg.model_inspector()
        return self.sg.get_query_output_port().Eval(context).inspector()

    def C(self, context: Any = None) -> builtins.set[str]:
        """Candidate pairs as 'a-b' strings, names sorted within each pair."""
        pairs = set()
        for a, b in self.inspector(context).GetCollisionCandidates():
            pairs.add("-".join(sorted((self.names[a.get_value()], self.names[b.get_value()]))))
        return pairs

    def filtered(self, a: str, b: str, context: Any = None) -> bool:
        inspector = self.inspector(context)
        forward = inspector.CollisionFiltered(geometry_id1=self.ids[a], geometry_id2=self.ids[b])
        backward = inspector.CollisionFiltered(geometry_id1=self.ids[b], geometry_id2=self.ids[a])
        assert forward == backward, f"CollisionFiltered({a}, {b}) is not symmetric"
        return bool(forward)


@pytest.fixture
def scene(api: Api) -> Scene:
    return Scene(api)


def all_pairs(*names: str) -> set[str]:
    return {f"{a}-{b}" for i, a in enumerate(sorted(names)) for b in sorted(names)[i + 1 :]}


def _runs_on_pydrake(item: pytest.Item) -> bool:
    """False only for an item parametrized onto reimpl (its ``api`` or ``implementation``)."""
    params = getattr(getattr(item, "callspec", None), "params", {})
    return "reimpl" not in (params.get("api"), params.get("implementation"))


def pytest_addoption(parser: pytest.Parser) -> None:
    opt_in.add_options(parser)


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """``--slice N`` keeps N items of each opt-in test function (``tests/opt_in.py``).

    ``@pytest.mark.release_fact(id)``: the test asserts what a release fact records.

    The fact is a row of the release table (``conformance/_policy/release_facts.json``),
    which holds for a range of Drake releases. Run on an implementation whose release is
    outside it (the installed pydrake's; for reimpl, the release it follows:
    ``REIMPL_DRAKE_RELEASE``, default 1.51.1), the test is an expected failure naming the
    row (strict: if it passes, the table is wrong).
    """
    from importlib.metadata import version  # noqa: PLC0415

    from conformance._policy.release_facts import release_fact  # noqa: PLC0415
    from reimpl._release import release  # noqa: PLC0415

    opt_in.keep_slice(config, items)
    releases = {True: version("drake"), False: release.version}
    for item in items:
        for marker in item.iter_markers("release_fact"):
            fact = release_fact(marker.args[0])
            tested = releases[_runs_on_pydrake(item)]
            if tested not in fact.releases:
                item.add_marker(
                    pytest.mark.xfail(
                        reason=f"release fact {fact.id}: holds for Drake {fact.releases}, "
                        f"not {tested}",
                        strict=True,
                    )
                )
