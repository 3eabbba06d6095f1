#include "gltf/write/gltf_write_files.h"

#include <algorithm>
#include <cctype>
#include <fstream>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"

namespace phyir::scenes::gltf_write {

namespace fs = std::filesystem;

namespace {

bool is_uri_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '_' || c == '-';
}

// Up to `count` leading bytes of the source.
std::string first_bytes(const GltfFileSource& source, size_t count) {
  if (!source.bytes.empty()) return source.bytes.substr(0, count);
  std::ifstream in(source.file, std::ios::binary);
  std::string bytes(count, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(count));
  bytes.resize(static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return bytes;
}

std::string lower_extension(const std::string& uri) {
  std::string ext = fs::path(uri).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace

void check_side_uri(const std::string& uri, const std::string& what) {
  const auto bad = [&](const char* why) { fail("glTF writer: {} uri '{}' {}", what, uri, why); };
  if (uri.empty()) bad("is empty");
  size_t start = 0;
  while (start <= uri.size()) {
    const size_t end = std::min(uri.find('/', start), uri.size());
    const std::string part = uri.substr(start, end - start);
    if (part.empty()) bad("has an empty path component (a leading, trailing or doubled '/')");
    if (part == "." || part == "..") bad("has a '.' or '..' component: files stay in the .gltf's folder");
    if (!std::all_of(part.begin(), part.end(), is_uri_char))
      bad("has a character other than letters, digits, '.', '_', '-' and '/' (it would need percent-encoding)");
    start = end + 1;
  }
}

std::string image_mime_type(const GltfFileSource& source, const std::string& uri, const std::string& what) {
  static const std::string kPng("\x89PNG\r\n\x1a\n", 8), kJpeg("\xFF\xD8\xFF", 3);
  const std::string head = first_bytes(source, kPng.size());
  const std::string ext = lower_extension(uri);
  if (head.rfind(kPng, 0) == 0) {
    if (ext != ".png") fail("glTF writer: {} '{}' holds a PNG image: its uri must end in .png", what, uri);
    return "image/png";
  }
  if (head.rfind(kJpeg, 0) == 0) {
    if (ext != ".jpg" && ext != ".jpeg")
      fail("glTF writer: {} '{}' holds a JPEG image: its uri must end in .jpg or .jpeg", what, uri);
    return "image/jpeg";
  }
  fail("glTF writer: {} '{}' ({}) is neither PNG nor JPEG", what, uri,
       source.bytes.empty() ? source.file.string() : std::to_string(source.bytes.size()) + " bytes in memory");
}

void check_source(const GltfFileSource& source, const std::string& what) {
  if (!source.bytes.empty() || source.file.empty()) return;
  std::error_code ec;
  if (!fs::is_regular_file(source.file, ec)) fail("glTF writer: {}: source file {} not found", what, source.file.string());
}

bool same_source(const GltfFileSource& a, const GltfFileSource& b) { return a.file == b.file && a.bytes == b.bytes; }

void write_side_file(const fs::path& dir, const GltfSideFile& file) {
  const fs::path target = dir / file.uri;
  fs::create_directories(target.parent_path());
  if (file.source.bytes.empty()) {
    std::error_code ec;
    if (fs::equivalent(file.source.file, target, ec)) return;  // the caller wrote it in place
    write_file_atomic(target, read_file(file.source.file));
  } else {
    write_file_atomic(target, file.source.bytes);
  }
}

}  // namespace phyir::scenes::gltf_write
