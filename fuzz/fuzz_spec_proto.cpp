// libFuzzer target: a job spec as protobuf bytes (what `dem submit` and the server take), through
// the same checks as the JSON target. With DEM_FUZZ_WRITE_SEED=SPEC.json:OUT.pb set, writes that
// JSON spec's protobuf bytes (a seed of the corpus) and stops.
#include <cstdlib>
#include <fstream>

#include "fuzz/spec_checks.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* paths = std::getenv("DEM_FUZZ_WRITE_SEED")) {
    const std::string both = paths;
    const std::size_t colon = both.find(':');
    const std::string bytes = dem::spec::read_json_file(both.substr(0, colon)).SerializeAsString();
    std::ofstream(both.substr(colon + 1), std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  dem::fuzz::check_spec([&] { return dem::spec::parse_binary(bytes); });
  return 0;
}
