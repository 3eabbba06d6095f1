#pragma once
// Image files through OpenImageIO. Writers are atomic (temporary name, then rename).
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "phyir/core/image.h"

namespace phyir {

// Reads any format OIIO knows as float. Values are returned as stored (no colour
// conversion): 8-bit PNG/JPEG arrive in [0,1], still sRGB-encoded. Throws phyir::Error
// naming the file on failure.
Image read_image(const std::filesystem::path& path);

// Decodes an image held in memory (e.g. a glTF data: URI or a .glb buffer view).
// `what` names the source in error messages.
Image read_image_from_memory(const std::vector<unsigned char>& bytes, const std::string& what);

// The same decode, at the depth the file stores: an 8-bit image (JPEG, WebP, most PNGs) as its
// code values, anything deeper (16-bit PNG) as float like read_image_from_memory. The bytes
// are what read_image_from_memory scales by 1/255.
std::variant<ByteImage, Image> read_image_from_memory_at_file_depth(const std::vector<unsigned char>& bytes,
                                                                    const std::string& what);

// Writes float data. The extension picks the format: .exr is written as 32-bit float
// (lossless ZIP compression); .png/.jpg are quantised to 8 bits (values clamped to [0,1]).
// Channel names default to R,G,B,A or Y for one channel.
void write_image(const std::filesystem::path& path, const Image& image,
                 const std::vector<std::string>& channel_names = {});

// Writes display-encoded RGB frames in [0, 1] of one size as an animation (the extension's
// format must hold several images: .gif loops forever at `fps`). Atomic like write_image.
void write_animation(const std::filesystem::path& path, const std::vector<Image>& frames, float fps);

}  // namespace phyir
