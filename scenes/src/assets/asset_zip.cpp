// ZipArchive: libzip behind the three calls the asset library needs.
#include "assets/asset_zip.h"

#include <zip.h>

#include <algorithm>
#include <cctype>
#include <memory>

#include "phyir/core/error.h"

namespace phyir::scenes {

namespace {

std::string libzip_error_text(int code) {
  zip_error_t error;
  zip_error_init_with_code(&error, code);
  std::string text = zip_error_strerror(&error);
  zip_error_fini(&error);
  return text;
}

bool equal_ignoring_ascii_case(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

ZipArchive::ZipArchive(const std::filesystem::path& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("{}: no such file", path.string());
  int code = 0;
  archive_ = zip_open(path.c_str(), ZIP_RDONLY, &code);
  if (!archive_) fail("{}: cannot open as a zip archive: {}", path.string(), libzip_error_text(code));
}

ZipArchive::~ZipArchive() {
  if (archive_) zip_discard(archive_);  // read-only: nothing to write back
}

std::vector<std::string> ZipArchive::names() const {
  const zip_int64_t count = zip_get_num_entries(archive_, 0);
  std::vector<std::string> result;
  result.reserve(static_cast<size_t>(std::max<zip_int64_t>(count, 0)));
  for (zip_int64_t i = 0; i < count; ++i) {
    if (const char* name = zip_get_name(archive_, static_cast<zip_uint64_t>(i), ZIP_FL_ENC_GUESS)) {
      result.emplace_back(name);
    }
  }
  return result;
}

bool ZipArchive::contains(const std::string& name) const {
  return zip_name_locate(archive_, name.c_str(), ZIP_FL_ENC_GUESS) >= 0;
}

std::optional<std::string> ZipArchive::find_ignoring_case(const std::string& name) const {
  if (contains(name)) return name;
  for (const std::string& stored : names()) {
    if (equal_ignoring_ascii_case(stored, name)) return stored;
  }
  return std::nullopt;
}

std::vector<unsigned char> ZipArchive::read(const std::string& name) const {
  const zip_int64_t index = zip_name_locate(archive_, name.c_str(), ZIP_FL_ENC_GUESS);
  if (index < 0) fail("{}: no file '{}' in the archive", path_.string(), name);
  zip_stat_t stat;
  zip_stat_init(&stat);
  if (zip_stat_index(archive_, static_cast<zip_uint64_t>(index), 0, &stat) != 0 || !(stat.valid & ZIP_STAT_SIZE)) {
    fail("{}: '{}': cannot read its size: {}", path_.string(), name, zip_strerror(archive_));
  }
  std::unique_ptr<zip_file_t, decltype(&zip_fclose)> file(
      zip_fopen_index(archive_, static_cast<zip_uint64_t>(index), 0), &zip_fclose);
  if (!file) fail("{}: '{}': cannot open: {}", path_.string(), name, zip_strerror(archive_));
  std::vector<unsigned char> bytes(static_cast<size_t>(stat.size));
  const zip_int64_t got = zip_fread(file.get(), bytes.data(), bytes.size());
  if (got < 0 || static_cast<zip_uint64_t>(got) != stat.size) {
    fail("{}: '{}': read {} of {} bytes: {}", path_.string(), name, got, stat.size,
         zip_file_strerror(file.get()));
  }
  // libzip checks the CRC once the end is reached: one more read reports a mismatch.
  unsigned char probe;
  if (zip_fread(file.get(), &probe, 1) < 0) {
    fail("{}: '{}': {}", path_.string(), name, zip_file_strerror(file.get()));
  }
  return bytes;
}

}  // namespace phyir::scenes
