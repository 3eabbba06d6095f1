#pragma once
// The FutureHouse release's folder layout and encodings, as its published loader reads them
// (github.com/LZleejean/FutureHouse, DataSet.py: classes KePanoMaterial and KePanoLighting).
// docs/futurehouse.md lists every convention with its source and every assumption.
//
//   ROOT/split.json                                            {"train": [plan], "val": [..], "test": [..]}
//   ROOT/KePanoData/<plan>/ue4_result/CubemapData/<i>_<map>.hdr     7 Radiance maps per view, i = 0, 1, ..
//   ROOT/KePanoLight/<plan>/ue4_result/LightProbeData/<i>_light.exr  the view's probe mosaic
//   ROOT/phyir/                                                ours: export.json and what the format has
//                                                              no slot for (outside every path the loader reads)
#include <array>
#include <filesystem>
#include <string>

#include <glm/glm.hpp>

namespace phyir::dataset::futurehouse {

inline constexpr const char* kDataFolder = "KePanoData";
inline constexpr const char* kLightFolder = "KePanoLight";
inline constexpr const char* kSplitFile = "split.json";
inline constexpr const char* kSidecarFolder = "phyir";
inline constexpr const char* kExportRecordFile = "export.json";  // in kSidecarFolder, written last
inline constexpr const char* kExportFormat = "phyir-futurehouse-export";

// The seven maps of a view. The loader counts the files of a CubemapData folder and skips the
// plan unless the count is a multiple of 7, so a view is exactly these and nothing else.
enum class Map { Image, Albedo, Roughness, Metallic, Mask, Normal, Depth };
inline constexpr std::array<Map, 7> kMaps = {Map::Image, Map::Albedo, Map::Roughness, Map::Metallic,
                                             Map::Mask,  Map::Normal, Map::Depth};
inline constexpr int kMapsPerView = 7;
const char* map_name(Map map);  // "image", "albedo", ...

std::filesystem::path maps_folder(const std::filesystem::path& root, const std::string& plan);
std::filesystem::path map_path(const std::filesystem::path& root, const std::string& plan, int index, Map map);
std::filesystem::path light_folder(const std::filesystem::path& root, const std::string& plan);
std::filesystem::path light_path(const std::filesystem::path& root, const std::string& plan, int index);
// ROOT/phyir/<plan>/<i>_<name>.exr: our masks the format cannot hold.
std::filesystem::path sidecar_path(const std::filesystem::path& root, const std::string& plan, int index,
                                   const std::string& name);

// Single-value maps (roughness, metallic, mask, depth) are read by the loader as OpenCV's
// channel 0, which for a Radiance file is its blue channel: we read channel 2 of OpenImageIO's
// RGB and write R = G = B.
inline constexpr int kScalarChannel = 2;

// Depth: the file holds d / 5 (the loader multiplies by max_depth / 2 = 10 / 2); its depth_mask
// keeps 0 < d <= 10 m. Euclidean distance to the panorama's centre (docs/futurehouse.md).
inline constexpr float kDepthScale = 5.0f;
inline constexpr float kLoaderMaxDepth = 10.0f;
inline float decode_depth(float stored) { return stored * kDepthScale; }
inline float encode_depth(float metres) { return metres / kDepthScale; }

// Normals: the file holds (n + 1) / 2 per component, R G B = x y z (the loader reverses
// OpenCV's BGR, then computes 2 v - 1).
inline float decode_normal(float stored) { return 2.0f * stored - 1.0f; }
inline float encode_normal(float n) { return 0.5f * (n + 1.0f); }

// The mask: 1 on surfaces that are neither light sources nor transmissive (the paper's
// M_mask, eq. 7), at or above this value.
inline constexpr float kMaskThreshold = 0.5f;

// The loader's default probe size (env_h = 16, env_w = 2 env_h): the mosaic's block size
// when nothing else says it.
inline constexpr int kProbeHeight = 16;
inline constexpr int kProbeWidth = 32;

// Which of FutureHouse's normal components (with a sign) is each of ours. "x,y,z" is the
// identity: FutureHouse's +Y is up (its author, junxuan-li/LRG_360Panoramic issue 1) and the
// horizontal axes are assumed to be ours; "-z,y,x" would say our x is their -z, and so on.
struct NormalAxes {
  std::array<int, 3> source = {0, 1, 2};
  std::array<float, 3> sign = {1.0f, 1.0f, 1.0f};

  // "x,y,z", "-z,y,x", ...: each of x, y, z once. Throws phyir::Error naming the text.
  static NormalAxes parse(const std::string& text);
  std::string name() const;
  glm::vec3 to_ours(const glm::vec3& theirs) const;
  glm::vec3 to_theirs(const glm::vec3& ours) const;
};

}  // namespace phyir::dataset::futurehouse
