// Keys a JSON spec gives twice in one object. The protobuf parser keeps the last one silently; a
// spec given twice a value (or once as "normalStiffness" and once as "normal_stiffness", the two
// spellings it accepts) is a mistake to name, not to guess.
#pragma once

#include <string>
#include <vector>

#include <google/protobuf/descriptor.h>
#include <nlohmann/json.hpp>

namespace dem::spec {

// The field a key names, by either spelling the parser accepts (normal_stiffness, normalStiffness).
const google::protobuf::FieldDescriptor* field_named(const google::protobuf::Descriptor& message,
                                                     const std::string& key);

// What a value of `field` (one element of it, if it is repeated) is, in the words of the checks'
// messages: "a number", "a whole number", "a string", "true or false", "a name", "an object".
std::string expected_item(const google::protobuf::FieldDescriptor& field);

// An enum's names as a spec gives them ("LINEAR, HERTZ"): every value but the UNSPECIFIED one.
std::string enum_names(const google::protobuf::EnumDescriptor& type);

// The paths ("interactions[0].restitution") of the keys repeated in their object, in the order met.
// The text must be well-formed JSON (parse it for syntax first).
std::vector<std::string> repeated_keys(const std::string& json);

// The lists of a spec that are not lists: protobuf's JSON parser reads a single value given for a
// repeated field ("tags": "a", "materials": {...}) as a list of one, flattens a list inside a
// list, and drops a null element; each is a mistake to name ("tags: expected a list, got a
// string"). Also named here, where the parser's words would not say it: a key that is empty, and
// an enum given as a number that is none of its values. `message` is the descriptor the document
// is read as.
std::vector<std::string> list_problems(const nlohmann::json& document, const google::protobuf::Descriptor& message);

}  // namespace dem::spec
