// libFuzzer target: `dem import`'s reading of a legacy INPT.inp (engine/legacy/inpt_file.hpp) and its
// translation (import/inpt_import.hpp). Every input must give a spec with every line's fate, or an
// InptError naming the line. (The specs it makes go through the spec loader in the unit tests: here
// a BallastDEM file's stones would take a minute each to make under the sanitizers, and the loader
// has fuzz targets of its own.)
#include <cstdint>
#include <string>

#include "import/inpt_import.hpp"
#include "legacy/inpt_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dem::import::Imported imported;
  try {
    imported = dem::import::import_inpt(text, {});
  } catch (const dem::legacy::InptError&) {
    return 0;
  }
  if (imported.lines.empty()) __builtin_trap();   // every line has its fate
  const std::string json = imported.spec.dump();  // and the spec is JSON (no NaN or infinity to write)
  if (json.find("null") != std::string::npos) __builtin_trap();
  return 0;
}
