"""Readers of the files a job spec may name: triangle meshes (the legacy format of
docs/formats.md section 1, and STL, ASCII or binary) and clump templates (docs/spec.md,
ClumpShape.file). They read as the engine does (engine/mesh/mesh_io.cpp,
spec/clump_template.cpp), so a spec inlined here is the spec `dem submit` sends."""

from __future__ import annotations

import math
import re
import struct
from dataclasses import dataclass, field

Vec3 = tuple[float, float, float]


class MeshFileError(ValueError):
    """A file that cannot be read, with the file, the line and what is wrong."""


@dataclass
class TriangleMesh:
    vertices: list[Vec3] = field(default_factory=list)
    triangles: list[tuple[int, int, int]] = field(default_factory=list)  # 0-based vertex indices


# Fortran reals (docs/formats.md, "Rules common to every file"): 1.0D9, .5, 5., +3, and 1.0-100
# for 1.0e-100 (Fortran drops the exponent letter before a three-digit exponent).
_FORTRAN_REAL = re.compile(r"([+-]?)(\d+\.?\d*|\.\d+)(?:([eEdD])([+-]?\d+)|([+-]\d+))?")
_MAX_TOKEN = 128  # as the engine: far more than any program prints


def parse_fortran_real(token: str) -> float | None:
    """The token as a finite double, or None when it is not a number as a whole."""
    if len(token) > _MAX_TOKEN:
        return None
    m = _FORTRAN_REAL.fullmatch(token)
    if not m:
        return None
    sign, mantissa, letter, exponent, bare_exponent = m.groups()
    text = sign + mantissa
    if letter:
        text += "e" + exponent
    elif bare_exponent:
        text += "e" + bare_exponent
    value = float(text)
    # the engine's from_chars refuses values beyond a double's range rather than clamping them
    if math.isinf(value) or (value == 0.0 and any(c in "123456789" for c in mantissa)):
        return None
    return value


def _token_lines(text: str) -> list[tuple[int, list[str]]]:
    """(line number, tokens) of each non-blank line; spaces, tabs, CR and commas separate."""
    out = []
    for number, line in enumerate(text.split("\n"), start=1):
        tokens = [t for t in re.split(r"[ \t\r,]+", line) if t]
        if tokens:
            out.append((number, tokens))
    return out


def _real(name: str, number: int, token: str) -> float:
    value = parse_fortran_real(token)
    if value is None:
        raise MeshFileError(f'{name} line {number}: expected a number, got "{token}"')
    return value


def _count(name: str, number: int, token: str, what: str, least: int = 0) -> int:
    value = _real(name, number, token)
    if value < least or value != math.floor(value) or value > 2e9:
        raise MeshFileError(f'{name} line {number}: {what} must be a whole number >= {least}, got "{token}"')
    return int(value)


def _expect(name: str, number: int, tokens: list[str], count: int, what: str) -> None:
    if len(tokens) != count:
        raise MeshFileError(f"{name} line {number}: expected {count} values ({what}), got {len(tokens)}")


def parse_legacy_mesh(text: str, name: str) -> TriangleMesh:
    lines = _token_lines(text)
    if not lines:
        raise MeshFileError(f"{name}: the file is empty")
    first, header = lines[0]
    _expect(name, first, header, 2, "number of vertices, number of triangles")
    nv = _count(name, first, header[0], "the number of vertices")
    nt = _count(name, first, header[1], "the number of triangles")
    if nt == 0:
        raise MeshFileError(f"{name} line {first}: the mesh has no triangles")
    need = 1 + nv + nt
    if len(lines) < need:
        have = len(lines) - 1
        which = f"{have} of {nv} vertices" if have < nv else f"{have - nv} of {nt} triangles"
        raise MeshFileError(f"{name}: the file ends after {which} (truncated, last line {lines[-1][0]})")
    if len(lines) > need:
        raise MeshFileError(
            f"{name} line {lines[need][0]}: more lines than the {nv} vertices and {nt} triangles of line {first}"
        )
    mesh = TriangleMesh()
    for number, tokens in lines[1 : 1 + nv]:
        _expect(name, number, tokens, 3, "vertex x y z")
        mesh.vertices.append((_real(name, number, tokens[0]), _real(name, number, tokens[1]), _real(name, number, tokens[2])))
    for number, tokens in lines[1 + nv :]:
        _expect(name, number, tokens, 3, "1-based vertex indices i j k")
        i, j, k = (_count(name, number, t, "a vertex index (the first vertex is 1)", 1) - 1 for t in tokens)
        for index in (i, j, k):
            if index >= nv:
                raise MeshFileError(
                    f"{name} line {number}: triangle {len(mesh.triangles) + 1} refers to vertex {index + 1}, "
                    f"but the vertices are numbered 1 to {nv}"
                )
        mesh.triangles.append((i, j, k))
    return mesh


class _CornerIndex:
    """STL repeats the corners that facets share: one vertex per distinct corner, in order of first
    appearance (as the engine merges them), so an STL mesh has a legacy mesh's connectivity."""

    def __init__(self, mesh: TriangleMesh) -> None:
        self.mesh = mesh
        self.index: dict[Vec3, int] = {}

    def __call__(self, corner: Vec3) -> int:
        found = self.index.get(corner)
        if found is None:
            found = self.index[corner] = len(self.mesh.vertices)
            self.mesh.vertices.append(corner)
        return found


def _parse_ascii_stl(text: str, name: str) -> TriangleMesh:
    mesh = TriangleMesh()
    corner_index = _CornerIndex(mesh)
    corners: list[int] | None = None  # the current facet's; None outside a facet
    facet_line = 0
    for number, tokens in _token_lines(text):
        key = tokens[0]
        if key in ("solid", "endsolid", "outer", "endloop"):
            continue
        if key == "facet":
            if corners is not None:
                raise MeshFileError(f"{name} line {number}: \"facet\" before the previous facet's \"endfacet\"")
            corners, facet_line = [], number
        elif key == "vertex":
            if corners is None:
                raise MeshFileError(f'{name} line {number}: "vertex" outside a facet')
            if len(corners) == 3:
                raise MeshFileError(f"{name} line {number}: a facet with more than 3 vertices")
            _expect(name, number, tokens, 4, "vertex x y z")
            corners.append(corner_index((_real(name, number, tokens[1]), _real(name, number, tokens[2]), _real(name, number, tokens[3]))))
        elif key == "endfacet":
            if corners is None or len(corners) != 3:
                raise MeshFileError(f"{name} line {number}: a facet with {len(corners or [])} vertices (3 needed)")
            mesh.triangles.append((corners[0], corners[1], corners[2]))
            corners = None
        else:
            raise MeshFileError(f'{name} line {number}: unexpected "{key}" in an ASCII STL file')
    if corners is not None:
        raise MeshFileError(f"{name}: the file ends inside the facet of line {facet_line}")
    if not mesh.triangles:
        raise MeshFileError(f"{name}: the file has no facets")
    return mesh


def _parse_binary_stl(data: bytes, name: str) -> TriangleMesh:
    if len(data) < 84:
        raise MeshFileError(f"{name}: binary STL shorter than its 84-byte header")
    (count,) = struct.unpack_from("<I", data, 80)
    if len(data) < 84 + 50 * count:
        raise MeshFileError(
            f"{name}: binary STL header says {count} triangles, but the file holds only {(len(data) - 84) // 50} (truncated)"
        )
    if count == 0:
        raise MeshFileError(f"{name}: binary STL with no triangles")
    mesh = TriangleMesh()
    corner_index = _CornerIndex(mesh)
    for t in range(count):
        # after the facet's normal, which the engine recomputes
        c = struct.unpack_from("<9f", data, 84 + 50 * t + 12)
        a, b, d = (c[0], c[1], c[2]), (c[3], c[4], c[5]), (c[6], c[7], c[8])
        mesh.triangles.append((corner_index(a), corner_index(b), corner_index(d)))
    return mesh


def parse_stl(data: bytes, name: str) -> TriangleMesh:
    # "solid" opens ASCII files, but some binary exporters put it in the header too: a size that
    # matches the header's triangle count, or any NUL byte (text has none), means binary
    if len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]:
        return _parse_binary_stl(data, name)
    if b"\0" not in data and data.lstrip(b" \t\r\n").startswith(b"solid"):
        return _parse_ascii_stl(data.decode("latin-1"), name)
    return _parse_binary_stl(data, name)


def _read(path: str) -> bytes:
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError:
        raise MeshFileError(f"{path}: cannot open the file") from None


def read_mesh(path: str, format: str = "AUTO") -> TriangleMesh:
    """A mesh file as Mesh.format says: STL, LEGACY, or AUTO (by the extension: .stl is STL)."""
    if format == "STL" or (format == "AUTO" and path.lower().endswith(".stl")):
        return parse_stl(_read(path), path)
    return parse_legacy_mesh(_read(path).decode("latin-1"), path)


_PLAIN_NUMBER = re.compile(r"-?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")  # what std::from_chars reads


def read_clump_template(path: str) -> list[tuple[Vec3, float]]:
    """A clump template: one sphere a line, "x y z r" (blanks or commas between, # comments)."""
    try:
        with open(path, encoding="latin-1") as f:
            text = f.read()
    except OSError:
        raise MeshFileError(f"cannot open clump template {path}") from None
    spheres: list[tuple[Vec3, float]] = []
    for number, line in enumerate(text.split("\n"), start=1):
        # the C locale's blanks only: latin-1's NBSP is part of a word there, as in the engine
        words = [w for w in re.split(r"[ \t\v\f\r]+", line.split("#", 1)[0].replace(",", " ")) if w]
        if not words:
            continue
        values = [float(w) for w in words if _PLAIN_NUMBER.fullmatch(w)]
        if len(words) != 4 or len(values) != 4 or not all(math.isfinite(v) for v in values):
            raise MeshFileError(f'{path} line {number}: expected four numbers "x y z r"')
        if not values[3] > 0:
            raise MeshFileError(f"{path} line {number}: the radius must be positive")
        spheres.append(((values[0], values[1], values[2]), values[3]))
    if not spheres:
        raise MeshFileError(f"clump template {path} has no spheres")
    return spheres
