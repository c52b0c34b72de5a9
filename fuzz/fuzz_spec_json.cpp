// libFuzzer target: a job spec as JSON, through the checks of `dem validate` (the loader, then the
// simulation's own set-up: the time step, the neighbour search, the first forces). Every input must
// end in a SpecError or SceneError or a valid scene; a crash, a leak or undefined behaviour is a bug.
#include "fuzz/spec_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dem::fuzz::check_spec([&] { return dem::spec::parse_json(text); });
  return 0;
}
