#pragma once

#include <stdexcept>
#include <string>

namespace dem {

// Impossible or unsupported input, found before anything runs. The message names what is wrong.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The run became unstable; the message names the step, the particle and the likely cause.
class InstabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace dem
