#include "gltf/read/gltf_values.h"

#include <cmath>
#include <limits>

namespace phyir::scenes::gltf {

namespace {

std::optional<float> as_finite_float(const tinygltf::Value& value) {
  if (!value.IsNumber()) return std::nullopt;
  return to_finite_float(value.GetNumberAsDouble());
}

}  // namespace

std::optional<float> to_finite_float(double v) {
  if (!std::isfinite(v) || std::abs(v) > static_cast<double>(std::numeric_limits<float>::max())) return std::nullopt;
  return static_cast<float>(v);
}

const tinygltf::Value* member(const tinygltf::Value& object, const std::string& key) {
  return object.IsObject() && object.Has(key) ? &object.Get(key) : nullptr;
}

std::optional<float> number_member(const Diagnostics& diagnostics, const tinygltf::Value& object,
                                   const std::string& key, const std::string& where) {
  const tinygltf::Value* value = member(object, key);
  if (value == nullptr) return std::nullopt;
  const auto number = as_finite_float(*value);
  if (!number) diagnostics.fail("{} {} is not a finite number", where, key);
  return number;
}

std::optional<int> integer_member(const Diagnostics& diagnostics, const tinygltf::Value& object,
                                  const std::string& key, const std::string& where) {
  const tinygltf::Value* value = member(object, key);
  if (value == nullptr) return std::nullopt;
  if (!value->IsInt()) diagnostics.fail("{} {} is not an integer", where, key);
  return value->GetNumberAsInt();
}

std::optional<glm::vec2> vec2_member(const Diagnostics& diagnostics, const tinygltf::Value& object,
                                     const std::string& key, const std::string& where) {
  const tinygltf::Value* value = member(object, key);
  if (value == nullptr) return std::nullopt;
  const auto x = value->ArrayLen() == 2 ? as_finite_float(value->Get(0)) : std::nullopt;
  const auto y = value->ArrayLen() == 2 ? as_finite_float(value->Get(1)) : std::nullopt;
  if (!x || !y) diagnostics.fail("{} {} is not an array of two finite numbers", where, key);
  return glm::vec2(*x, *y);
}

std::optional<glm::vec3> as_vec3(const tinygltf::Value& value) {
  if (value.ArrayLen() != 3) return std::nullopt;
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) {
    const auto c = as_finite_float(value.Get(i));
    if (!c) return std::nullopt;
    v[i] = *c;
  }
  return v;
}

}  // namespace phyir::scenes::gltf
