// Live frames of a running job, encoded once per frame for every viewer (proto/dem.proto, Frame).
// A frame is cut into parts that are protobuf messages of their own: parts concatenated are one
// Frame message (protobuf merges concatenated messages), so each viewer gets the parts it needs
// without another copy or encoding.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace dem::server {

struct EncodedFrame {
  std::int64_t step = 0;
  std::shared_ptr<const std::string> base;          // everything but the radii and the force chains
  std::shared_ptr<const std::string> radii;         // the radii alone
  std::shared_ptr<const std::string> force_chains;  // the force chains alone; null when not asked for
  std::uint64_t radii_version = 0;                  // changes when the radii change (growth)
};

class FrameEncoder {
 public:
  explicit FrameEncoder(std::int64_t job) : job_(job) {}
  EncodedFrame encode(const Simulation& sim, bool with_force_chains);

 private:
  std::int64_t job_;
  std::vector<float> radii_;
  std::shared_ptr<const std::string> radii_part_;
  std::uint64_t radii_version_ = 0;
};

}  // namespace dem::server
