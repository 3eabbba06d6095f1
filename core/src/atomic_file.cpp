#include "phyir/core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "phyir/core/error.h"

namespace phyir {

namespace fs = std::filesystem;

fs::path temporary_sibling(const fs::path& final_path) {
  const std::string name = "." + final_path.filename().string() + ".partial-" +
                           std::to_string(::getpid()) + final_path.extension().string();
  return final_path.parent_path() / name;
}

void commit_file(const fs::path& temporary, const fs::path& final_path) {
  const int fd = ::open(temporary.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  std::error_code ec;
  fs::rename(temporary, final_path, ec);
  if (ec) {
    fs::remove(temporary, ec);
    fail("{}: cannot move the finished file into place: {}", final_path.string(), ec.message());
  }
}

void write_file_atomic(const fs::path& path, const std::string& contents) {
  if (!path.parent_path().empty()) fs::create_directories(path.parent_path());
  const fs::path tmp = temporary_sibling(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail("{}: cannot open for writing: {}", tmp.string(), std::strerror(errno));
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    if (!out) fail("{}: write failed: {}", tmp.string(), std::strerror(errno));
  }
  commit_file(tmp, path);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open: {}", path.string(), std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void ensure_writable_directory(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) fail("{}: cannot create the output folder: {}", dir.string(), ec.message());
  if (!fs::is_directory(dir, ec)) fail("{}: the output path exists and is not a folder", dir.string());
  const fs::path probe = dir / (".phyir-write-test-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) fail("{}: cannot write in the output folder: {}", dir.string(), std::strerror(errno));
  ::close(fd);
  fs::remove(probe, ec);
}

}  // namespace phyir
