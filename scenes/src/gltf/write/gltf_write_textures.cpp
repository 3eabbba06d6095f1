#include "gltf/write/gltf_write_textures.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "gltf/write/gltf_write_files.h"
#include "phyir/core/error.h"

namespace phyir::scenes::gltf_write {

namespace {

using nlohmann::json;

// glTF enums (specification section 5).
constexpr int kFilterLinear = 9729;
constexpr int kFilterLinearMipmapLinear = 9987;

int wrap_code(GltfWrap wrap) {
  switch (wrap) {
    case GltfWrap::ClampToEdge: return 33071;
    case GltfWrap::MirroredRepeat: return 33648;
    case GltfWrap::Repeat: break;
  }
  return 10497;
}

json sampler_json(const GltfSampler& s) {
  return {{"magFilter", kFilterLinear},
          {"minFilter", kFilterLinearMipmapLinear},
          {"wrapS", wrap_code(s.wrap_s)},
          {"wrapT", wrap_code(s.wrap_t)}};
}

// The images: one per uri, the first texture with a source supplying its bytes.
class ImageTable {
 public:
  explicit ImageTable(EncodedTextures& out) : out_(out) {}

  int add(const GltfTexture& t, size_t index) {
    const std::string what = fmt::format("texture {}", index);
    const auto found = by_uri_.find(t.uri);
    if (found != by_uri_.end()) {
      check_same_source(t, index, found->second);
      return found->second;
    }
    check_side_uri(t.uri, what);
    json image = {{"uri", t.uri}};
    if (!t.source.empty()) {
      check_source(t.source, what);
      image["mimeType"] = image_mime_type(t.source, t.uri, what);
      out_.side_files.push_back({t.uri, t.source});
    }
    out_.images.push_back(std::move(image));
    sources_.push_back({index, t.source});
    const int image_index = static_cast<int>(out_.images.size()) - 1;
    by_uri_[t.uri] = image_index;
    return image_index;
  }

 private:
  struct Source {
    size_t texture;
    GltfFileSource source;
  };

  // One uri holds one file: a second texture may leave the source out or repeat it.
  void check_same_source(const GltfTexture& t, size_t index, int image) const {
    const Source& first = sources_[static_cast<size_t>(image)];
    if (t.source.empty() || same_source(t.source, first.source)) return;
    if (first.source.empty())
      fail("glTF writer: texture {} gives uri '{}' a source, but texture {} (the first with that uri) has none",
           index, t.uri, first.texture);
    fail("glTF writer: textures {} and {} give uri '{}' different sources", first.texture, index, t.uri);
  }

  EncodedTextures& out_;
  std::map<std::string, int> by_uri_;
  std::vector<Source> sources_;  // per image
};

}  // namespace

EncodedTextures encode_textures(const std::vector<GltfTexture>& textures) {
  EncodedTextures out;
  ImageTable images(out);
  std::vector<GltfSampler> samplers;
  for (size_t i = 0; i < textures.size(); ++i) {
    const GltfTexture& t = textures[i];
    auto sampler = std::find(samplers.begin(), samplers.end(), t.sampler);
    if (sampler == samplers.end()) {
      samplers.push_back(t.sampler);
      out.samplers.push_back(sampler_json(t.sampler));
      sampler = samplers.end() - 1;
    }
    out.textures.push_back({{"sampler", sampler - samplers.begin()}, {"source", images.add(t, i)}});
  }
  return out;
}

}  // namespace phyir::scenes::gltf_write
