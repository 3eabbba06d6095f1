#pragma once
// The glTF writer's one little-endian buffer, with one tightly packed buffer view per
// accessor (views shared between vertex attributes would need byteStride).
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace phyir::scenes::gltf_write {

class BufferEncoder {
 public:
  // A VEC2, VEC3 or VEC4 float accessor; with bounds, its exact per-component min and max (the
  // validator compares them with the buffer's contents; POSITION requires them).
  template <int N>
  int add_vectors(const std::vector<glm::vec<N, float>>& data, bool with_bounds) {
    const size_t offset = bin_.size();
    glm::vec<N, float> lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& v : data) {
      for (int c = 0; c < N; ++c) put_float(v[c]);
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    nlohmann::json accessor = {{"bufferView", add_view(offset, kArrayBuffer)},
                               {"componentType", kComponentFloat},
                               {"count", data.size()},
                               {"type", N == 2 ? "VEC2" : N == 3 ? "VEC3" : "VEC4"}};
    if (with_bounds) {
      nlohmann::json min = nlohmann::json::array(), max = nlohmann::json::array();
      for (int c = 0; c < N; ++c) {
        min.push_back(static_cast<double>(lo[c]));
        max.push_back(static_cast<double>(hi[c]));
      }
      accessor["min"] = min;
      accessor["max"] = max;
    }
    return add_accessor(std::move(accessor));
  }

  int add_indices(const std::vector<uint32_t>& indices);

  const std::string& bytes() const { return bin_; }
  const nlohmann::json& views() const { return views_; }
  const nlohmann::json& accessors() const { return accessors_; }

 private:
  // glTF enums (specification section 5).
  static constexpr int kArrayBuffer = 34962;
  static constexpr int kElementArrayBuffer = 34963;
  static constexpr int kComponentFloat = 5126;
  static constexpr int kComponentUnsignedInt = 5125;

  void put_u32(uint32_t w);
  void put_float(float f);
  int add_view(size_t offset, int target);
  int add_accessor(nlohmann::json accessor);

  std::string bin_;
  nlohmann::json views_ = nlohmann::json::array();
  nlohmann::json accessors_ = nlohmann::json::array();
};

}  // namespace phyir::scenes::gltf_write
