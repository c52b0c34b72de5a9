// libFuzzer target: the readers of the legacy output files (ANIMATION_3D.dat, ANIMATION_2D.dat, ForceChain_3D.dat,
// the wall files, Force_Displacement.dat and the statistics rows), which the tests and the tools
// use on files cut short or damaged. The first byte chooses the reader. A reader reports a problem
// or a truncation; it never crashes.
#include <cstdint>
#include <sstream>
#include <string>

#include "legacy/legacy_formats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  namespace legacy = dem::legacy;
  switch (data[0] % 7) {
    case 0:
      legacy::read_animation(in);
      break;
    case 1:
      legacy::read_force_chains(in);
      break;
    case 2:
      legacy::read_wall_frames(in);
      break;
    case 3:
      legacy::read_wall_force_chains(in);
      break;
    case 4:
      legacy::read_force_displacement(in);
      break;
    case 5:
      legacy::read_rows(in, 1 + data[0] % 17);
      break;
    default:
      legacy::read_animation_2d(in);
      break;
  }
  return 0;
}
