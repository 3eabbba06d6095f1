#pragma once
// The image files MTL materials name, found in the archive and read once per model.
#include <map>
#include <string>
#include <vector>

#include "phyir/scenes/asset_model.h"

namespace phyir::scenes {

class ZipArchive;

class TextureFiles {
 public:
  TextureFiles(const ZipArchive& zip, std::string mtl_folder, std::vector<AssetTexture>& textures)
      : zip_(zip), folder_(std::move(mtl_folder)), textures_(textures) {}

  // Index into the texture list of the file `name` (tinyobjloader's), the last word of `raw`
  // (the whole MTL argument, Sweet Home 3D's first guess) or `raw` itself names, or -1 when
  // none is in the archive. Tried in that order, each exactly and then ignoring case: relative
  // to the MTL's folder, then as their last path component in that folder (MTL files often
  // keep the author's absolute paths).
  int find(const std::string& name, const std::string& raw);

 private:
  const ZipArchive& zip_;
  std::string folder_;
  std::vector<AssetTexture>& textures_;
  std::map<std::string, int> index_of_;  // archive path -> index
};

// A PNG whose pixels carry alpha: colour type 4 or 6, or a tRNS chunk. False for JPEG.
bool png_has_alpha(const std::vector<unsigned char>& bytes);

}  // namespace phyir::scenes
