// libFuzzer target: `dem import`'s reading of a legacy INPT.inp (engine/legacy/inpt_file.hpp) and its
// translation (import/inpt_import.hpp), then the spec it makes through the spec loader. Every input
// must give a spec or an InptError naming the line; every spec made must load or be refused by name.
#include <cstdint>
#include <string>

#include "import/inpt_import.hpp"
#include "legacy/inpt_file.hpp"
#include "spec/spec_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dem::import::Imported imported;
  try {
    imported = dem::import::import_inpt(text, {});
  } catch (const dem::legacy::InptError&) {
    return 0;
  }
  if (imported.lines.empty()) __builtin_trap();  // every line has its fate
  try {
    dem::spec::to_scene(dem::spec::parse_json(imported.spec.dump()));
  } catch (const dem::spec::SpecError&) {
  }
  return 0;
}
