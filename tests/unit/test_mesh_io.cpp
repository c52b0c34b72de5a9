// Mesh files: the legacy format and STL (ASCII and binary) read and round-trip; every kind of bad
// file gives its own error naming the file, the line and what is wrong.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "mesh/mesh_io.hpp"

namespace dem {
namespace {

const std::string kTwoTriangles =
    "4 2\n"
    "0.0 0.0 0.0\n"
    "1.0D0 0 0\n"
    "1.000000e+000 1. 0\n"
    ".0 1.0E0 0\n"
    "1 2 3\n"
    "1 3 4\n";

std::string error_of(const std::string& text, bool stl = false) {
  try {
    if (stl)
      parse_stl(text, "m.stl");
    else
      parse_legacy_mesh(text, "m.dat");
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

TEST(LegacyMesh, ReadsFortranNumbersAndOneBasedIndices) {
  const TriangleMesh m = parse_legacy_mesh(kTwoTriangles, "m.dat");
  ASSERT_EQ(m.vertices.size(), 4u);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.vertices[2], Vec3(1, 1, 0));
  EXPECT_EQ(m.triangles[1], (std::array<int, 3>{0, 2, 3}));
}

TEST(LegacyMesh, RoundTripsThroughTheWriter) {
  TriangleMesh m = parse_legacy_mesh(kTwoTriangles, "m.dat");
  m.vertices[1] = Vec3(754.7503, 1405.110, 1393.944);  // the manual's sample magnitudes
  const auto path = std::filesystem::temp_directory_path() / ("dem_mesh_" + std::to_string(::getpid()) + ".dat");
  std::FILE* out = std::fopen(path.c_str(), "wb");
  ASSERT_NE(out, nullptr);
  write_legacy_mesh(out, m);
  std::fclose(out);
  const TriangleMesh back = read_legacy_mesh(path.string());
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "4 2");
  std::filesystem::remove(path);
  ASSERT_EQ(back.triangles, m.triangles);
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    EXPECT_TRUE(back.vertices[v].isApprox(m.vertices[v], 1e-6)) << v;  // %.6e keeps 7 digits
}

TEST(LegacyMesh, EachBadFileHasItsOwnError) {
  EXPECT_EQ(error_of(""), "m.dat: the file is empty");
  EXPECT_EQ(error_of("4\n"), "m.dat line 1: expected 2 values (number of vertices, number of triangles), got 1");
  EXPECT_EQ(error_of("4 2.5\n"), "m.dat line 1: the number of triangles must be a whole number >= 0, got \"2.5\"");
  EXPECT_EQ(error_of("4 2\n0 0 0\n1 0 0\n"), "m.dat: the file ends after 2 of 4 vertices (truncated, last line 3)");
  EXPECT_EQ(error_of("4 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n1 2 3\n"),
            "m.dat: the file ends after 1 of 2 triangles (truncated, last line 6)");
  EXPECT_EQ(error_of("4 2\n0 0 0\n1 0 x\n1 1 0\n0 1 0\n1 2 3\n1 3 4\n"), "m.dat line 3: expected a number, got \"x\"");
  EXPECT_EQ(error_of("4 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n1 2 3\n1 3 9\n"),
            "m.dat line 7: triangle 2 refers to vertex 9, but the vertices are numbered 1 to 4");
  EXPECT_EQ(error_of("4 2\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 2 3\n1 3 4\n"),
            "m.dat line 6: triangle 1 is degenerate (its corners are repeated or on one line)");
  EXPECT_EQ(error_of("4 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n1 2 3\n1 3 4\n5 5 5\n"),
            "m.dat line 8: more lines than the 4 vertices and 2 triangles of line 1");
  EXPECT_EQ(error_of("4 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 2 3\n1 3 4\n"),
            "m.dat line 6: a vertex index (the first vertex is 1) must be a whole number >= 1, got \"0\"");
  EXPECT_EQ(error_of("4 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n-3 2 3\n1 3 4\n"),
            "m.dat line 6: a vertex index (the first vertex is 1) must be a whole number >= 1, got \"-3\"");
}

const std::string kAsciiStl =
    "solid square\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n"
    "    endloop\n  endfacet\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 1 0\n      vertex 0 1 0\n"
    "    endloop\n  endfacet\n"
    "endsolid square\n";

std::string binary_stl(const TriangleMesh& m, std::uint32_t claimed) {
  std::string bytes(80, ' ');
  bytes.replace(0, 5, "solid");  // some exporters do this: the size must decide
  bytes.append(reinterpret_cast<const char*>(&claimed), 4);
  for (const auto& t : m.triangles) {
    float record[12] = {0, 0, 1};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) record[3 + 3 * k + d] = static_cast<float>(m.vertices[t[k]][d]);
    bytes.append(reinterpret_cast<const char*>(record), sizeof record);
    bytes.append(2, '\0');
  }
  return bytes;
}

TEST(Stl, AsciiSharesCornersBetweenFacets) {
  const TriangleMesh m = parse_stl(kAsciiStl, "m.stl");
  EXPECT_EQ(m.vertices.size(), 4u);  // 6 corners, 4 distinct: connectivity for the contact test
  EXPECT_EQ(m.triangles.size(), 2u);
}

TEST(Stl, BinaryReadsTheSameMeshAsAscii) {
  const TriangleMesh ascii = parse_stl(kAsciiStl, "m.stl");
  const TriangleMesh binary = parse_stl(binary_stl(ascii, 2), "m.stl");
  EXPECT_EQ(binary.vertices, ascii.vertices);
  EXPECT_EQ(binary.triangles, ascii.triangles);
}

TEST(Stl, EachBadFileHasItsOwnError) {
  const TriangleMesh ascii = parse_stl(kAsciiStl, "m.stl");
  std::string cut = binary_stl(ascii, 2);
  cut.resize(cut.size() - 20);
  EXPECT_EQ(error_of(cut, true), "m.stl: binary STL header says 2 triangles, but the file holds only 1 (truncated)");
  EXPECT_EQ(error_of("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n", true),
            "m.stl: the file ends inside the facet of line 2");
  EXPECT_EQ(error_of("solid x\nfacet\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 2 2 2\n", true),
            "m.stl line 6: a facet with more than 3 vertices");
  EXPECT_EQ(error_of("solid x\nfacet\nvertex 0 0 0\nvertex 1 0 0\nvertex 2 0 0\nendfacet\n", true),
            "m.stl line 2: triangle 1 is degenerate (its corners are repeated or on one line)");
  EXPECT_EQ(error_of("solid x\nfacet\nvertex 0 0 zero\n", true), "m.stl line 3: expected a number, got \"zero\"");
  EXPECT_EQ(error_of("solid x\nendsolid x\n", true), "m.stl: the file has no facets");
  EXPECT_EQ(error_of("3 0\n0 0 0\n1 0 0\n0 1 0\n"), "m.dat line 1: the mesh has no triangles");
}

TEST(MeshFiles, MissingFileIsNamed) {
  try {
    read_mesh("/nonexistent/terrain.stl");
    FAIL();
  } catch (const MeshError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/terrain.stl: cannot open the file");
  }
}

}  // namespace
}  // namespace dem
