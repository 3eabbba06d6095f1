#pragma once
// The building blocks of the schema check (gltf_schema.h): one JSON object at a known
// place in the file, asked about its properties one rule at a time. The first broken rule
// ends the load with "<file>: <where> is <value>: <requirement> (<document>, <rule>)", e.g.
// "room.gltf: accessors[3].byteOffset is -4: must be >= 0 (glTF 2.0 schema, accessor.byteOffset)".
#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <string>

#include "gltf/read/gltf_context.h"

namespace phyir::scenes::gltf::schema {

using nlohmann::json;

// An interval of numbers as JSON schema states it (minimum, exclusiveMinimum, ...).
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  double max = std::numeric_limits<double>::infinity();
  bool max_exclusive = false;

  bool contains(double value) const;
  std::string requirement() const;  // "must be >= 0", "must be in (0, 1.5708]"
};

Range at_least(double min);
Range above(double min);
Range unit_interval();  // [0, 1]

// Array lengths: minItems and maxItems.
struct Length {
  size_t min = 0;
  size_t max = std::numeric_limits<size_t>::max();
};

inline Length exactly(size_t n) { return {n, n}; }
inline Length at_least_items(size_t n) { return {n, std::numeric_limits<size_t>::max()}; }

// What every object of one file shares: the messages' file name and the declared extensions.
struct Document {
  const Diagnostics& diagnostics;
  std::set<std::string> extensions_used;
};

// Where an object's rules come from: the schema it follows ("glTF 2.0 schema"), the spec
// whose prose adds rules ("glTF 2.0 spec"), and its name there ("accessor.sparse").
struct Source {
  std::string schema;
  std::string spec;
  std::string object;
};

Source core(const std::string& object);
Source extension(const std::string& name, const std::string& object);

class Object {
 public:
  // The file's root object (path "").
  Object(const json& value, Source source, const Document& document);

  const json& value() const { return *value_; }
  const Document& document() const { return *document_; }
  bool has(const char* key) const { return value_->contains(key); }

  // Typed properties; absent ones pass unless required(). Each returns the value when present
  // (integers as doubles too: JSON numbers, and only compared).
  void required(const char* key) const;
  std::optional<double> integer(const char* key, const Range& range = {}) const;
  std::optional<double> index(const char* key) const;  // glTFid: an integer >= 0
  std::optional<double> number(const char* key, const Range& range = {}) const;
  bool boolean(const char* key) const;
  std::optional<std::string> string(const char* key) const;
  void integer_enum(const char* key, std::initializer_list<long long> allowed) const;
  std::optional<std::string> string_enum(const char* key, const std::set<std::string>& allowed) const;
  std::optional<size_t> number_array(const char* key, Length length, const Range& items = {}) const;
  void index_array(const char* key) const;   // unique glTFids, at least one
  void string_array(const char* key) const;  // unique strings, at least one
  void index_map(const char* key) const;     // {"NAME": glTFid, ...}, at least one entry
  void index_maps(const char* key) const;    // an array of those, at least one

  // Sub-objects, checked by `check` when present (arrays: each item, at least one item).
  using Check = std::function<void(const Object&)>;
  bool object(const char* key, const std::string& schema_object, const Check& check) const;
  bool objects(const char* key, const std::string& schema_object, const Check& check) const;
  // The top-level arrays (accessors, nodes, ...): items named "nodes[2] ('lamp')" in messages.
  void named_objects(const char* key, const std::string& schema_object, const Check& check) const;
  // extensions.<name> when present, checked against that extension's schema.
  void extension(const char* name, const std::string& schema_object, const Check& check) const;

  // "must not be both" / "needs" rules between properties (schema `not` and `dependencies`).
  void forbid_together(const char* key, const char* other) const;
  void depends_on(const char* key, const char* needed) const;

  // Ends the load naming `key` of this object; `state` says what it is ("is -4", "is missing").
  [[noreturn]] void fail(const std::string& key, const std::string& state,
                         const std::string& requirement) const;
  // The same for a rule of the spec's prose rather than its schema.
  [[noreturn]] void fail_spec(const std::string& key, const std::string& state,
                              const std::string& requirement) const;

 private:
  Object(const json& value, std::string path, Source source, const Document& document);
  Object child(const json& value, const std::string& path, const Source& source) const;
  void check_extensions_member() const;
  std::string where(const std::string& key) const;
  std::string rule(const std::string& key) const;
  void check_index_map(const json& map, const std::string& key) const;
  void check_integer(const json& value, const std::string& key, const char* requirement) const;
  [[noreturn]] void fail_rule(const std::string& key, const std::string& state,
                              const std::string& requirement, const std::string& document,
                              const std::string& rule_name) const;

  const json* value_;
  std::string path_;
  Source source_;
  const Document* document_;
};

// "is -4", "is \"4\"", "is [1,2,...]": a JSON value quoted short enough for a message.
std::string is(const json& value);

}  // namespace phyir::scenes::gltf::schema
