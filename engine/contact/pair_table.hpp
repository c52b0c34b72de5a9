// The coefficients of every pair of materials of a scene, made once by the contact law's `mix`.
#pragma once

#include <vector>

#include "core/scene.hpp"

namespace dem {

template <class Pair>
class PairTable {
 public:
  PairTable() = default;
  template <class Mix>
  PairTable(const Scene& scene, Mix&& mix) : count_(static_cast<int>(scene.materials.size())) {
    params_.reserve(static_cast<size_t>(count_) * count_);
    for (int a = 0; a < count_; ++a)
      for (int b = 0; b < count_; ++b)
        params_.push_back(mix(scene.materials[a], scene.materials[b], scene.interaction(a, b), scene.contact));
  }

  const Pair& operator()(int a, int b) const { return params_[a * count_ + b]; }
  int material_count() const { return count_; }

 private:
  int count_ = 0;
  std::vector<Pair> params_;
};

}  // namespace dem
