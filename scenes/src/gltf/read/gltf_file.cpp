#include "gltf/read/gltf_file.h"

#include <cstdint>
#include <cstring>

#include "phyir/core/atomic_file.h"

namespace phyir::scenes::gltf {

namespace {

// GLB layout (glTF 2.0 section 4.4): 12-byte header, then chunks of
// {uint32 length, uint32 type, data padded to 4 bytes}; the first chunk is JSON.
constexpr uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr size_t kHeaderSize = 12;
constexpr size_t kChunkHeaderSize = 8;

uint32_t read_u32(const std::string& bytes, size_t offset) {
  uint32_t value;  // GLB is little-endian, as are the machines we run on
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

void locate_glb_chunks(GltfFile& file, const Diagnostics& diagnostics) {
  const std::string& b = file.bytes;
  if (b.size() < kHeaderSize + kChunkHeaderSize)
    diagnostics.fail("GLB file is {} bytes, shorter than its 20-byte header", b.size());
  const uint32_t version = read_u32(b, 4);
  const uint32_t length = read_u32(b, 8);
  if (version != 2) diagnostics.fail("GLB version {} is not supported (only 2)", version);
  if (length != b.size())
    diagnostics.fail("GLB header declares {} bytes but the file has {} (truncated?)", length, b.size());
  const uint32_t json_length = read_u32(b, 12);
  if (read_u32(b, 16) != kChunkJson) diagnostics.fail("GLB first chunk is not JSON");
  const size_t json_start = kHeaderSize + kChunkHeaderSize;
  if (json_length > b.size() - json_start)
    diagnostics.fail("GLB JSON chunk of {} bytes runs past the end of the file ({} bytes)", json_length,
                     b.size());
  file.json = std::string_view(b).substr(json_start, json_length);
  const size_t bin_header = json_start + json_length;
  if (b.size() - bin_header >= kChunkHeaderSize && read_u32(b, bin_header + 4) == kChunkBin) {
    const uint32_t bin_length = read_u32(b, bin_header);
    if (bin_length > b.size() - bin_header - kChunkHeaderSize)
      diagnostics.fail("GLB BIN chunk of {} bytes runs past the end of the file ({} bytes)", bin_length,
                       b.size());
    file.bin_chunk_size = bin_length;
  }
}

}  // namespace

GltfFile read_gltf_file(const std::filesystem::path& path, const Diagnostics& diagnostics) {
  GltfFile file;
  file.path = path;
  if (!std::filesystem::exists(path)) diagnostics.fail("file not found");
  file.bytes = read_file(path);
  // tinygltf takes 32-bit lengths.
  if (file.bytes.size() > UINT32_MAX) diagnostics.fail("file is larger than 4 GiB");
  file.binary = file.bytes.size() >= 4 && read_u32(file.bytes, 0) == kGlbMagic;
  if (file.binary) {
    locate_glb_chunks(file, diagnostics);
  } else {
    file.json = file.bytes;
  }
  return file;
}

}  // namespace phyir::scenes::gltf
