#include "phyir/render/film.h"

#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/view/view_files.h"

namespace phyir::render {

namespace {
enum AovIndex { kDepth, kNormal, kBasecolor, kRoughness, kMetalness, kEmissive, kTransparent, kGeometry };
constexpr int kAovChannels[] = {1, 3, 3, 1, 1, 1, 1, 1};
}  // namespace

const std::vector<std::string>& Film::aov_names() {
  static const std::vector<std::string> names = {"depth",         "normal",          "basecolor",
                                                 "roughness",     "metalness",       "mask_emissive",
                                                 "mask_transparent", "mask_geometry"};
  return names;
}

Film::Film(int width, int height, bool with_aovs)
    : width_(width), height_(height), with_aovs_(with_aovs), color_(width, height, 3) {
  if (width <= 0 || height <= 0) fail("image size {}x{} is not positive", width, height);
  if (with_aovs) {
    for (int channels : kAovChannels) aovs_.emplace_back(width, height, channels);
  }
}

void Film::set_color(int x, int y, const glm::vec3& radiance) {
  for (int c = 0; c < 3; ++c) color_.at(x, y, c) = radiance[c];
}

void Film::set_gbuffer(int x, int y, const GBufferSample& g) {
  aovs_[kDepth].at(x, y) = g.depth;
  for (int c = 0; c < 3; ++c) {
    aovs_[kNormal].at(x, y, c) = g.normal[c];
    aovs_[kBasecolor].at(x, y, c) = g.basecolor[c];
  }
  aovs_[kRoughness].at(x, y) = g.roughness;
  aovs_[kMetalness].at(x, y) = g.metalness;
  aovs_[kEmissive].at(x, y) = g.emissive;
  aovs_[kTransparent].at(x, y) = g.transparent;
  aovs_[kGeometry].at(x, y) = g.geometry;
}

const Image& Film::aov(const std::string& name) const {
  const auto& names = aov_names();
  for (size_t i = 0; i < names.size() && i < aovs_.size(); ++i)
    if (names[i] == name) return aovs_[i];
  fail("no AOV named '{}' in this render", name);
}

std::vector<std::string> Film::write_exr(const std::filesystem::path& dir) const {
  std::vector<std::string> written;
  write_image(dir / view::kColorFile, color_);
  written.push_back(view::kColorFile);
  if (!with_aovs_) return written;
  const auto& names = aov_names();
  for (size_t i = 0; i < aovs_.size(); ++i) {
    const std::string file = names[i] + ".exr";
    std::vector<std::string> channels;
    if (i == kNormal) channels = {"X", "Y", "Z"};
    write_image(dir / file, aovs_[i], channels);
    written.push_back(file);
  }
  return written;
}

}  // namespace phyir::render
