// The spec loader's problem list: every check of a field adds "path: what is wrong (got value;
// allowed range)", and the small helpers the section loaders share.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/vec.hpp"
#include "dem.pb.h"
#include "spec/input_range.hpp"
#include "spec/spec_loader.hpp"

namespace dem::spec {

// The shortest text that reads back as v: "0.10000001" stays itself ("(got 0.1)" hid why it was refused).
inline std::string num(double v) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general).ptr;
  return std::string(buf, end);
}

inline std::string at(const std::string& path, int index) { return path + "[" + std::to_string(index) + "]"; }

inline Vec3 vec(const api::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// A direction of any length (1e-300 too, whose square underflows): scaled by its largest component first.
inline Vec3 unit(const Vec3& d) {
  const Vec3 scaled = d / d.cwiseAbs().maxCoeff();
  return scaled.normalized();
}

// Collects problems, each "path: what is wrong (got value; allowed range)"; past the limits' count
// they are only counted (a spec of 20,000 bad particles once got a 121 MB list).
class Checker {
 public:
  explicit Checker(const SpecLimits& l = {}, double particle_bytes = kEstimatedBytesPerParticle)
      : limits(l), bytes_per_particle(particle_bytes) {}

  void fail(const std::string& path, const std::string& what) {
    ++found;
    if (problems.size() < limits.max_problems) problems.push_back(path + ": " + what);
  }
  // The problems as reported: the first ones, then how many more there were.
  std::vector<std::string> listed() const {
    std::vector<std::string> out = problems;
    if (found > problems.size()) {
      // built by appending: GCC 12 warns falsely (-Wrestrict) on "(" + std::string once inlined
      std::string more = "(";
      more += std::to_string(found - problems.size());
      more += " more problems not listed)";
      out.push_back(std::move(more));
    }
    return out;
  }
  bool failed() const { return found > 0; }
  std::size_t count() const { return found; }

  // Whether `more` particles fit beside the `already` made, within the spec's limit; a problem at
  // `path` when not.
  bool room(const std::string& path, std::size_t already, double more) {
    const double total = static_cast<double>(already) + more;
    if (total > static_cast<double>(limits.max_particles)) {
      fail(path, "would make " + num(std::round(total)) + " particles in all, more than the limit of " +
                     std::to_string(limits.max_particles));
      return false;
    }
    const double bytes = total * bytes_per_particle;
    if (limits.max_memory_bytes > 0 && bytes > limits.max_memory_bytes) {
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "would make %.0f particles in all, which would need about %.1f GB of memory to run (%.0f bytes "
                    "a particle), more than %s allows (%.1f GB)",
                    std::round(total), bytes / 1e9, bytes_per_particle, limits.memory_limit_name.c_str(),
                    limits.max_memory_bytes / 1e9);
      fail(path, buf);
      return false;
    }
    return true;
  }

  // A name shown in lists, terminals and file headers: no line breaks or escape sequences.
  void printable_name(const std::string& path, const std::string& name) {
    for (std::size_t k = 0; k < name.size(); ++k) {
      const auto c = static_cast<unsigned char>(name[k]);
      if (c < 0x20 || c == 0x7F) {
        char buf[120];
        std::snprintf(buf, sizeof buf, "must not hold control characters (byte %zu is 0x%02X)", k, c);
        fail(path, buf);
        return;
      }
    }
  }
  void positive(const std::string& path, double v) {
    if (!(v > 0) || !std::isfinite(v)) fail(path, "must be a positive number (got " + num(v) + ")");
  }
  void non_negative(const std::string& path, double v) {
    if (!(v >= 0) || !std::isfinite(v)) fail(path, "must be >= 0 (got " + num(v) + ")");
  }
  void in_range(const std::string& path, double v, double lo, double hi, bool lo_open, bool hi_open) {
    const bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    if (!ok)
      fail(path, "must be in " + std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]") +
                     " (got " + num(v) + ")");
  }
  // A vector quantity: finite, each component within the quantity's range (spec/input_range.hpp).
  void vector(const std::string& path, const api::Vec3& v, const Quantity& q) {
    const double largest = std::max({std::abs(v.x()), std::abs(v.y()), std::abs(v.z())});
    if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z()))
      fail(path, "must be finite (got (" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "))");
    else if (largest > q.max)
      fail(path, beyond(largest, q));
  }
  // A quantity >= 0 within its range's largest value (0 switches a feature off).
  void non_negative(const std::string& path, double v, const Quantity& q) {
    if (!(v >= 0) || !std::isfinite(v))
      fail(path, "must be >= 0 (got " + num(v) + ")");
    else if (v > q.max)
      fail(path, beyond(v, q));
  }
  // A positive quantity within its range.
  void positive(const std::string& path, double v, const Quantity& q) {
    if (!(v > 0) || !std::isfinite(v))
      fail(path, "must be a positive number (got " + num(v) + ")");
    else if (v > q.max)
      fail(path, beyond(v, q));
    else if (v < q.min)
      fail(path, "must be at least " + num(q.min) + (q.unit[0] ? " " : "") + q.unit + " (got " + num(v) +
                     "): far below any scene; check the units");
  }
  static std::string beyond(double v, const Quantity& q) {
    return "must be at most " + num(q.max) + (q.unit[0] ? " " : "") + q.unit + " in size (got " + num(v) +
           "): far beyond any scene; check the units";
  }

  std::vector<std::string> problems;
  SpecLimits limits;
  double bytes_per_particle;  // the memory estimate of one particle of this spec

 private:
  std::size_t found = 0;
};

}  // namespace dem::spec
