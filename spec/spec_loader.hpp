// From a job spec (proto/dem.proto, as JSON or protobuf bytes) to a checked Scene.
// Every problem is reported with the JSON path of the field, the value and what is allowed.
#pragma once

#include <stdexcept>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene.hpp"
#include "dem.pb.h"

namespace dem::spec {

class SpecError : public std::runtime_error {
 public:
  explicit SpecError(std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

// Parses the canonical JSON mapping; unknown fields and wrong types are errors.
api::JobSpec parse_json(const std::string& text);
// The JSON library's "number overflow parsing '1e400'" (`what`) with its place in `text`: "line 2,
// column 19: the number 1e400 is out of a double's range (about ±1.8e308)"; another message as it is.
std::string number_out_of_range(const std::string& text, const std::string& what);
// The canonical JSON mapping of a spec (fields at their defaults left out).
std::string to_json_text(const api::JobSpec& spec);
// Parses protobuf wire bytes.
api::JobSpec parse_binary(const std::string& bytes);
// Reads a JSON spec file (errors name the file).
api::JobSpec read_json_file(const std::string& path);

// What one spec may ask for in all; a front end may set lower limits of its own.
struct SpecLimits {
  std::int64_t max_particles = 50'000'000;
  std::int64_t max_triangles = 50'000'000;
  int max_threads = 256;           // numerics.threads
  int max_materials = 256;         // every pair of them has its coefficients: a table of M x M
  int max_walls = 10000;           // planes, plates and meshes: every particle is checked against each plane
  std::size_t max_name = 200;      // name, in bytes
  std::size_t max_problems = 100;  // problems listed in a SpecError (then "N more")
  // The memory a run may take, estimated from its particle count before any particle is made
  // (kEstimatedBytesPerParticle each, or ...BondedParticle with bonds); 0: no limit.
  // `memory_limit_name` says where it is set.
  double max_memory_bytes = 0;
  std::string memory_limit_name = "the memory limit";
};

// What a running particle costs in memory, all told (its state, its share of contacts and their
// history, neighbour lists, cells, the spec's copy), rounded up from the peak resident size per
// particle of a dense FCC packing with Hertz-Mindlin and rolling springs: 1,517 bytes, and 3,411
// with every touching pair bonded (docs/architecture.md, "What one job may cost").
inline constexpr double kEstimatedBytesPerParticle = 1600;
inline constexpr double kEstimatedBytesPerBondedParticle = 3500;

// A job's tags (JobSpec.tags): at most kMaxTags, each 1 to kMaxTagBytes letters, digits and
// - _ . : = (a tag is matched in a query, ?tag=a,b: no commas, spaces or escapes to get wrong).
inline constexpr int kMaxTags = 32;
inline constexpr std::size_t kMaxTagBytes = 64;
bool is_tag(std::string_view tag);

// Checks the spec and builds the scene; throws SpecError listing every problem found. Mesh files
// are read relative to `base_dir` (the spec file's folder; empty: the working directory).
Scene to_scene(const api::JobSpec& spec, const std::string& base_dir = "", const SpecLimits& limits = {});

}  // namespace dem::spec
