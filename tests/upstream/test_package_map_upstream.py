# Ported from Drake: multibody/parsing/test/package_map_test.cc and
# multibody/parsing/test/package_map_remote_test.cc (https://github.com/RobotLocomotion/drake),
# the parts the public Python API reaches, re-expressed as pytest functions that run unchanged
# on pydrake and on reimpl.
#
# Drake's license (BSD 3-Clause), which covers the upstream test this file is ported from:
#
#   Copyright 2012-2022, Robot Locomotion Group @ CSAIL, Massachusetts Institute of Technology
#   All rights reserved.
#
#   Redistribution and use in source and binary forms, with or without modification, are
#   permitted provided that the following conditions are met:
#
#   1. Redistributions of source code must retain the above copyright notice, this list of
#      conditions and the following disclaimer.
#   2. Redistributions in binary form must reproduce the above copyright notice, this list of
#      conditions and the following disclaimer in the documentation and/or other materials
#      provided with the distribution.
#   3. Neither the name of the copyright holder nor the names of its contributors may be used
#      to endorse or promote products derived from this software without specific prior
#      written permission.
#
#   THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS" AND ANY
#   EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE IMPLIED WARRANTIES OF
#   MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE DISCLAIMED. IN NO EVENT SHALL THE
#   COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE FOR ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL,
#   EXEMPLARY, OR CONSEQUENTIAL DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF
#   SUBSTITUTE GOODS OR SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION)
#   HOWEVER CAUSED AND ON ANY THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY, OR
#   TORT (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE OF THIS
#   SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
"""Upstream PackageMap tests, on pydrake and on reimpl.

pydrake binds neither ``SetDeprecated``/``GetDeprecated`` nor ``GetPath``'s
deprecation output argument, so a package's deprecation is read where Python
sees it: the warning ``PackageMap: Package '<name>' is deprecated: <message>``
that ``GetPath`` logs on the ``drake`` logger. Deprecations come from
``package.xml`` files (``AddPackageXml`` accepts any file name, and takes its
folder as the package's path). Move semantics and the (deprecated) stream and
fmt printing are not bound; ``str()`` of a map is the object's repr.

Remote packages are fetched from ``file://`` URLs into a cache under
``$TEST_TMPDIR`` (Drake's first cache location), so no test touches the user's
cache or the network. Left out: the unwritable cache (the tests run as root,
which writes anyway) and fetching ``drake_models`` (a download; reimpl does not
download).
"""

from __future__ import annotations

import copy
import hashlib
import logging
import os
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

TEST_PACKAGES = "multibody/parsing/test/package_map_test_packages"
COMPRESSED_SHA256 = "b4bdbad313293ca61fe8f4ed1b5579dadadb3a5c08f0a6d06a8e39e5f97f1bd1"
DEPRECATED_B = (
    "package_map_test_package_b is deprecated, and will be removed on or around "
    "2038-01-19. Please use the 'drake' package instead."
)


def _root(drake_models: Path) -> str:
    """GetTestDataRoot(): the test packages' folder, with a trailing slash."""
    return f"{drake_models / TEST_PACKAGES}/"


def _deprecation(package_map: Any, name: str, caplog: pytest.LogCaptureFixture) -> str | None:
    """The deprecation message GetPath logs for ``name`` (None if it logs none)."""
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="drake"):
        package_map.GetPath(package_name=name)
    prefix = f"PackageMap: Package '{name}' is deprecated: "
    messages = [r.getMessage() for r in caplog.records if r.getMessage().startswith(prefix)]
    return messages[0].removeprefix(prefix) if messages else None


def _verify_match(
    package_map: Any, expected: dict[str, str], caplog: pytest.LogCaptureFixture
) -> None:
    """VerifyMatch: the map holds exactly ``expected``; b and d are deprecated."""
    assert package_map.size() == len(expected)
    assert sorted(package_map.GetPackageNames()) == sorted(expected)
    for name, path in expected.items():
        assert package_map.Contains(package_name=name)
        assert package_map.GetPath(package_name=name) == path
        deprecated = name in ("package_map_test_package_b", "package_map_test_package_d")
        message = _deprecation(package_map, name, caplog)
        assert (message is not None) == deprecated, name
        assert bool(message) == deprecated, name


def _test_data_packages(root: str) -> dict[str, str]:
    return {
        "package_map_test_package_a": root + "package_map_test_package_a/",
        "package_map_test_package_aa": (
            root + "package_map_test_package_a/package_map_test_package_aa/"
        ),
        "package_map_test_package_b": root + "package_map_test_package_b/",
        "package_map_test_package_c": (
            root + "package_map_test_package_set/package_map_test_package_c/"
        ),
        "package_map_test_package_d": (
            root + "package_map_test_package_set/package_map_test_package_d/"
        ),
        "package_map_test_package_e": root + "package_map_test_package_e/",
    }


def _manifest(folder: Path, file_name: str, package: str, deprecated: str | None = None) -> str:
    """Writes a package.xml (by any file name) and returns its path."""
    export = f"<export><deprecated>{deprecated}</deprecated></export>" if deprecated else ""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / file_name
    path.write_text(f"<?xml version='1.0'?>\n<package><name>{package}</name>{export}</package>\n")
    return str(path)


# --------------------------------------------------------------- package_map_test.cc
def test_lifecycle_copies_keep_the_default_packages(drake: ModuleType) -> None:
    PackageMap = drake.multibody.parsing.PackageMap
    original = PackageMap()
    default_size = original.size()
    assert default_size == 2
    assert sorted(original.GetPackageNames()) == ["drake", "drake_models"]
    copied = PackageMap(other=original)
    assert copied.size() == default_size
    assert copy.copy(original).size() == default_size
    assert copy.deepcopy(original).size() == default_size
    empty = PackageMap.MakeEmpty()
    assert empty.size() == 0
    copied.Remove(package_name="drake")
    assert original.size() == default_size


def test_a_map_is_populated_and_unpopulated_by_hand(
    drake: ModuleType,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
) -> None:
    """TestManualPopulation, with folders relative to the working folder."""
    monkeypatch.chdir(tmp_path)
    for folder in ("package_foo", "package_bar", "package_baz"):
        os.mkdir(folder)
    expected = {"package_foo": "package_foo", "my_package": "package_bar", "third": "package_baz"}
    package_map = drake.multibody.parsing.PackageMap.MakeEmpty()
    for i, (name, path) in enumerate(expected.items()):
        package_map.Add(package_name=name, package_path=Path(path) if i % 2 else path)
    _verify_match(package_map, expected, caplog)

    # Adding a duplicate package with the same path is OK.
    package_map.Add(package_name="package_foo", package_path="package_foo")
    with pytest.raises(RuntimeError) as info:
        package_map.Add(package_name="package_foo", package_path="package_baz")
    assert str(info.value) == (
        "PackageMap::Add() cannot add 'package_foo' because the local paths are not "
        "equivalent ('package_foo' vs 'package_baz')"
    )
    with pytest.raises(RuntimeError) as info:
        package_map.Add(package_name="garbage", package_path="garbage")
    assert str(info.value) == (
        "PackageMap::Add cannot add 'garbage' because directory 'garbage' does not exist"
    )
    _verify_match(package_map, expected, caplog)

    remaining = dict(expected)
    for name in expected:
        package_map.Remove(package_name=name)
        del remaining[name]
        _verify_match(package_map, remaining, caplog)
    with pytest.raises(RuntimeError) as info:
        package_map.Remove(package_name="never_existed")
    assert str(info.value) == (
        "Could not find and remove package://never_existed from the search path."
    )


def test_default_maps_always_merge(drake: ModuleType) -> None:
    """AddDefaultConstructedMaps."""
    PackageMap = drake.multibody.parsing.PackageMap
    foo, bar, dut = PackageMap(), PackageMap(), PackageMap()
    dut.AddMap(other_map=foo)
    dut.AddMap(other_map=bar)
    assert dut.size() == foo.size()


def test_maps_combine_and_a_conflict_is_refused(
    drake: ModuleType,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
) -> None:
    """TestAddMap."""
    monkeypatch.chdir(tmp_path)
    for folder in ("package_foo", "package_bar", "package_baz"):
        os.mkdir(folder)
    PackageMap = drake.multibody.parsing.PackageMap

    def make(packages: dict[str, str]) -> Any:
        package_map = PackageMap.MakeEmpty()
        for name, path in packages.items():
            package_map.Add(package_name=name, package_path=path)
        _verify_match(package_map, packages, caplog)
        return package_map

    map_1 = make({"package_foo": "package_foo", "package_bar": "package_bar"})
    map_2 = make({"package_foo": "package_foo", "package_baz": "package_baz"})
    conflicting = make({"package_foo": "package_foo", "package_baz": "package_bar"})
    combined = PackageMap(other=map_1)
    combined.AddMap(other_map=map_2)
    _verify_match(
        combined,
        {"package_foo": "package_foo", "package_bar": "package_bar", "package_baz": "package_baz"},
        caplog,
    )
    with pytest.raises(RuntimeError) as info:
        combined.AddMap(other_map=conflicting)
    assert str(info.value) == (
        "PackageMap::AddMap cannot merge the package definition for 'package_baz' because "
        "the local paths are not equivalent ('package_baz' vs 'package_bar')"
    )


def test_merging_maps_keeps_deprecations(
    drake: ModuleType, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """TestAddMapDeprecated, with the deprecations written in package.xml files."""
    PackageMap = drake.multibody.parsing.PackageMap
    default, hats = tmp_path / "default", tmp_path / "hats"
    dut = PackageMap.MakeEmpty()
    dut.Add(package_name="default", package_path=str(default.mkdir() or default))

    # The deprecation comes along while merging.
    hats_map = PackageMap.MakeEmpty()
    hats_map.AddPackageXml(filename=_manifest(hats, "package.xml", "hats", "I like hats."))
    dut.AddMap(other_map=hats_map)
    assert dut.size() == 2
    assert _deprecation(dut, "default", caplog) is None
    assert _deprecation(dut, "hats", caplog) == "I like hats."

    # An existing deprecation stays when the merged map has none ...
    temp = PackageMap.MakeEmpty()
    temp.Add(package_name="hats", package_path=str(hats))
    dut.AddMap(other_map=temp)
    assert _deprecation(dut, "hats", caplog) == "I like hats."

    # ... or another one.
    temp = PackageMap.MakeEmpty()
    temp.AddPackageXml(filename=_manifest(hats, "ignored.xml", "hats", "Ignored!"))
    dut.AddMap(other_map=temp)
    assert _deprecation(dut, "hats", caplog) == "I like hats."

    # Merging a deprecated package onto an undeprecated one inherits the deprecation.
    temp = PackageMap.MakeEmpty()
    temp.AddPackageXml(filename=_manifest(default, "nelly.xml", "default", "Oh nelly!"))
    dut.AddMap(other_map=temp)
    assert _deprecation(dut, "default", caplog) == "Oh nelly!"


def test_a_package_xml_adds_its_folder(
    drake: ModuleType, drake_models: Path, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """TestPopulateFromXml."""
    xml = drake_models / TEST_PACKAGES / "package_map_test_package_a" / "package.xml"
    package_map = drake.multibody.parsing.PackageMap.MakeEmpty()
    package_map.AddPackageXml(filename=xml)
    expected = {"package_map_test_package_a": str(xml.parent)}
    _verify_match(package_map, expected, caplog)

    # The same package.xml again is OK: the same name and path.
    package_map.AddPackageXml(filename=str(xml))
    _verify_match(package_map, expected, caplog)

    conflicting = drake_models / "multibody/parsing/test/package_map_test_package_conflicting"
    with pytest.raises(RuntimeError) as info:
        package_map.AddPackageXml(filename=str(conflicting / "package.xml"))
    assert str(info.value) == (
        "PackageMap::Add() cannot add 'package_map_test_package_a' because the local paths "
        f"are not equivalent ('{xml.parent}' vs '{conflicting}')"
    )

    # The same filesystem-canonical package.xml twice is not an error.
    alternative = tmp_path / "alternative_package_a"
    alternative.mkdir()
    (alternative / "package.xml").symlink_to(xml)
    package_map.Add(package_name="package_map_test_package_a", package_path=str(alternative))


@pytest.mark.parametrize("suffix", ["", "///////"])
def test_a_folder_is_crawled_for_packages(
    drake: ModuleType, drake_models: Path, suffix: str, caplog: pytest.LogCaptureFixture
) -> None:
    """TestPopulateMapFromFolder and ...ExtraTrailingSlashes."""
    root = _root(drake_models)
    package_map = drake.multibody.parsing.PackageMap.MakeEmpty()
    package_map.PopulateFromFolder(path=root + suffix)
    _verify_match(package_map, _test_data_packages(root), caplog)


def test_an_environment_variable_lists_folders_to_crawl(
    drake: ModuleType,
    drake_models: Path,
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
) -> None:
    """TestPopulateFromEnvironment: unset, empty, then a bad, a good and an empty path."""
    package_map = drake.multibody.parsing.PackageMap.MakeEmpty()
    monkeypatch.delenv("FOOBAR", raising=False)
    package_map.PopulateFromEnvironment(environment_variable="FOOBAR")
    assert package_map.size() == 0
    monkeypatch.setenv("FOOBAR", "")
    package_map.PopulateFromEnvironment(environment_variable="FOOBAR")
    assert package_map.size() == 0
    root = _root(drake_models)
    monkeypatch.setenv("FOOBAR", f"/does/not/exist:{root}:")
    with caplog.at_level(logging.WARNING, logger="drake"):
        package_map.PopulateFromEnvironment(environment_variable="FOOBAR")
    assert "Unable to open directory: /does/not/exist" in caplog.messages
    _verify_match(package_map, _test_data_packages(root), caplog)


def test_ros_package_path_stops_at_packages_and_ignore_markers(
    drake: ModuleType,
    drake_models: Path,
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
) -> None:
    """TestPopulateFromRosPackagePath: no package inside a package (aa), nor one marked
    COLCON_IGNORE (e)."""
    package_map = drake.multibody.parsing.PackageMap.MakeEmpty()
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    package_map.PopulateFromRosPackagePath()
    assert package_map.size() == 0
    monkeypatch.setenv("ROS_PACKAGE_PATH", "")
    package_map.PopulateFromRosPackagePath()
    assert package_map.size() == 0
    root = _root(drake_models)
    monkeypatch.setenv("ROS_PACKAGE_PATH", f"/does/not/exist:{root}:")
    package_map.PopulateFromRosPackagePath()
    expected = _test_data_packages(root)
    del expected["package_map_test_package_aa"], expected["package_map_test_package_e"]
    _verify_match(package_map, expected, caplog)
    with pytest.raises(RuntimeError) as info:
        package_map.PopulateFromEnvironment(environment_variable="ROS_PACKAGE_PATH")
    assert str(info.value) == (
        "PackageMap::PopulateFromEnvironment() must not be used to load a "
        '"ROS_PACKAGE_PATH"; use PopulateFromRosPackagePath() instead.'
    )


def test_resolve_url_names_a_file_of_a_package(drake: ModuleType, drake_models: Path) -> None:
    """TestResolveUrl."""
    package_a = drake_models / TEST_PACKAGES / "package_map_test_package_a"
    package_map = drake.multibody.parsing.PackageMap.MakeEmpty()
    package_map.AddPackageXml(filename=str(package_a / "package.xml"))
    assert package_map.ResolveUrl(
        url="package://package_map_test_package_a/sdf/test_model.sdf"
    ) == str(package_a / "sdf" / "test_model.sdf")
    with pytest.raises(RuntimeError) as info:
        package_map.ResolveUrl(url="package://bad_package_name/sdf/test_model.sdf")
    assert str(info.value) == (
        "error: URI 'package://bad_package_name/sdf/test_model.sdf' refers to unknown "
        "package 'bad_package_name'"
    )
    with pytest.raises(RuntimeError) as info:
        package_map.ResolveUrl(url="package://package_map_test_package_a/bad_filename.sdf")
    assert str(info.value) == (
        "error: URI 'package://package_map_test_package_a/bad_filename.sdf' resolved to "
        f"'{package_a}/bad_filename.sdf' which does not exist."
    )


def test_package_xml_deprecations_are_read(
    drake: ModuleType, drake_models: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """TestDeprecation: b's message (line breaks and indentation collapsed), d's empty tag."""
    expected = {
        "package_map_test_package_b": DEPRECATED_B,
        "package_map_test_package_d": "(no explanation given)",
    }
    package_map = drake.multibody.parsing.PackageMap()
    package_map.PopulateFromFolder(path=_root(drake_models))
    names = [n for n in package_map.GetPackageNames() if n.startswith("package_map_test")]
    assert len(names) == 6
    for name in names:
        assert _deprecation(package_map, name, caplog) == expected.get(name)


def test_using_a_deprecated_package_in_a_url_warns(
    drake: ModuleType, drake_models: Path, caplog: pytest.LogCaptureFixture
) -> None:
    package_map = drake.multibody.parsing.PackageMap.MakeEmpty()
    package_map.PopulateFromFolder(path=_root(drake_models))
    url = "package://package_map_test_package_b/package.xml"
    with caplog.at_level(logging.WARNING, logger="drake"):
        package_map.ResolveUrl(url=url)
    assert caplog.messages == [
        f"warning: In URI '{url}': Package 'package_map_test_package_b' is deprecated: "
        f"{DEPRECATED_B}"
    ]


# -------------------------------------------------------- package_map_remote_test.cc
@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Drake's download cache, under $TEST_TMPDIR (the first place Drake looks)."""
    monkeypatch.setenv("TEST_TMPDIR", str(tmp_path))
    return tmp_path / ".cache" / "drake" / "package_map"


def _good_params(drake: ModuleType, drake_models: Path) -> Any:
    """MakeGoodParams(): params that fetch compressed.zip from a file:// URL."""
    return drake.multibody.parsing.PackageMap.RemoteParams(
        urls=[f"file://{drake_models / TEST_PACKAGES / 'compressed.zip'}"],
        sha256=COMPRESSED_SHA256,
        strip_prefix="compressed_prefix",
    )


def test_a_cached_remote_package_is_not_fetched(drake: ModuleType, cache: Path) -> None:
    """GetPathPrepopulated."""
    sha256 = "0" * 64
    package_dir = cache / f"{sha256}-{hashlib.sha256(b'').hexdigest()}"
    package_dir.mkdir(parents=True)
    (package_dir / "package.xml").write_text(
        "<?xml version='1.0'?>\n<package><name>some_remote_name</name></package>\n"
    )
    dut = drake.multibody.parsing.PackageMap.MakeEmpty()
    params = drake.multibody.parsing.PackageMap.RemoteParams(
        urls=["http://127.0.0.1/missing.zip"], sha256=sha256
    )
    dut.AddRemote(package_name="some_remote_name", params=params)
    assert dut.GetPath(package_name="some_remote_name") == str(package_dir)


def test_a_remote_package_is_fetched_and_unpacked(
    drake: ModuleType, drake_models: Path, cache: Path
) -> None:
    """ActuallyFetch."""
    dut = drake.multibody.parsing.PackageMap.MakeEmpty()
    dut.AddRemote(package_name="compressed", params=_good_params(drake, drake_models))
    resolved = Path(dut.GetPath(package_name="compressed"))
    assert resolved.parent == cache
    assert (resolved / "README").read_text() == "This package is empty.\n"


def test_the_same_archive_with_another_strip_prefix_is_another_package(
    drake: ModuleType, drake_models: Path, cache: Path
) -> None:
    """FetchWithDifferentStrip."""
    dut = drake.multibody.parsing.PackageMap.MakeEmpty()
    dut.AddRemote(package_name="foo", params=_good_params(drake, drake_models))
    bar_params = _good_params(drake, drake_models)
    bar_params.strip_prefix = None
    dut.AddRemote(package_name="bar", params=bar_params)
    foo, bar = Path(dut.GetPath("foo")), Path(dut.GetPath("bar"))
    assert (foo / "README").is_file()
    assert (bar / "compressed_prefix" / "README").is_file()


def test_without_network_only_file_urls_are_tried(
    drake: ModuleType, drake_models: Path, cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """GetPathEnvironmentDenied."""
    monkeypatch.setenv("DRAKE_ALLOW_NETWORK", "none")
    params = _good_params(drake, drake_models)
    file_url = params.urls[0]
    params.urls = ["http://127.0.0.1/missing.zip", file_url]
    dut = drake.multibody.parsing.PackageMap.MakeEmpty()
    dut.AddRemote(package_name="ok", params=params)
    dut.GetPath(package_name="ok")

    params.urls = ["http://127.0.0.1/missing.zip"]
    params.sha256 = "f" * 64
    dut = drake.multibody.parsing.PackageMap.MakeEmpty()
    with pytest.raises(RuntimeError) as info:
        dut.AddRemote(package_name="bad", params=params)
    assert str(info.value) == (
        "PackageMap::AddRemote on 'bad' only provides network URLs (i.e., no file:// "
        "fallbacks) but PackageMap networking has been disabled via the DRAKE_ALLOW_NETWORK "
        "environment variable and the download cache does not contain any matching file"
    )


def test_a_remote_package_cannot_replace_a_local_one(
    drake: ModuleType, drake_models: Path, tmp_path: Path
) -> None:
    """RejectDuplicates."""
    dut = drake.multibody.parsing.PackageMap.MakeEmpty()
    dut.Add(package_name="foo", package_path=str(tmp_path))
    with pytest.raises(RuntimeError) as info:
        dut.AddRemote(package_name="foo", params=_good_params(drake, drake_models))
    url = _good_params(drake, drake_models).urls[0]
    assert str(info.value) == (
        f"PackageMap::AddRemote() cannot add 'foo' because the existing path is local "
        f"('{tmp_path}') but the the new path is remote ('{url}')"
    )


@pytest.mark.parametrize(
    ("params", "message"),
    [
        ({}, "PackageMap::AddRemote on 'foo' requires at least one URL"),
        (
            {"urls": ["mailfrom:rico@drake.mit.edu"]},
            "PackageMap::AddRemote on 'foo' has unsupported URL 'mailfrom:rico@drake.mit.edu'",
        ),
        (
            {"urls": ["http://127.0.0.1/missing.zip"], "sha256": "256"},
            "PackageMap::AddRemote on 'foo' has invalid sha256 '256'",
        ),
        (
            {"urls": ["http://127.0.0.1/missing.zip"], "sha256": "X" * 64},
            f"PackageMap::AddRemote on 'foo' has invalid sha256 '{'X' * 64}'",
        ),
        (
            {"urls": ["http://127.0.0.1/missing.zip"], "sha256": "0" * 64, "archive_type": "arj"},
            "PackageMap::AddRemote on 'foo' has unsupported archive type 'arj'",
        ),
    ],
)
def test_remote_params_are_checked_when_added(
    drake: ModuleType, params: dict[str, Any], message: str
) -> None:
    """InputSanitization."""
    PackageMap = drake.multibody.parsing.PackageMap
    with pytest.raises(RuntimeError) as info:
        PackageMap.MakeEmpty().AddRemote(
            package_name="foo", params=PackageMap.RemoteParams(**params)
        )
    assert str(info.value) == message


def test_a_wrong_checksum_fails_every_time(
    drake: ModuleType, drake_models: Path, cache: Path
) -> None:
    """CouldNotFetch: a failed download leaves the cache as it was."""
    params = _good_params(drake, drake_models)
    params.sha256 = "f" + params.sha256[1:]
    dut = drake.multibody.parsing.PackageMap.MakeEmpty()
    dut.AddRemote(package_name="compressed", params=params)
    expected = (
        "PackageMap: when downloading 'compressed', the downloader experienced an error: All "
        f"downloads failed:\n\nCandidate {params.urls[0]} failed:\nChecksum mismatch; was "
        f"{COMPRESSED_SHA256} but wanted {params.sha256}."
    )
    for _ in range(2):
        with pytest.raises(RuntimeError) as info:
            dut.GetPath(package_name="compressed")
        assert str(info.value) == expected


@pytest.mark.parametrize("fetched", [False, True])
def test_a_merged_remote_package_still_fetches(
    drake: ModuleType, drake_models: Path, cache: Path, fetched: bool
) -> None:
    """AddMapMergeUnfetched and AddMapMergeFetched."""
    compressed = drake.multibody.parsing.PackageMap.MakeEmpty()
    compressed.AddRemote(package_name="compressed", params=_good_params(drake, drake_models))
    if fetched:
        compressed.GetPath(package_name="compressed")
    dut = drake.multibody.parsing.PackageMap.MakeEmpty()
    dut.AddMap(other_map=compressed)
    assert dut.GetPackageNames() == ["compressed"]
    assert (Path(dut.GetPath(package_name="compressed")) / "README").is_file()


def test_merging_the_same_remote_package_does_nothing(
    drake: ModuleType, drake_models: Path
) -> None:
    """AddMapDeduplicate."""
    PackageMap = drake.multibody.parsing.PackageMap
    dut = PackageMap.MakeEmpty()
    dut.AddRemote(package_name="compressed", params=_good_params(drake, drake_models))
    dut.AddMap(other_map=PackageMap(other=dut))
    assert dut.GetPackageNames() == ["compressed"]


def test_merging_a_different_remote_package_of_the_same_name_fails(
    drake: ModuleType, drake_models: Path
) -> None:
    """AddMapMismatch: the message shows both params as Drake's JSON."""
    PackageMap = drake.multibody.parsing.PackageMap
    params1 = _good_params(drake, drake_models)
    params2 = _good_params(drake, drake_models)
    params2.urls = [*params1.urls, params1.urls[-1]]
    dut = PackageMap.MakeEmpty()
    dut.AddRemote(package_name="compressed", params=params1)
    other = PackageMap.MakeEmpty()
    other.AddRemote(package_name="compressed", params=params2)
    with pytest.raises(RuntimeError) as info:
        dut.AddMap(other_map=other)
    assert str(info.value) == (
        "PackageMap::AddMap cannot merge the package definition for 'compressed' because the "
        f"remote package parameters differ ({params1.ToJson()} vs {params2.ToJson()})"
    )
    url = params1.urls[0]
    assert params1.ToJson() == (
        f'{{"sha256":"{COMPRESSED_SHA256}","strip_prefix":"compressed_prefix","urls":["{url}"]}}'
    )
