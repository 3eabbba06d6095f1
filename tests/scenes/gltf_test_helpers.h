#pragma once
// Small glTF files for the loader tests. Geometry is given as literal arrays and lands in
// one binary buffer (a .bin beside the .gltf, or the GLB BIN chunk); the JSON is an
// nlohmann::json the test can edit freely before writing, e.g. to break one thing.
#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace phyir::scenes::test {

// An empty folder for the running test: <gtest temp dir>/phyir_scenes_test/<suite>.<test>.
inline std::filesystem::path fresh_test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "phyir_scenes_test" /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void write_bytes(const std::filesystem::path& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

class GltfBuilder {
 public:
  nlohmann::json doc = {{"asset", {{"version", "2.0"}, {"generator", "phyir loader tests"}}},
                        {"bufferViews", nlohmann::json::array()},
                        {"accessors", nlohmann::json::array()},
                        {"meshes", nlohmann::json::array()},
                        {"nodes", nlohmann::json::array()}};
  std::vector<unsigned char> bin;

  // Appends raw bytes (4-byte aligned) as a new bufferView; returns its index.
  int add_view(const void* data, size_t size, size_t stride = 0) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (stride != 0) view["byteStride"] = stride;
    bin.insert(bin.end(), static_cast<const unsigned char*>(data),
               static_cast<const unsigned char*>(data) + size);
    return append("bufferViews", view);
  }

  int add_accessor(const nlohmann::json& accessor) { return append("accessors", accessor); }

  template <typename Vec>
  int add_floats(const std::vector<Vec>& values) {
    static const char* kTypes[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
    const int view = add_view(values.data(), values.size() * sizeof(Vec));
    return add_accessor({{"bufferView", view},
                         {"componentType", 5126},
                         {"count", values.size()},
                         {"type", kTypes[Vec::length()]}});
  }

  // u8 (5121), u16 (5123) or u32 (5125) indices, by the element type.
  template <typename T>
  int add_indices(const std::vector<T>& indices) {
    const int component = sizeof(T) == 1 ? 5121 : sizeof(T) == 2 ? 5123 : 5125;
    const int view = add_view(indices.data(), indices.size() * sizeof(T));
    return add_accessor(
        {{"bufferView", view}, {"componentType", component}, {"count", indices.size()}, {"type", "SCALAR"}});
  }

  int add_mesh(const std::string& name, const std::vector<nlohmann::json>& primitives) {
    return append("meshes", {{"name", name}, {"primitives", primitives}});
  }

  int add_node(const nlohmann::json& node) { return append("nodes", node); }

  // A mesh of one primitive over `positions` (and `normals` when given), returns the mesh.
  int add_triangles(const std::string& name, const std::vector<glm::vec3>& positions,
                    const std::vector<uint16_t>& indices, const std::vector<glm::vec3>& normals = {},
                    nlohmann::json extra = nlohmann::json::object()) {
    nlohmann::json primitive = extra;
    primitive["attributes"]["POSITION"] = add_floats(positions);
    if (!normals.empty()) primitive["attributes"]["NORMAL"] = add_floats(normals);
    if (!indices.empty()) primitive["indices"] = add_indices(indices);
    return add_mesh(name, {primitive});
  }

  void set_scene(const std::vector<int>& roots) {
    doc["scenes"] = nlohmann::json::array({{{"nodes", roots}}});
    doc["scene"] = 0;
  }

  // name.gltf plus name.bin in `dir`.
  std::filesystem::path write_gltf(const std::filesystem::path& dir, const std::string& name) {
    nlohmann::json out = without_empty_arrays(doc);
    if (!bin.empty()) {
      write_bytes(dir / (name + ".bin"), bin.data(), bin.size());
      out["buffers"] = nlohmann::json::array({{{"uri", name + ".bin"}, {"byteLength", bin.size()}}});
    }
    const std::filesystem::path path = dir / (name + ".gltf");
    std::ofstream(path) << out.dump(1);
    return path;
  }

  // A GLB container: header, JSON chunk, BIN chunk (glTF 2.0 section 4.4).
  std::filesystem::path write_glb(const std::filesystem::path& dir, const std::string& name) {
    nlohmann::json out = without_empty_arrays(doc);
    std::vector<unsigned char> chunk = bin;
    while (chunk.size() % 4 != 0) chunk.push_back(0);
    if (!bin.empty()) out["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
    std::string json_text = out.dump();
    while (json_text.size() % 4 != 0) json_text.push_back(' ');
    std::vector<unsigned char> glb;
    auto put_u32 = [&](uint32_t v) {
      unsigned char b[4];
      std::memcpy(b, &v, 4);
      glb.insert(glb.end(), b, b + 4);
    };
    const size_t total = 12 + 8 + json_text.size() + (chunk.empty() ? 0 : 8 + chunk.size());
    put_u32(0x46546C67);
    put_u32(2);
    put_u32(static_cast<uint32_t>(total));
    put_u32(static_cast<uint32_t>(json_text.size()));
    put_u32(0x4E4F534A);
    glb.insert(glb.end(), json_text.begin(), json_text.end());
    if (!chunk.empty()) {
      put_u32(static_cast<uint32_t>(chunk.size()));
      put_u32(0x004E4942);
      glb.insert(glb.end(), chunk.begin(), chunk.end());
    }
    const std::filesystem::path path = dir / (name + ".glb");
    write_bytes(path, glb.data(), glb.size());
    return path;
  }

 private:
  // The schema gives every top-level array minItems 1: a test that adds no node, say, omits "nodes".
  static nlohmann::json without_empty_arrays(nlohmann::json root) {
    for (auto it = root.begin(); it != root.end();) it = it->is_array() && it->empty() ? root.erase(it) : std::next(it);
    return root;
  }

  int append(const char* array, const nlohmann::json& item) {
    if (!doc.contains(array)) doc[array] = nlohmann::json::array();
    doc[array].push_back(item);
    return static_cast<int>(doc[array].size()) - 1;
  }
};

// The triangle most tests start from: counter-clockwise in the XY plane, facing +Z.
inline std::vector<glm::vec3> unit_triangle() { return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}; }

}  // namespace phyir::scenes::test
