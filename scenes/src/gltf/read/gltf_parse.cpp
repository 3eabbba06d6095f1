#include "gltf/read/gltf_parse.h"

#include <fmt/ranges.h>

#include <sstream>
#include <string_view>

#include "gltf/compression/gltf_meshopt.h"
#include "gltf/read/gltf_tinygltf_input.h"

namespace phyir::scenes::gltf {

namespace {

// tinygltf's image callback: keep the bytes; gltf_textures.cpp decodes the images a
// material actually uses, through OpenImageIO.
bool keep_encoded_image(tinygltf::Image* image, const int /*index*/, std::string* /*err*/,
                        std::string* /*warn*/, int /*width*/, int /*height*/, const unsigned char* bytes,
                        int size, void* /*user*/) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// tinygltf's messages can quote whole data URIs; keep them readable.
std::string shorten(const std::string& message) {
  constexpr size_t kMaxLength = 400;
  return message.size() <= kMaxLength ? message : message.substr(0, kMaxLength) + "...";
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);)
    if (!line.empty()) lines.push_back(shorten(line));
  return lines;
}

}  // namespace

tinygltf::Model parse_gltf(const GltfFile& file, const Diagnostics& diagnostics) {
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&keep_encoded_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const std::string base_dir = file.path.parent_path().string();
  const TinygltfInput prepared = prepare_tinygltf_input(file, diagnostics);
  const std::string_view input = prepared.bytes ? std::string_view(*prepared.bytes)
                                 : file.binary  ? std::string_view(file.bytes)
                                                : file.json;
  bool ok = false;
  try {
    if (file.binary) {
      ok = parser.LoadBinaryFromMemory(&model, &error, &warning,
                                       reinterpret_cast<const unsigned char*>(input.data()),
                                       static_cast<unsigned int>(input.size()), base_dir);
    } else {
      ok = parser.LoadASCIIFromString(&model, &error, &warning, input.data(),
                                      static_cast<unsigned int>(input.size()), base_dir);
    }
  } catch (const std::exception& e) {
    error = e.what();
    ok = false;
  }
  if (!ok) diagnostics.fail("tinygltf: {}", fmt::join(lines_of(error), "; "));
  // tinygltf also reports problems it recovered from in `error`: keep them as warnings.
  for (const std::string& line : lines_of(error)) diagnostics.warn("tinygltf: {}", line);
  for (const std::string& line : lines_of(warning)) diagnostics.warn("tinygltf: {}", line);
  restore_hidden_indices(prepared, model);
  decode_meshopt_views(model, diagnostics);
  return model;
}

}  // namespace phyir::scenes::gltf
