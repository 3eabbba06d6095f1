#include "phyir/core/png_structure.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>

namespace phyir {

std::string png_structure_error(const unsigned char* bytes, size_t size) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size < sizeof kSignature || std::memcmp(bytes, kSignature, sizeof kSignature) != 0)
    return "no PNG signature (not a PNG or JPEG image)";
  // Each chunk: 4-byte big-endian length, 4-byte type, data, 4-byte CRC. The PNG
  // specification caps a length at 2^31 - 1.
  size_t offset = sizeof kSignature;
  for (int index = 0;; ++index) {
    if (size - offset < 12) return fmt::format("truncated before the end of chunk {} ({} bytes in all)", index, size);
    const uint32_t length = uint32_t(bytes[offset]) << 24 | uint32_t(bytes[offset + 1]) << 16 |
                            uint32_t(bytes[offset + 2]) << 8 | uint32_t(bytes[offset + 3]);
    const std::string type(reinterpret_cast<const char*>(bytes + offset + 4), 4);
    if (length > 0x7FFFFFFFu) return fmt::format("chunk {} declares {} bytes, more than PNG allows", index, length);
    if (size - offset - 12 < length)
      return fmt::format("truncated in chunk {} ({}: {} bytes declared, {} left)", index, type, length, size - offset - 12);
    offset += 12 + size_t(length);
    if (type == "IEND") return "";
  }
}

}  // namespace phyir
