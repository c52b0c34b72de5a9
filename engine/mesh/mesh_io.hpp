// Mesh files: the legacy mesh format (legacy-formats.md section 1: "NV NT", NV vertex lines, NT
// 1-based triangle lines, Fortran-style numbers) and STL, ASCII or binary. Every reader checks the
// mesh (check_mesh) and throws MeshError with the file, the line (or triangle) and what is wrong.
#pragma once

#include <cstdio>
#include <string>

#include "mesh/triangle_mesh.hpp"

namespace dem {

TriangleMesh read_legacy_mesh(const std::string& path);
TriangleMesh read_stl(const std::string& path);  // ASCII or binary, told apart by content and size
// By the extension: .stl is STL, anything else the legacy format.
TriangleMesh read_mesh(const std::string& path);

// Parses the legacy format from text (`name` only labels errors).
TriangleMesh parse_legacy_mesh(const std::string& text, const std::string& name);
// Parses STL bytes.
TriangleMesh parse_stl(const std::string& bytes, const std::string& name);

// Writes the legacy format (%.6e coordinates, lengths divided by `length_unit` metres).
void write_legacy_mesh(std::FILE* out, const TriangleMesh& mesh, double length_unit = 1.0);

}  // namespace dem
