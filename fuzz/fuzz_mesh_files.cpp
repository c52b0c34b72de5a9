// libFuzzer target: the mesh readers (the legacy mesh text format and STL, ASCII or binary). The
// first byte chooses the reader. Every input must give a checked mesh or a MeshError.
#include <cstdint>
#include <string>

#include "mesh/mesh_io.hpp"
#include "mesh/triangle_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    if (data[0] & 1)
      dem::parse_stl(bytes, "fuzz.stl");
    else
      dem::parse_legacy_mesh(bytes, "fuzz.dat");
  } catch (const dem::MeshError&) {
  }
  return 0;
}
