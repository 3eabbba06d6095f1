#pragma once
// Scene textures made from glTF textures on demand. One Scene texture per (glTF texture,
// encoding): an image used both as colour and as data becomes two entries, one
// sRGB-decoded, one kept linear. Each image is decoded once, by OpenImageIO. A texture
// shows its EXT_texture_webp image when it has one; KHR_texture_basisu falls back to the
// core source.
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "gltf_context.h"
#include "phyir/core/image.h"
#include "phyir/scenes/texture.h"

namespace phyir::scenes::gltf {

class TextureTable {
 public:
  // With decode = false the entries keep their name and sampler state but no texels
  // (Texture::sample then returns white).
  TextureTable(const GltfContext& ctx, std::vector<Texture>& scene_textures, bool decode);

  // The Scene texture index for glTF texture `texture` used with `encoding`; `role`
  // names the use in messages ("material 0 'wood' baseColorTexture").
  int get(int texture, TextureEncoding encoding, const std::string& role);

 private:
  int image_index(int texture, const std::string& role);
  const Image& decoded_image(int image);
  Texture make_texture(int texture, TextureEncoding encoding, const std::string& role);

  const GltfContext& ctx_;
  std::vector<Texture>& textures_;
  bool decode_;
  std::map<std::pair<int, TextureEncoding>, int> entries_;
  std::map<int, Image> images_;
  std::set<int> warned_basisu_;  // textures whose KTX2 image was replaced, warned once each
};

}  // namespace phyir::scenes::gltf
