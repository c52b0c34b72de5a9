#include "spec/json_keys.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <set>

#include <nlohmann/json.hpp>

#include "spec/json_field_key.hpp"

namespace dem::spec {
namespace {

// Walks the document keeping the path to where it is and each open object's keys.
class KeyWalker : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::vector<std::string> repeated;

  bool key(string_t& k) override {
    Level& level = levels_.back();
    level.key = k;
    if (!level.fields.insert(json_field_key(k)).second) repeated.push_back(path());
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

namespace {

const char* json_kind(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::array:
      return "a list";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::boolean:
      return "true or false";
    default:
      return "a number";
  }
}

void check_lists(const nlohmann::json& object, const google::protobuf::Descriptor& message, const std::string& at,
                 std::vector<std::string>& problems) {
  using google::protobuf::FieldDescriptor;
  for (const auto& [key, value] : object.items()) {
    if (key.empty()) {  // the parser's own words: "Proto fields must have a name."
      problems.push_back((at.empty() ? std::string("spec") : at) + ": a key is empty (\"\"): unknown field");
      continue;
    }
    const FieldDescriptor* field = field_named(message, key);
    if (field == nullptr || field->is_map()) continue;  // unknown: the parser names it
    const std::string path = at.empty() ? key : at + "." + key;
    // an enum as a number: a value's number is taken as that value, any other number was read as
    // the unset value (contact.normal 7: 'no normal model "" in this build')
    auto check_enum = [&](const nlohmann::json& v, const std::string& where) {
      if (field->type() != FieldDescriptor::TYPE_ENUM || !v.is_number()) return;
      const std::int64_t n = v.is_number_integer() ? v.get<std::int64_t>() : std::int64_t{-1} << 40;
      const bool known = n >= std::numeric_limits<int>::min() && n <= std::numeric_limits<int>::max() &&
                         field->enum_type()->FindValueByNumber(static_cast<int>(n)) != nullptr;
      if (!known)
        problems.push_back(where + ": expected one of " + enum_names(*field->enum_type()) + ", got " + v.dump());
    };
    const bool nested = field->type() == FieldDescriptor::TYPE_MESSAGE &&
                        field->message_type()->full_name().rfind("google.protobuf.", 0) != 0;
    if (!field->is_repeated()) {
      if (nested && value.is_object()) check_lists(value, *field->message_type(), path, problems);
      check_enum(value, path);
      continue;
    }
    if (!value.is_array()) {
      if (!value.is_null()) problems.push_back(path + ": expected a list, got " + json_kind(value));
      continue;
    }
    for (std::size_t k = 0; k < value.size(); ++k) {
      const std::string item = path + "[" + std::to_string(k) + "]";
      if (value[k].is_null() || value[k].is_array())
        problems.push_back(item + ": expected " + expected_item(*field) + ", got " + json_kind(value[k]));
      else if (nested && value[k].is_object())
        check_lists(value[k], *field->message_type(), item, problems);
      else
        check_enum(value[k], item);
    }
  }
}

}  // namespace

std::vector<std::string> list_problems(const nlohmann::json& document, const google::protobuf::Descriptor& message) {
  std::vector<std::string> problems;
  if (document.is_object()) check_lists(document, message, "", problems);
  return problems;
}

std::vector<std::string> repeated_keys(const std::string& json) {
  KeyWalker walker;
  nlohmann::json::sax_parse(json, &walker);
  return walker.repeated;
}

std::string enum_names(const google::protobuf::EnumDescriptor& type) {
  std::string names;
  for (int k = 0; k < type.value_count(); ++k) {
    const std::string& name = type.value(k)->name();
    if (name.find("UNSPECIFIED") != std::string::npos) continue;
    names += (names.empty() ? "" : ", ") + name;
  }
  return names;
}

std::string expected_item(const google::protobuf::FieldDescriptor& field) {
  using google::protobuf::FieldDescriptor;
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_MESSAGE:
      return "an object";
    case FieldDescriptor::CPPTYPE_STRING:
      return "a string";
    case FieldDescriptor::CPPTYPE_DOUBLE:
    case FieldDescriptor::CPPTYPE_FLOAT:
      return "a number";
    case FieldDescriptor::CPPTYPE_BOOL:
      return "true or false";
    case FieldDescriptor::CPPTYPE_ENUM:
      return "a name";
    default:
      return "a whole number";
  }
}

const google::protobuf::FieldDescriptor* field_named(const google::protobuf::Descriptor& message,
                                                     const std::string& key) {
  if (const auto* f = message.FindFieldByName(key)) return f;
  return message.FindFieldByCamelcaseName(key);
}

}  // namespace dem::spec
