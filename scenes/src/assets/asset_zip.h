#pragma once
// Read access to one zip archive (a .sh3f furniture library) through libzip. Not shared
// between threads: each user opens its own (opening reads only the central directory).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

struct zip;

namespace phyir::scenes {

class ZipArchive {
 public:
  // Throws phyir::Error naming the file and libzip's reason (not a zip, truncated...).
  explicit ZipArchive(const std::filesystem::path& path);
  ~ZipArchive();
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Entry names exactly as stored (folders end with '/').
  std::vector<std::string> names() const;
  bool contains(const std::string& name) const;
  // The stored name equal to `name` ignoring ASCII case, if any (textures named by
  // Windows-authored MTL files often differ in case from the file in the archive).
  std::optional<std::string> find_ignoring_case(const std::string& name) const;
  // The whole entry, decompressed and checked (CRC). Throws phyir::Error naming the
  // archive and the entry when it is absent or unreadable.
  std::vector<unsigned char> read(const std::string& name) const;

 private:
  std::filesystem::path path_;
  zip* archive_ = nullptr;
};

}  // namespace phyir::scenes
