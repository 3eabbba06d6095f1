#pragma once
// How the glTF writer prints numbers. nlohmann::json prints a double in its shortest
// round-trip form, so a float widened to double prints all its binary digits
// (0.3499999940395355); these helpers choose what to print instead.
#include <fmt/format.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cmath>

namespace phyir::scenes::gltf_write {

// Factors rounded to 6 decimals print short ("0.35"); a millionth is far below what 8-bit
// textures or renderers resolve.
inline double tidy(float v) { return std::round(static_cast<double>(v) * 1e6) / 1e6; }

inline nlohmann::json tidy_array(const float* v, int n) {
  nlohmann::json a = nlohmann::json::array();
  for (int i = 0; i < n; ++i) a.push_back(tidy(v[i]));
  return a;
}

// The shortest decimal that reads back as exactly `v` (fmt's float formatting), as a JSON
// number: light values round-trip to the bit without printing 17 digits. Whole numbers stay
// floating-point ("2.0"), as nlohmann::json prints a double. `v` must be finite.
inline nlohmann::json exact(float v) {
  const nlohmann::json parsed = nlohmann::json::parse(fmt::format("{}", v));
  return parsed.get<double>();
}

template <int N>
nlohmann::json exact_array(const glm::vec<N, float>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (int i = 0; i < N; ++i) a.push_back(exact(v[i]));
  return a;
}

}  // namespace phyir::scenes::gltf_write
