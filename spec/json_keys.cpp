#include "spec/json_keys.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include <nlohmann/json.hpp>

namespace dem::spec {
namespace {

// A key as the protobuf parser matches it: "normal_stiffness" and "normalStiffness" are one field.
std::string field_of(const std::string& key) {
  std::string out;
  for (char c : key)
    if (c != '_') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Walks the document keeping the path to where it is and each open object's keys.
class KeyWalker : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::vector<std::string> repeated;

  bool key(string_t& k) override {
    Level& level = levels_.back();
    level.key = k;
    if (!level.fields.insert(field_of(k)).second) repeated.push_back(path());
    return true;
  }
  bool start_object(std::size_t) override { return open(true); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_array() override { return close(); }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  struct Level {
    bool object = true;
    std::string key;  // the object's current key
    long index = -1;  // the array's current element
    std::set<std::string> fields;
  };
  std::vector<Level> levels_;

  // A value (or a container starting) takes the next place of an array.
  bool value() {
    if (!levels_.empty() && !levels_.back().object) ++levels_.back().index;
    return true;
  }
  bool open(bool object) {
    value();
    levels_.push_back({object, "", -1, {}});
    return true;
  }
  bool close() {
    levels_.pop_back();
    return true;
  }
  std::string path() const {
    std::string out;
    for (const Level& l : levels_) {
      // appended piece by piece: GCC 12 misreads `a + b` into a temporary as an overlapping copy
      // (a false -Wrestrict)
      if (l.object) {
        if (!out.empty()) out += '.';
        out += l.key;
      } else {
        out += '[';
        out += std::to_string(std::max(0L, l.index));
        out += ']';
      }
    }
    return out;
  }
};

}  // namespace

std::vector<std::string> repeated_keys(const std::string& json) {
  KeyWalker walker;
  nlohmann::json::sax_parse(json, &walker);
  return walker.repeated;
}

}  // namespace dem::spec
