"""MuJoCo ``<asset>``: materials and meshes, as Drake 1.51.1 reads them (measured).

Every ``<material>`` must have a ``name`` (``ERROR: Material elements must
have a name attribute.``, at the ``<asset>``'s line); the last of a name wins,
and a geom takes its ``rgba``.

A ``<mesh>`` takes its class's defaults (``class``, else ``main``); its
``smoothnormal``, ``maxhullvert``, ``vertex``, ``refpos`` and ``refquat`` and a
``<plugin>`` child are warned about. With a ``file``: the name defaults to the
file's stem; ``scale`` (3, default 1 1 1); the path is the file's if absolute,
else below the compiler's ``meshdir`` (or ``assetdir``), which is itself below
the model file's folder (the working folder for model text) unless absolute;
made canonical. It must exist (``The mesh asset "P" could not be found.``)
and be an ``.obj`` (any case; else ``Drake's MuJoCo parser currently only
supports mesh files in .obj format, but the meshfile "P" was requested. See
https://drake.mit.edu/troubleshooting.html for additional resources.``), both
errors at the ``<asset>``'s line. Without a ``file`` it is warned about and
ignored. A ``<texture>`` child is warned about (``The texture element is not
supported, ...``), then ``<hfield>`` and ``<skin>`` children.
"""

from __future__ import annotations

import os

import numpy as np

from reimpl.geometry import Mesh
from reimpl.multibody.parsing import _mjcf_values as values
from reimpl.multibody.parsing._mjcf_context import MjcfContext
from reimpl.multibody.parsing._mjcf_defaults import apply_defaults, class_of
from reimpl.multibody.parsing._xml import XmlElement, children

__all__ = ["read_asset", "stem"]

_MESH_UNSUPPORTED = ("smoothnormal", "maxhullvert", "vertex", "refpos", "refquat")


def stem(path: str) -> str:
    """std::filesystem::path(path).stem(): the file name without its last extension."""
    name = path.rsplit("/", 1)[-1]
    dot = name.rfind(".")
    if name in (".", "..") or dot <= 0:
        return name
    return name[:dot]


def _resolve(context: MjcfContext, file: str) -> str:
    """The mesh file's canonical path (compiler ``meshdir`` and the model's folder)."""
    path = file
    if not os.path.isabs(path):
        meshdir = context.compiler.meshdir
        if meshdir is None:
            path = os.path.join(context.main_dir, path)
        elif os.path.isabs(meshdir):
            path = os.path.join(meshdir, path)
        else:
            path = os.path.join(context.main_dir, meshdir, path)
    return os.path.realpath(path)


def _mesh(context: MjcfContext, asset: XmlElement, node: XmlElement) -> None:
    d = context.d
    apply_defaults(context, "mesh", class_of(node), node)
    d.warn_unsupported_attributes(node, _MESH_UNSUPPORTED)
    d.warn_unsupported_elements(node, ("plugin",))
    file = node.get("file")
    if file is None:
        d.warning(
            asset,
            f"The mesh asset named {node.get('name') or ''} did not specify a 'file' attribute "
            "and so will be ignored.",
        )
        return
    name = node.get("name")
    if name is None:
        name = stem(file)
    scale = values.vector(node, "scale", 3) or [1.0, 1.0, 1.0]
    path = _resolve(context, file)
    if not os.path.exists(path):
        raise d.error(asset, f'The mesh asset "{path}" could not be found.')
    if os.path.splitext(path)[1].lower() != ".obj":
        raise d.error(
            asset,
            "Drake's MuJoCo parser currently only supports mesh files in .obj format, but the "
            f'meshfile "{path}" was requested. See https://drake.mit.edu/troubleshooting.html '
            "for additional resources.",
        )
    Mesh(path, scale3=np.asarray(scale))  # N.B. Drake makes the Mesh (and checks it) here.
    context.meshes[name] = (path, (scale[0], scale[1], scale[2]))


def read_asset(context: MjcfContext, node: XmlElement) -> None:
    """ParseAsset."""
    for material in children(node, "material"):
        name = material.get("name")
        if name is None:
            raise context.d.error(node, "ERROR: Material elements must have a name attribute.")
        context.materials[name] = material
    for mesh in children(node, "mesh"):
        _mesh(context, node, mesh)
    if children(node, "texture"):
        context.d.warning(
            node,
            "The texture element is not supported, see https://drake.mit.edu/troubleshooting.html "
            "for additional resources.",
        )
    context.d.warn_unsupported_elements(node, ("hfield", "skin"))
