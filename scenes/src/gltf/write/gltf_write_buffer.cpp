#include "gltf/write/gltf_write_buffer.h"

#include <cstring>

namespace phyir::scenes::gltf_write {

int BufferEncoder::add_indices(const std::vector<uint32_t>& indices) {
  const size_t offset = bin_.size();
  for (uint32_t i : indices) put_u32(i);
  return add_accessor({{"bufferView", add_view(offset, kElementArrayBuffer)},
                       {"componentType", kComponentUnsignedInt},
                       {"count", indices.size()},
                       {"type", "SCALAR"}});
}

// Little-endian whatever the host: the file must not depend on the machine.
void BufferEncoder::put_u32(uint32_t w) {
  for (int b = 0; b < 4; ++b) bin_.push_back(static_cast<char>((w >> (8 * b)) & 0xFFu));
}

void BufferEncoder::put_float(float f) {
  uint32_t w;
  std::memcpy(&w, &f, sizeof w);
  put_u32(w);
}

int BufferEncoder::add_view(size_t offset, int target) {
  views_.push_back(
      {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin_.size() - offset}, {"target", target}});
  return static_cast<int>(views_.size()) - 1;
}

int BufferEncoder::add_accessor(nlohmann::json accessor) {
  accessors_.push_back(std::move(accessor));
  return static_cast<int>(accessors_.size()) - 1;
}

}  // namespace phyir::scenes::gltf_write
