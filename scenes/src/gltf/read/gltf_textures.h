#pragma once
// Scene textures made from glTF textures on demand. One Scene texture per (glTF texture,
// encoding): an image used both as colour and as data becomes two entries, one
// sRGB-decoded, one kept linear. Each image is decoded once, by OpenImageIO, all of them in
// parallel once the materials have asked for theirs. A texture shows its EXT_texture_webp
// image when it has one; KHR_texture_basisu falls back to the core source.
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "gltf/read/gltf_context.h"
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

  // Decodes the images of every texture get() returned (nothing with decode = false), in
  // parallel with TBB, each image once. Results do not depend on the thread count; when images
  // fail to decode, the error is that of the first failing texture in Scene order.
  void decode_all();

 private:
  int image_index(int texture, const std::string& role);
  Texture make_texture(int texture, int image, TextureEncoding encoding);
  void decode_image(int image, const std::vector<size_t>& textures);

  const GltfContext& ctx_;
  std::vector<Texture>& textures_;
  bool decode_;
  std::map<std::pair<int, TextureEncoding>, int> entries_;
  std::vector<std::pair<size_t, int>> image_of_;  // (Scene texture, glTF image) in get() order
  std::set<int> warned_basisu_;  // textures whose KTX2 image was replaced, warned once each
};

}  // namespace phyir::scenes::gltf
