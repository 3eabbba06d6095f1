#pragma once
// The images of one render: the HDR colour estimate and the G-buffer AOVs, and the one
// place that writes them to disk (EXR through OpenImageIO, atomic).
#include <filesystem>
#include <string>
#include <vector>

#include "phyir/core/image.h"
#include "phyir/render/gbuffer.h"

namespace phyir::render {

class Film {
 public:
  Film(int width, int height, bool with_aovs);

  int width() const { return width_; }
  int height() const { return height_; }
  bool has_aovs() const { return with_aovs_; }

  void set_color(int x, int y, const glm::vec3& radiance);
  void set_gbuffer(int x, int y, const GBufferSample& g);

  const Image& color() const { return color_; }
  const Image& aov(const std::string& name) const;

  // Writes color.exr and, with AOVs, depth.exr, normal.exr, basecolor.exr, roughness.exr,
  // metalness.exr, mask_emissive.exr, mask_transparent.exr, mask_geometry.exr.
  // Returns the file names written.
  std::vector<std::string> write_exr(const std::filesystem::path& dir) const;

  static const std::vector<std::string>& aov_names();

 private:
  int width_, height_;
  bool with_aovs_;
  Image color_;
  std::vector<Image> aovs_;  // in aov_names() order
};

}  // namespace phyir::render
