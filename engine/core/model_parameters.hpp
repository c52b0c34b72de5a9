// The parameters of the contact models a scene chose (contact/model_traits.hpp declares them per
// model), as the spec gave them: by the schema's field name, absent ones taking the model's default.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <string_view>

namespace dem {

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// One parameter of a model: a double field of the schema's ContactModel message.
struct ModelParameter {
  std::string_view field;  // the schema's field name, e.g. "tangential_stiffness_ratio"
  double default_value;
  double min;  // allowed range [min, max]
  double max;
  std::string_view meaning;  // for the docs and for error messages
};

class ModelParameters {
 public:
  void set(std::string_view field, double value) { given_[std::string(field)] = value; }
  bool has(std::string_view field) const { return given_.count(std::string(field)) > 0; }
  double value(const ModelParameter& p) const {
    const auto it = given_.find(std::string(p.field));
    return it == given_.end() ? p.default_value : it->second;
  }
  const std::map<std::string, double>& given() const { return given_; }

 private:
  std::map<std::string, double> given_;
};

}  // namespace dem
