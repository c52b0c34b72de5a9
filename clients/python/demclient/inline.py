"""Inlining the files a job spec names: the server reads no files of the client's, so a mesh file
becomes the mesh's `vertices` and `triangles`, and a clump template file its shape's `spheres`,
as `dem submit` does (spec/referenced_files.cpp)."""

from __future__ import annotations

import copy
import os
from typing import Any, Iterator

from .errors import SpecFileError
from .meshes import MeshFileError, read_clump_template, read_mesh

# The protobuf JSON mapping takes a field by its lowerCamelCase name or its .proto name.
_CLUMP_SHAPES = ("clumpShapes", "clump_shapes")
_ADD_WALLS = ("addWalls", "add_walls")
_FORMATS = {0: "AUTO", 1: "LEGACY", 2: "STL"}  # Mesh.Format, by number as the mapping also allows


def resolve_file(name: str, base_dir: str) -> str:
    """Where a named file is: relative to the spec's folder, or as given when absolute."""
    return name if not base_dir or os.path.isabs(name) else os.path.join(base_dir, name)


def _list(parent: Any, *keys: str) -> list[Any]:
    if not isinstance(parent, dict):
        return []
    for key in keys:
        value = parent.get(key)
        if isinstance(value, list):
            return value
    return []


def _meshes(spec: dict[str, Any]) -> Iterator[tuple[dict[str, Any], str]]:
    """Every mesh of the spec with its field path, in the engine's order."""

    def mesh_of(owner: Any, key: str, path: str) -> Iterator[tuple[dict[str, Any], str]]:
        if isinstance(owner, dict) and isinstance(owner.get(key), dict):
            yield owner[key], f"{path}.{key}"

    for k, wall in enumerate(_list(spec, "walls")):
        yield from mesh_of(wall, "mesh", f"walls[{k}]")
    for k, packing in enumerate(_list(spec, "packings")):
        yield from mesh_of(packing, "inside", f"packings[{k}]")
    for k, lattice in enumerate(_list(spec, "lattices")):
        yield from mesh_of(lattice, "inside", f"lattices[{k}]")
    for k, stage in enumerate(_list(spec, "stages")):
        for j, wall in enumerate(_list(stage, *_ADD_WALLS)):
            yield from mesh_of(wall, "mesh", f"stages[{k}].addWalls[{j}]")


def file_references(spec: dict[str, Any]) -> list[str]:
    """The field paths of every file the spec names ("walls[0].mesh.file", ...)."""
    paths = [f"{path}.file" for mesh, path in _meshes(spec) if mesh.get("file")]
    for k, shape in enumerate(_list(spec, *_CLUMP_SHAPES)):
        if isinstance(shape, dict) and shape.get("file"):
            paths.append(f"clumpShapes[{k}].file")
    return paths


def _inline_mesh(mesh: dict[str, Any], base_dir: str) -> None:
    fmt = mesh.get("format", "AUTO")
    fmt = _FORMATS.get(fmt, str(fmt)) if isinstance(fmt, int) else str(fmt)
    read = read_mesh(resolve_file(str(mesh["file"]), base_dir), fmt)
    del mesh["file"]
    mesh.pop("format", None)
    mesh["vertices"] = [{"x": x, "y": y, "z": z} for x, y, z in read.vertices]
    # inline triangles are 1-based, as in the legacy file
    mesh["triangles"] = [{"i": i + 1, "j": j + 1, "k": k + 1} for i, j, k in read.triangles]


def _inline_shape(shape: dict[str, Any], base_dir: str) -> None:
    spheres = read_clump_template(resolve_file(str(shape["file"]), base_dir))
    del shape["file"]
    shape["spheres"] = [{"center": {"x": c[0], "y": c[1], "z": c[2]}, "radius": r} for c, r in spheres]


def inline_files(spec: dict[str, Any], base_dir: str = "") -> dict[str, Any]:
    """A copy of `spec` with the files it names inline, read relative to `base_dir` (the spec
    file's folder; "" for the working folder). Raises SpecFileError naming the field and the
    file of each one that cannot be read. A mesh or shape that has both a file and inline content
    is left as it is, for the server to name the conflict."""
    out = copy.deepcopy(spec)
    problems: list[str] = []
    for mesh, path in _meshes(out):
        if mesh.get("file") and not mesh.get("vertices") and not mesh.get("triangles"):
            try:
                _inline_mesh(mesh, base_dir)
            except MeshFileError as e:
                problems.append(f"{path}.file: {e}")
    for k, shape in enumerate(_list(out, *_CLUMP_SHAPES)):
        if isinstance(shape, dict) and shape.get("file") and not shape.get("spheres"):
            try:
                _inline_shape(shape, base_dir)
            except MeshFileError as e:
                problems.append(f"clumpShapes[{k}].file: {e}")
    if problems:
        raise SpecFileError(problems)
    return out
