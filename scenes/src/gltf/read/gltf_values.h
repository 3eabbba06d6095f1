#pragma once
// Reading extension objects and extras (tinygltf::Value) with type checks whose
// failures name the object and the property.
#include <glm/glm.hpp>

#include <optional>
#include <string>

#include "gltf/read/gltf_context.h"

namespace phyir::scenes::gltf {

// `v` as a float when it is finite and inside float's range, else nullopt (converting a
// larger double to float is undefined behaviour, and JSON allows 1e300).
std::optional<float> to_finite_float(double v);

// The member `key` of `object`, or nullptr when `object` is not an object or lacks it.
const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key);

// A finite number, nullopt when absent; fails naming `where` and `key` when it is not one.
std::optional<float> number_member(const Diagnostics& diagnostics, const tinygltf::Value& object,
                                   const std::string& key, const std::string& where);

// An integer, nullopt when absent.
std::optional<int> integer_member(const Diagnostics& diagnostics, const tinygltf::Value& object,
                                  const std::string& key, const std::string& where);

// An array of two finite numbers, nullopt when absent.
std::optional<glm::vec2> vec2_member(const Diagnostics& diagnostics, const tinygltf::Value& object,
                                     const std::string& key, const std::string& where);

// A value as a 3-vector of finite numbers, nullopt when it is not one.
std::optional<glm::vec3> as_vec3(const tinygltf::Value& value);

}  // namespace phyir::scenes::gltf
