#include "spec/spec_loader.hpp"

#include <google/protobuf/util/json_util.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <regex>
#include <sstream>
#include <fstream>

#include "spec/json_keys.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

std::string join(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += (s.empty() ? "" : "\n") + l;
  return s;
}

std::string printable_tag(const std::string& tag) {
  std::string shown = tag.substr(0, 64);
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return shown;
}

void check_triangle_count(const Scene& scene, Checker& check) {
  std::size_t triangles = 0;
  for (const WallInit& w : scene.walls)
    if (const MeshShape* m = std::get_if<MeshShape>(&w.shape)) triangles += m->triangles.size();
  if (static_cast<std::int64_t>(triangles) > check.limits.max_triangles)
    check.fail("walls", std::to_string(triangles) + " mesh triangles in all, more than the limit of " +
                            std::to_string(check.limits.max_triangles));
}

void check_tags(const api::JobSpec& spec, Checker& check) {
  if (spec.tags_size() > kMaxTags)
    check.fail("tags", "at most " + std::to_string(kMaxTags) + " tags (got " + std::to_string(spec.tags_size()) + ")");
  for (int k = 0; k < spec.tags_size() && k < kMaxTags; ++k) {
    const std::string& tag = spec.tags(k);
    const std::string path = "tags[" + std::to_string(k) + "]";
    if (!is_tag(tag))
      check.fail(path, "\"" + printable_tag(tag) + "\" is not a tag: 1 to " + std::to_string(kMaxTagBytes) +
                           " letters, digits and - _ . : =");
    for (int j = 0; j < k; ++j)
      if (spec.tags(j) == tag)
        check.fail(path, "\"" + tag + "\" is given twice (also tags[" + std::to_string(j) + "])");
  }
}

// What a field takes, found by its parent's path ("materials[0]") and its name ("density"): "a
// number", "a string", ...; "a single value" where the path leads to no field.
std::string scalar_kind(const std::string& parent, const std::string& name) {
  using google::protobuf::FieldDescriptor;
  auto field_of = [](const google::protobuf::Descriptor* d, const std::string& n) {
    return field_named(*d, n.substr(0, n.find('[')));  // "materials[0]": the field materials
  };
  const google::protobuf::Descriptor* d = api::JobSpec::descriptor();
  std::stringstream parts(parent);
  for (std::string part; !parent.empty() && std::getline(parts, part, '.');) {
    const FieldDescriptor* f = field_of(d, part);
    if (f == nullptr || f->message_type() == nullptr) return "a single value";
    d = f->message_type();
  }
  const FieldDescriptor* f = field_of(d, name);
  return f == nullptr ? "a single value" : expected_item(*f);
}

}  // namespace

SpecError::SpecError(std::vector<std::string> problems)
    : std::runtime_error(join(problems)), problems_(std::move(problems)) {}

// Protobuf's JSON errors name the field as "(parent) name: ..." or "(path): ..."; say them the way
// the checks do: "path: what is wrong".
std::string reword_protobuf_error(const std::string& message) {
  static const std::regex unknown(R"(^\(([^)]*)\) ?(.+?): Cannot find field\.?$)");
  static const std::regex unknown_top(R"(^(.+?): Cannot find field\.?$)");
  static const std::regex object_for_value(
      R"(^\(([^)]*)\): invalid value Starting an object on a scalar field for type (.+)$)");
  static const std::regex list_for_value(R"(^\(([^)]*)\) ?(.+?): Proto field is not repeating, cannot start list\.?$)");
  static const std::regex list_for_value_top(R"(^([^(].*?): Proto field is not repeating, cannot start list\.?$)");
  static const std::regex bad_value(R"(^\(([^)]*)\): invalid value (.*) for type TYPE_([A-Z0-9]+)$)");
  static const std::regex bad_enum(R"(^\(([^)]*)\): invalid value (.*) for type type\.googleapis\.com/(.+)$)");
  std::smatch m;
  auto field = [](const std::string& parent, const std::string& name) {
    return parent.empty() ? name : parent + "." + name;
  };
  if (std::regex_match(message, m, object_for_value))
    return field(m[1].str(), m[2].str()) + ": expected " + scalar_kind(m[1].str(), m[2].str()) + ", got an object";
  if (std::regex_match(message, m, list_for_value))
    return field(m[1].str(), m[2].str()) + ": expected " + scalar_kind(m[1].str(), m[2].str()) + ", got a list";
  if (std::regex_match(message, m, list_for_value_top))
    return m[1].str() + ": expected " + scalar_kind("", m[1].str()) + ", got a list";
  if (std::regex_match(message, m, bad_enum)) {
    if (google::protobuf::DescriptorPool::generated_pool()->FindMessageTypeByName(m[3].str()) != nullptr)
      return m[1].str() + ": expected an object, got " + m[2].str();
    std::string names;
    if (const auto* e = google::protobuf::DescriptorPool::generated_pool()->FindEnumTypeByName(m[3].str()))
      names = enum_names(*e);
    return m[1].str() + ": expected one of " + (names.empty() ? m[3].str() : names) + ", got " + m[2].str();
  }
  if (std::regex_match(message, m, unknown)) return m[1].str() + "." + m[2].str() + ": unknown field";
  if (std::regex_match(message, m, unknown_top)) return m[1].str() + ": unknown field";
  if (std::regex_match(message, m, bad_value)) {
    const std::string type = m[3].str();
    const std::string expected = type == "DOUBLE" || type == "FLOAT"     ? "a number"
                                 : type == "BOOL"                        ? "true or false"
                                 : type == "STRING"                      ? "a string"
                                 : type.find("INT") != std::string::npos ? "a whole number"
                                                                         : "a value of type " + type;
    return m[1].str() + ": expected " + expected + ", got " + m[2].str();
  }
  return "spec: " + message;
}

std::string number_out_of_range(const std::string& text, const std::string& what) {
  static const std::regex literal(R"(number overflow parsing '([^']+)')");
  std::smatch m;
  if (!std::regex_search(what, m, literal)) return what;
  const std::string number = m[1].str();
  std::string problem = "the number " + number + " is out of a double's range (about ±1.8e308)";
  auto in_number = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-';
  };
  // the first occurrence outside a string (a name or key may hold the same characters), as a token
  bool in_string = false;
  for (std::size_t at = 0; at < text.size(); ++at) {
    if (in_string) {
      if (text[at] == '\\')
        ++at;  // an escaped character, a quote too
      else if (text[at] == '"')
        in_string = false;
      continue;
    }
    if (text[at] == '"') {
      in_string = true;
      continue;
    }
    const std::size_t end = at + number.size();
    if (text.compare(at, number.size(), number) != 0 || (at > 0 && in_number(text[at - 1])) ||
        (end < text.size() && in_number(text[end])))
      continue;
    const std::size_t line_start = at == 0 ? 0 : text.rfind('\n', at - 1) + 1;  // npos + 1 is 0
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
    return "line " + std::to_string(line) + ", column " + std::to_string(at - line_start + 1) + ": " + problem;
  }
  return problem;
}

api::JobSpec parse_json(const std::string& text) {
  // Syntax first, with a line and column (protobuf's parser gives neither).
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw SpecError({std::string("spec: malformed JSON: ") + e.what()});
  } catch (const nlohmann::json::exception& e) {  // a number too large for a double (1e999)
    throw SpecError({"spec: malformed JSON: " + number_out_of_range(text, e.what())});
  }
  std::vector<std::string> repeated = repeated_keys(text);
  if (!repeated.empty()) {
    for (std::string& path : repeated)
      if (path.empty() || path.back() == '.')  // an empty key, given twice
        path = (path.empty() ? std::string("spec") : path.substr(0, path.size() - 1)) +
               ": a key is empty (\"\"), and given twice: unknown field";
      else
        path += ": is given twice in its object (the parser would keep the last one)";
    throw SpecError(repeated);
  }
  if (std::vector<std::string> lists = list_problems(document, *api::JobSpec::descriptor()); !lists.empty())
    throw SpecError(lists);
  api::JobSpec spec;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(text, &spec, options);
  if (!status.ok()) throw SpecError({reword_protobuf_error(std::string(status.message()))});
  return spec;
}

std::string to_json_text(const api::JobSpec& spec) {
  std::string text;
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  const auto status = google::protobuf::util::MessageToJsonString(spec, &text, options);
  if (!status.ok()) throw SpecError({"spec: cannot be written as JSON: " + std::string(status.message())});
  return text;
}

api::JobSpec parse_binary(const std::string& bytes) {
  api::JobSpec spec;
  if (!spec.ParseFromString(bytes)) throw SpecError({"spec: not a valid protobuf JobSpec message"});
  return spec;
}

api::JobSpec read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SpecError({path + ": cannot open the spec file"});
  std::stringstream text;
  text << in.rdbuf();
  try {
    return parse_json(text.str());
  } catch (const SpecError& e) {
    throw SpecError({path + ": " + e.what()});
  }
}

bool is_tag(std::string_view tag) {
  return !tag.empty() && tag.size() <= kMaxTagBytes && std::all_of(tag.begin(), tag.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == ':' || c == '=';
  });
}

Scene to_scene(const api::JobSpec& spec, const std::string& base_dir, const SpecLimits& limits) {
  Checker check(limits, spec.has_bonds() ? kEstimatedBytesPerBondedParticle : kEstimatedBytesPerParticle);
  if (spec.name().size() > limits.max_name)
    check.fail("name", "must be at most " + std::to_string(limits.max_name) + " bytes (got " +
                           std::to_string(spec.name().size()) + ")");
  check.printable_name("name", spec.name());
  check_tags(spec, check);
  Scene scene;
  scene.name = spec.name();
  SpecContext ctx(check, base_dir, scene);
  load_materials(spec, ctx);
  load_plane(spec, ctx);
  load_particles(spec, ctx);
  load_walls(spec, ctx);
  load_growth(spec, ctx);
  load_bonds(spec, ctx);
  load_stages(spec, ctx);
  load_sources(spec, ctx);
  check_interactions_complete(ctx);
  check_triangle_count(scene, check);
  load_run_settings(spec, ctx);
  check_plane(spec, ctx);
  if (check.failed()) throw SpecError(check.listed());
  return scene;
}

}  // namespace dem::spec
