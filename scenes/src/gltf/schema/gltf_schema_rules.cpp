#include "gltf/schema/gltf_schema_rules.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <utility>

namespace phyir::scenes::gltf::schema {

namespace {

// The spec (section 3.2.1 "JSON encoding"): integers may be written 100.0 or 1e2.
bool is_integer(const json& value) {
  if (value.is_number_integer()) return true;
  if (!value.is_number_float()) return false;
  const double v = value.get<double>();
  return std::isfinite(v) && std::floor(v) == v;
}

std::string length_requirement(Length length) {
  if (length.min == length.max) return fmt::format("must have {} items", length.min);
  if (length.max == std::numeric_limits<size_t>::max())
    return fmt::format("must have at least {}", length.min);
  return fmt::format("must have {} to {} items", length.min, length.max);
}

std::string item(const char* key, size_t i) { return fmt::format("{}[{}]", key, i); }

}  // namespace

bool Range::contains(double value) const {
  const bool above_min = min_exclusive ? value > min : value >= min;
  const bool below_max = max_exclusive ? value < max : value <= max;
  return above_min && below_max;
}

std::string Range::requirement() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max)
    return fmt::format("must be in {}{}, {}{}", min_exclusive ? '(' : '[', min, max,
                       max_exclusive ? ')' : ']');
  if (has_min) return fmt::format("must be {} {}", min_exclusive ? ">" : ">=", min);
  return fmt::format("must be {} {}", max_exclusive ? "<" : "<=", max);
}

Range at_least(double min) { return Range{min, false}; }
Range above(double min) { return Range{min, true}; }
Range unit_interval() { return Range{0, false, 1, false}; }

Source core(const std::string& object) { return {"glTF 2.0 schema", "glTF 2.0 spec", object}; }

Source extension(const std::string& name, const std::string& object) {
  return {name + " schema", name + " spec", object};
}

std::string is(const json& value) {
  constexpr size_t kMaxShown = 40;
  std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > kMaxShown) text = text.substr(0, kMaxShown - 3) + "...";
  return "is " + text;
}

Object::Object(const json& value, Source source, const Document& document)
    : Object(value, "", std::move(source), document) {}

Object::Object(const json& value, std::string path, Source source, const Document& document)
    : value_(&value), path_(std::move(path)), source_(std::move(source)), document_(&document) {
  check_extensions_member();
}

Object Object::child(const json& value, const std::string& path, const Source& source) const {
  return Object(value, path, source, *document_);
}

std::string Object::where(const std::string& key) const {
  if (path_.empty()) return key;
  return key.empty() ? path_ : path_ + "." + key;
}

// The rule is named after the property, not the array item: node.rotation for rotation[2].
std::string Object::rule(const std::string& key) const {
  const std::string property = key.substr(0, key.find('['));
  return property.empty() ? source_.object : source_.object + "." + property;
}

void Object::fail(const std::string& key, const std::string& state, const std::string& requirement) const {
  fail_rule(key, state, requirement, source_.schema, rule(key));
}

void Object::fail_spec(const std::string& key, const std::string& state,
                       const std::string& requirement) const {
  fail_rule(key, state, requirement, source_.spec, rule(key));
}

void Object::fail_rule(const std::string& key, const std::string& state, const std::string& requirement,
                       const std::string& document, const std::string& rule_name) const {
  document_->diagnostics.fail("{} {}: {} ({}, {})", where(key), state, requirement, document, rule_name);
}

// glTFProperty.extensions: an object of objects, each named in extensionsUsed.
void Object::check_extensions_member() const {
  if (!value_->is_object() || !has("extensions")) return;
  const json& extensions = value_->at("extensions");
  if (!extensions.is_object()) fail("extensions", is(extensions), "must be an object");
  for (const auto& [name, value] : extensions.items()) {
    const std::string key = "extensions." + name;
    if (!value.is_object()) fail_rule(key, is(value), "must be an object", source_.schema, "extension");
    if (document_->extensions_used.count(name) == 0)
      fail_rule(key, "is not in extensionsUsed", "every extension used must be listed there", source_.spec,
                "glTF.extensionsUsed");
  }
}

void Object::required(const char* key) const {
  if (!has(key)) fail(key, "is missing", "required");
}

std::optional<double> Object::integer(const char* key, const Range& range) const {
  if (!has(key)) return std::nullopt;
  const json& value = value_->at(key);
  check_integer(value, key, "must be an integer");
  if (!range.contains(value.get<double>())) fail(key, is(value), range.requirement());
  return value.get<double>();
}

// The spec allows 4.0 and 4e0 for the integer 4; tinygltf 2.7 does not (a required one is
// an error, an optional one silently reads as absent: byteOffset 8.0 as 0), so it is
// refused as what it is, a limitation of this loader.
void Object::check_integer(const json& value, const std::string& key, const char* requirement) const {
  if (!is_integer(value)) fail(key, is(value), requirement);
  if (!value.is_number_float()) return;
  const double v = value.get<double>();
  const std::string plain = std::fabs(v) < 1e15 ? fmt::format("{:.0f}", v) : "a plain integer";
  fail_rule(
      key, is(value),
      "write it as " + plain +
          " (integers written with a decimal point or exponent are valid glTF, but tinygltf 2.7 reads them "
          "as absent)",
      "limitation of this loader", rule(key));
}

std::optional<double> Object::index(const char* key) const { return integer(key, at_least(0)); }

std::optional<double> Object::number(const char* key, const Range& range) const {
  if (!has(key)) return std::nullopt;
  const json& value = value_->at(key);
  if (!value.is_number()) fail(key, is(value), "must be a number");
  if (!range.contains(value.get<double>())) fail(key, is(value), range.requirement());
  return value.get<double>();
}

bool Object::boolean(const char* key) const {
  if (!has(key)) return false;
  if (!value_->at(key).is_boolean()) fail(key, is(value_->at(key)), "must be true or false");
  return true;
}

std::optional<std::string> Object::string(const char* key) const {
  if (!has(key)) return std::nullopt;
  const json& value = value_->at(key);
  if (!value.is_string()) fail(key, is(value), "must be a string");
  return value.get<std::string>();
}

void Object::integer_enum(const char* key, std::initializer_list<long long> allowed) const {
  const std::optional<double> value = integer(key);
  if (!value) return;
  for (const long long a : allowed)
    if (*value == static_cast<double>(a)) return;
  fail(key, is(value_->at(key)), fmt::format("must be one of {}", fmt::join(allowed, ", ")));
}

std::optional<std::string> Object::string_enum(const char* key, const std::set<std::string>& allowed) const {
  const std::optional<std::string> value = string(key);
  if (value && allowed.count(*value) == 0)
    fail(key, is(*value), fmt::format("must be one of \"{}\"", fmt::join(allowed, "\", \"")));
  return value;
}

std::optional<size_t> Object::number_array(const char* key, Length length, const Range& items) const {
  if (!has(key)) return std::nullopt;
  const json& array = value_->at(key);
  if (!array.is_array()) fail(key, is(array), "must be an array of numbers");
  if (array.size() < length.min || array.size() > length.max)
    fail(key, fmt::format("has {} items", array.size()), length_requirement(length));
  for (size_t i = 0; i < array.size(); ++i) {
    if (!array[i].is_number()) fail(item(key, i), is(array[i]), "must be a number");
    if (!items.contains(array[i].get<double>())) fail(item(key, i), is(array[i]), items.requirement());
  }
  return array.size();
}

void Object::index_array(const char* key) const {
  if (!has(key)) return;
  const json& array = value_->at(key);
  if (!array.is_array()) fail(key, is(array), "must be an array of indices");
  if (array.empty()) fail(key, "is empty", "must have at least 1 item");
  std::set<double> seen;
  for (size_t i = 0; i < array.size(); ++i) {
    check_integer(array[i], item(key, i), "must be an index (an integer >= 0)");
    if (array[i].get<double>() < 0) fail(item(key, i), is(array[i]), "must be an index (an integer >= 0)");
    if (!seen.insert(array[i].get<double>()).second)
      fail(item(key, i), is(array[i]) + " again", "items must be unique");
  }
}

void Object::string_array(const char* key) const {
  if (!has(key)) return;
  const json& array = value_->at(key);
  if (!array.is_array()) fail(key, is(array), "must be an array of strings");
  if (array.empty()) fail(key, "is empty", "must have at least 1 item");
  std::set<std::string> seen;
  for (size_t i = 0; i < array.size(); ++i) {
    if (!array[i].is_string()) fail(item(key, i), is(array[i]), "must be a string");
    if (!seen.insert(array[i].get<std::string>()).second)
      fail(item(key, i), is(array[i]) + " again", "items must be unique");
  }
}

void Object::index_map(const char* key) const {
  if (has(key)) check_index_map(value_->at(key), key);
}

void Object::index_maps(const char* key) const {
  if (!has(key)) return;
  const json& array = value_->at(key);
  if (!array.is_array()) fail(key, is(array), "must be an array of objects");
  if (array.empty()) fail(key, "is empty", "must have at least 1 item");
  for (size_t i = 0; i < array.size(); ++i) check_index_map(array[i], item(key, i));
}

void Object::check_index_map(const json& map, const std::string& key) const {
  if (!map.is_object()) fail(key, is(map), "must be an object of indices");
  if (map.empty()) fail(key, "is empty", "must have at least 1 entry");
  for (const auto& [name, value] : map.items()) {
    check_integer(value, key + "." + name, "must be an index (an integer >= 0)");
    if (value.get<double>() < 0) fail(key + "." + name, is(value), "must be an index (an integer >= 0)");
  }
}

bool Object::object(const char* key, const std::string& schema_object, const Check& check) const {
  if (!has(key)) return false;
  const json& value = value_->at(key);
  if (!value.is_object()) fail(key, is(value), "must be an object");
  check(child(value, where(key), Source{source_.schema, source_.spec, schema_object}));
  return true;
}

bool Object::objects(const char* key, const std::string& schema_object, const Check& check) const {
  if (!has(key)) return false;
  const json& array = value_->at(key);
  if (!array.is_array()) fail(key, is(array), "must be an array of objects");
  if (array.empty()) fail(key, "is empty", "must have at least 1 item");
  for (size_t i = 0; i < array.size(); ++i) {
    if (!array[i].is_object()) fail(item(key, i), is(array[i]), "must be an object");
    check(child(array[i], where(item(key, i)), Source{source_.schema, source_.spec, schema_object}));
  }
  return true;
}

void Object::named_objects(const char* key, const std::string& schema_object, const Check& check) const {
  if (!has(key)) return;
  const json& array = value_->at(key);
  if (!array.is_array()) fail(key, is(array), "must be an array of objects");
  if (array.empty()) fail(key, "is empty", "must have at least 1 item");
  for (size_t i = 0; i < array.size(); ++i) {
    const json& value = array[i];
    if (!value.is_object()) fail(item(key, i), is(value), "must be an object");
    // glTFChildOfRootProperty.name: a string, shown in every message about the object.
    const auto name = value.find("name");
    if (name != value.end() && !name->is_string())
      fail_rule(item(key, i) + ".name", is(*name), "must be a string", source_.schema,
                schema_object + ".name");
    const std::string label = name != value.end() ? fmt::format(" ('{}')", name->get<std::string>()) : "";
    check(child(value, where(item(key, i)) + label, Source{source_.schema, source_.spec, schema_object}));
  }
}

void Object::extension(const char* name, const std::string& schema_object, const Check& check) const {
  if (!has("extensions") || !value_->at("extensions").contains(name)) return;
  const json& value = value_->at("extensions").at(name);
  check(child(value, where(std::string("extensions.") + name), schema::extension(name, schema_object)));
}

void Object::forbid_together(const char* key, const char* other) const {
  if (has(key) && has(other))
    fail(key, fmt::format("and {} are both given", other), "only one of them is allowed");
}

void Object::depends_on(const char* key, const char* needed) const {
  if (has(key) && !has(needed))
    fail(key, fmt::format("is given without {}", needed), fmt::format("needs {}", needed));
}

}  // namespace phyir::scenes::gltf::schema
