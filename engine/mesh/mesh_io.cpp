#include "mesh/mesh_io.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "legacy/legacy_formats.hpp"

namespace dem {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError(path + ": cannot open the file");
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Splits text into lines of whitespace-separated tokens, skipping blank lines; keeps line numbers.
struct TokenLine {
  int number;
  std::vector<std::string> tokens;
};

std::vector<TokenLine> token_lines(const std::string& text) {
  // by hand, not with streams: a 100,000-facet ASCII STL is 700,000 lines
  std::vector<TokenLine> lines;
  auto separator = [](char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == ','; };
  std::size_t at = 0;
  for (int number = 1; at < text.size(); ++number) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    TokenLine out{number, {}};
    for (std::size_t k = at; k < end;) {
      while (k < end && separator(text[k])) ++k;
      const std::size_t start = k;
      while (k < end && !separator(text[k])) ++k;
      if (k > start) out.tokens.emplace_back(text, start, k - start);
    }
    if (!out.tokens.empty()) lines.push_back(std::move(out));
    at = end + 1;
  }
  return lines;
}

double real_at(const std::string& name, const TokenLine& line, int k) {
  const auto value = legacy::parse_fortran_real(line.tokens[k]);
  if (!value)
    throw MeshError(name + " line " + std::to_string(line.number) + ": expected a number, got \"" + line.tokens[k] +
                    "\"");
  return *value;
}

int count_at(const std::string& name, const TokenLine& line, int k, const char* what, int least = 0) {
  const double value = real_at(name, line, k);
  if (value < least || value != std::floor(value) || value > 2e9)
    throw MeshError(name + " line " + std::to_string(line.number) + ": " + what +
                    " must be a whole number >= " + std::to_string(least) + ", got \"" + line.tokens[k] + "\"");
  return static_cast<int>(value);
}

void expect_tokens(const std::string& name, const TokenLine& line, std::size_t count, const char* what) {
  if (line.tokens.size() != count)
    throw MeshError(name + " line " + std::to_string(line.number) + ": expected " + std::to_string(count) +
                    " values (" + what + "), got " + std::to_string(line.tokens.size()));
}

TriangleMesh parse_ascii_stl(const std::string& text, const std::string& name) {
  TriangleMesh mesh;
  std::map<std::tuple<double, double, double>, int> index_of;  // STL repeats shared corners: merge them
  std::vector<int> triangle_line;
  std::array<int, 3> tri{};
  int corners = -1;  // corners read in the current facet; -1 outside a facet
  int facet_line = 0;
  for (const TokenLine& line : token_lines(text)) {
    const std::string& key = line.tokens[0];
    auto fail = [&](const std::string& what) {
      throw MeshError(name + " line " + std::to_string(line.number) + ": " + what);
    };
    if (key == "solid" || key == "endsolid" || key == "outer" || key == "endloop") continue;
    if (key == "facet") {
      if (corners >= 0) fail("\"facet\" before the previous facet's \"endfacet\"");
      corners = 0;
      facet_line = line.number;
    } else if (key == "vertex") {
      if (corners < 0) fail("\"vertex\" outside a facet");
      if (corners == 3) fail("a facet with more than 3 vertices");
      expect_tokens(name, line, 4, "vertex x y z");
      const Vec3 v(real_at(name, line, 1), real_at(name, line, 2), real_at(name, line, 3));
      auto [it, added] = index_of.try_emplace({v.x(), v.y(), v.z()}, static_cast<int>(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(v);
      tri[corners++] = it->second;
    } else if (key == "endfacet") {
      if (corners != 3) fail("a facet with " + std::to_string(std::max(corners, 0)) + " vertices (3 needed)");
      mesh.triangles.push_back(tri);
      triangle_line.push_back(facet_line);
      corners = -1;
    } else {
      fail("unexpected \"" + key + "\" in an ASCII STL file");
    }
  }
  if (corners >= 0) throw MeshError(name + ": the file ends inside the facet of line " + std::to_string(facet_line));
  if (mesh.triangles.empty()) throw MeshError(name + ": the file has no facets");
  check_mesh(mesh, [&](std::size_t t) { return name + " line " + std::to_string(triangle_line[t]); });
  return mesh;
}

TriangleMesh parse_binary_stl(const std::string& bytes, const std::string& name) {
  if (bytes.size() < 84) throw MeshError(name + ": binary STL shorter than its 84-byte header");
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  const std::size_t need = 84 + 50 * static_cast<std::size_t>(count);
  if (bytes.size() < need)
    throw MeshError(name + ": binary STL header says " + std::to_string(count) +
                    " triangles, but the file holds only " + std::to_string((bytes.size() - 84) / 50) + " (truncated)");
  if (count == 0) throw MeshError(name + ": binary STL with no triangles");
  TriangleMesh mesh;
  std::map<std::tuple<float, float, float>, int> index_of;
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + 84 + 50 * static_cast<std::size_t>(t);
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, record + 12 + 12 * static_cast<std::size_t>(k),
                  12);  // after the facet normal, which is recomputed
      auto [it, added] = index_of.try_emplace({xyz[0], xyz[1], xyz[2]}, static_cast<int>(mesh.vertices.size()));
      if (added) mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
      tri[k] = it->second;
    }
    mesh.triangles.push_back(tri);
  }
  check_mesh(mesh, [&](std::size_t t) { return name + " facet " + std::to_string(t + 1); });
  return mesh;
}

}  // namespace

TriangleMesh parse_legacy_mesh(const std::string& text, const std::string& name) {
  const std::vector<TokenLine> lines = token_lines(text);
  if (lines.empty()) throw MeshError(name + ": the file is empty");
  expect_tokens(name, lines[0], 2, "number of vertices, number of triangles");
  const int nv = count_at(name, lines[0], 0, "the number of vertices");
  const int nt = count_at(name, lines[0], 1, "the number of triangles");
  if (nt == 0) throw MeshError(name + " line " + std::to_string(lines[0].number) + ": the mesh has no triangles");
  const std::size_t need = 1 + static_cast<std::size_t>(nv) + nt;
  if (lines.size() < need) {
    const std::size_t have = lines.size() - 1;
    const std::string which = have < static_cast<std::size_t>(nv)
                                  ? std::to_string(have) + " of " + std::to_string(nv) + " vertices"
                                  : std::to_string(have - nv) + " of " + std::to_string(nt) + " triangles";
    throw MeshError(name + ": the file ends after " + which + " (truncated, last line " +
                    std::to_string(lines.back().number) + ")");
  }
  if (lines.size() > need)
    throw MeshError(name + " line " + std::to_string(lines[need].number) + ": more lines than the " +
                    std::to_string(nv) + " vertices and " + std::to_string(nt) + " triangles of line " +
                    std::to_string(lines[0].number));
  TriangleMesh mesh;
  mesh.vertices.reserve(nv);
  for (int v = 0; v < nv; ++v) {
    const TokenLine& line = lines[1 + v];
    expect_tokens(name, line, 3, "vertex x y z");
    mesh.vertices.emplace_back(real_at(name, line, 0), real_at(name, line, 1), real_at(name, line, 2));
  }
  mesh.triangles.reserve(nt);
  for (int t = 0; t < nt; ++t) {
    const TokenLine& line = lines[1 + nv + t];
    expect_tokens(name, line, 3, "1-based vertex indices i j k");
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) tri[k] = count_at(name, line, k, "a vertex index (the first vertex is 1)", 1) - 1;
    mesh.triangles.push_back(tri);
  }
  check_mesh(mesh, [&](std::size_t t) { return name + " line " + std::to_string(lines[1 + nv + t].number); });
  return mesh;
}

TriangleMesh parse_stl(const std::string& bytes, const std::string& name) {
  // "solid" opens ASCII files, but some binary exporters put it in the header too: a size that
  // matches the header's triangle count, or any NUL byte (text has none), means binary.
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50 * static_cast<std::size_t>(count)) return parse_binary_stl(bytes, name);
  }
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  const bool text = bytes.find('\0') == std::string::npos;
  if (text && first != std::string::npos && bytes.compare(first, 5, "solid") == 0) return parse_ascii_stl(bytes, name);
  return parse_binary_stl(bytes, name);
}

TriangleMesh read_legacy_mesh(const std::string& path) { return parse_legacy_mesh(read_file(path), path); }
TriangleMesh read_stl(const std::string& path) { return parse_stl(read_file(path), path); }

TriangleMesh read_mesh(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext == "stl" ? read_stl(path) : read_legacy_mesh(path);
}

void write_legacy_mesh(std::FILE* out, const TriangleMesh& mesh, double length_unit) {
  // std::to_chars: the text of printf's %.6e, never with a locale's decimal comma
  std::string text = std::to_string(mesh.vertices.size()) + " " + std::to_string(mesh.triangles.size()) + "\n";
  char digits[64];
  for (const Vec3& v : mesh.vertices) {
    for (int axis = 0; axis < 3; ++axis) {
      const auto r =
          std::to_chars(digits, digits + sizeof digits, v[axis] / length_unit, std::chars_format::scientific, 6);
      text.append(digits, r.ptr);
      text.push_back(axis < 2 ? ' ' : '\n');
    }
  }
  for (const auto& t : mesh.triangles)
    text += std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  std::fwrite(text.data(), 1, text.size(), out);
}

}  // namespace dem
